"""examples/consumer: a C++ program built against the INSTALLED netshape library (find_package), as a CAM
plugin would embed it. Skips in a development (in-place) build, where no installed library exists."""

from __future__ import annotations

import shutil
import subprocess

import pytest

import netshape as ns

PROGRAM = "G21 G90 G17 F600\nG0 X0 Y0 Z5\nG1 Z-1\nG1 X20\nG3 X25 Y5 R5\nG1 Y20\nG2 X30 Y25 I5 J0\nM2\n"


@pytest.mark.slow
def test_consumer_builds_against_installed_library(repo_root, tmp_path):
    try:
        cmake_dir = ns.cmake_dir()
    except FileNotFoundError as exc:
        pytest.skip(f"no installed C++ library: {exc}")
    cmake = shutil.which("cmake")
    if cmake is None:
        pytest.skip("cmake is not on PATH")
    gen = ["-G", "Ninja"] if shutil.which("ninja") else []
    build = tmp_path / "build"
    subprocess.run([cmake, "-S", str(repo_root / "examples" / "consumer"), "-B", str(build), *gen,
                    f"-Dnetshape_DIR={cmake_dir}", "-DCMAKE_BUILD_TYPE=Release"],
                   check=True, capture_output=True, text=True)
    subprocess.run([cmake, "--build", str(build)], check=True, capture_output=True, text=True)
    out = subprocess.run([str(build / "consumer")], check=True, capture_output=True, text=True).stdout
    fields = dict(line.split(" ", 1) for line in out.strip().splitlines())
    s = ns.toolpath.summary_of_text(PROGRAM)
    assert fields["blocks"].startswith(f"{s.blocks} (rapid {s.rapids}, line {s.lines}, arc {s.arcs})")
    assert float(fields["feed_length_mm"]) == pytest.approx(s.feed_length, rel=1e-6)
    assert float(fields["feed_time_s"]) == pytest.approx(s.feed_time, rel=1e-6)
    # the plugin's compensation: its report says the compensated program follows the nominal one
    proc = subprocess.run([str(build / "consumer_compensate")], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.startswith("(compensated for plugin demo)") and "arcs split" in proc.stderr
