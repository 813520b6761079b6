"""Output paths of every command (issue 42 items 5 and 7): checked before any work, refused with one line
naming the option and the path the user gave (never the atomic writer's temporary file); outputs written
all or nothing, with the user's umask; a run folder's stale files removed or reported."""

from __future__ import annotations

import json
import os
import shutil
import stat
from pathlib import Path

import pytest

from netshape.cli import main

REPO = Path(__file__).resolve().parents[2]
DEMO = REPO / "examples" / "demo"

PLAN = ["plan", str(DEMO / "part.ngc"), "--vmax", "250", "--amax", "3000", "--rule", "vector"]
FORCES = ["forces", "--diameter", "10", "--flutes", "2", "--rpm", "6000", "--feed-per-tooth", "0.1",
          "--ap", "3", "--coefficient-set", "leekunhwee_flat_slot"]
PATH_COMMON = ["--tool", str(DEMO / "tool.toml"), "--stock", "s.toml", "--coefficients", "cho_suh_example",
               "--rpm", "600"]


def quick_job(folder: Path, extra: str = "") -> Path:
    """The demo job made quick: coarse stock, no forces or deflection, no plots or STL."""
    d = folder / "job"
    shutil.copytree(DEMO, d)
    text = (d / "job.toml").read_text()
    text = text.replace("spacing_mm = 0.25", "spacing_mm = 1.0").replace("deflection = true", "deflection = false")
    text = text.replace("forces = true", "forces = false")
    text = text.replace("[cutting]", "[report]\nplots = false\nzmap_stl = false\n\n[cutting]")
    (d / "job.toml").write_text(text + extra)
    return d / "job.toml"


def _refused(capsys, argv, *needles) -> str:
    assert main(argv) == 2
    cap = capsys.readouterr()
    lines = [ln for ln in cap.err.splitlines() if ": warning: " not in ln]  # the reader's G54 note may precede
    assert len(lines) == 1, cap.err
    assert "Traceback" not in cap.err and ".tmp" not in lines[0], lines[0]
    for n in needles:
        assert n in lines[0], (n, lines[0])
    return lines[0]


def _cases(tmp: Path):
    """(argv, option, path) per command and kind of bad output path."""
    afile = tmp / "afile.txt"
    afile.write_text("x")
    adir = tmp / "adir"
    adir.mkdir()
    job = str(tmp / "missing-job.toml")
    # a device stands in for /dev/null: a FIFO of this test's own, so that a regression writing over it
    # (as root may) replaces nothing of the system's
    fifo = tmp / "device"
    os.mkfifo(fifo)
    out = []
    for bad, why in ((str(afile), "is a file, not a folder"), (str(afile / "sub"), "lies under"),
                     (str(fifo), "not a folder")):
        out += [(["run", job, "--out", bad, "--quiet"], "--out", bad, why),
                (["batch", job, "--out", bad, "--scheduler", "none", "--quiet"], "--out", bad, why),
                (["diagnose", str(tmp), "--json", str(tmp / "d.json"), "--report", bad], "--report", bad, why),
                (["deflection", "predict", "p.nc", *PATH_COMMON, "--plot", bad], "--plot", bad, why),
                (["posture", "plan", "--impeller", "--out", bad], "--out", bad, why)]
    for bad, why in ((str(adir), "is a folder, not a file"), (str(afile / "o.json"), "lies under"),
                     (str(fifo), "not a regular file")):
        out += [(PLAN + ["--json", bad], "--json", bad, why),
                (["diagnose", str(tmp), "--json", bad], "--json", bad, why),
                (["deflection", "compensate", "p.nc", *PATH_COMMON, "-o", bad], "--output", bad, why),
                (["volumetric", "map", str(DEMO / "machine.toml"), "--json", bad], "--json", bad, why),
                (FORCES + ["--csv", bad], "--csv", bad, why)]
    return out


def test_bad_output_paths_refused_before_any_work(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    for argv, option, bad, why in _cases(tmp_path):
        before = sorted(p.name for p in tmp_path.iterdir())
        line = _refused(capsys, argv, f"{option} = {bad!r}", why)
        # refused before reading any input (the job and bundle given here do not exist)
        assert "no such file" not in line
        assert sorted(p.name for p in tmp_path.iterdir()) == before, argv


def test_dev_null_refused_without_writing():
    """/dev/null itself, checked only (a writer that renamed over it would replace the device)."""
    from netshape._atomic import check_output_file, check_output_folder

    with pytest.raises(ValueError, match=r"--json = '/dev/null': is not a regular file"):
        check_output_file("/dev/null", "--json")
    with pytest.raises(ValueError, match=r"--out = '/dev/null': is a file, not a folder"):
        check_output_folder("/dev/null", "--out")


def test_unwritable_folder_refused_naming_the_option(tmp_path, monkeypatch, capsys):
    import tempfile

    from netshape import _atomic

    locked = tmp_path / "locked"
    locked.mkdir()
    real = tempfile.mkstemp

    def mkstemp(*a, dir=None, **k):  # root may write anywhere: a folder that refuses, as a user sees it
        if dir is not None and Path(dir) == locked:
            raise PermissionError(13, "Permission denied", str(dir))
        return real(*a, dir=dir, **k)

    monkeypatch.setattr(_atomic.tempfile, "mkstemp", mkstemp)
    _refused(capsys, ["posture", "plan", "--impeller", "--out", str(locked)], f"--out = {str(locked)!r}",
             "not writable (Permission denied)")
    _refused(capsys, PLAN + ["--json", str(locked / "o.json")], f"--json = {str(locked / 'o.json')!r}",
             "not writable")
    assert list(locked.iterdir()) == []


def test_same_path_for_two_outputs_refused(tmp_path, capsys):
    p = str(tmp_path / "o.json")
    _refused(capsys, PLAN + ["--json", p, "--samples", p], "--samples", "the same path as --json")


def test_no_output_when_a_later_one_fails(tmp_path, monkeypatch, capsys):
    """A failure while writing the last output leaves none of the command's outputs."""
    from netshape import _atomic

    def broken(fig, path, **kw):
        raise ValueError(f"output {str(path)!r}: cannot be written (No space left on device)")

    monkeypatch.setattr(_atomic, "atomic_save_figure", broken)
    argv = PLAN + ["--json", str(tmp_path / "p.json"), "--samples", str(tmp_path / "s.csv"),
                   "--plot", str(tmp_path / "p.png")]
    _refused(capsys, argv, "p.png", "No space left")
    assert list(tmp_path.iterdir()) == []


def test_all_or_nothing_keeps_earlier_files(tmp_path):
    from netshape._atomic import all_or_nothing, atomic_write

    (tmp_path / "a.txt").write_text("old")
    with pytest.raises(RuntimeError), all_or_nothing():
        with atomic_write(tmp_path / "a.txt") as fh:
            fh.write("new")
        with atomic_write(tmp_path / "b.txt") as fh:
            fh.write("new")
        raise RuntimeError("later failure")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]
    assert (tmp_path / "a.txt").read_text() == "old"


def test_writer_errors_name_the_output_not_the_temporary(tmp_path, monkeypatch):
    from netshape import _atomic

    def full(src, dst):
        raise OSError(28, "No space left on device", src)

    monkeypatch.setattr(_atomic.os, "replace", full)
    target = tmp_path / "out.json"
    with pytest.raises(ValueError) as ei:
        with _atomic.atomic_write(target) as fh:
            fh.write("{}")
    assert str(target) in str(ei.value) and ".tmp" not in str(ei.value)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("mask", [0o022, 0o077, 0o002])
def test_outputs_follow_the_umask(tmp_path, mask):
    old = os.umask(mask)
    try:
        assert main(PLAN + ["--json", str(tmp_path / "p.json"), "--samples", str(tmp_path / "s.csv")]) == 0
    finally:
        os.umask(old)
    for name in ("p.json", "s.csv"):
        assert stat.S_IMODE((tmp_path / name).stat().st_mode) == 0o666 & ~mask, name


def test_run_zmap_stl_follows_the_umask_and_stale_files_are_handled(tmp_path, monkeypatch, capsys):
    job = quick_job(tmp_path)
    out = tmp_path / "out"
    old = os.umask(0o022)
    try:
        text = job.read_text().replace("plots = false", "plots = true").replace("zmap_stl = false", "zmap_stl = true")
        job.write_text(text)
        assert main(["run", str(job), "--out", str(out), "--quiet"]) == 0
        for name in ("zmap.stl", "summary.json", "report.html", "force.png"):
            assert stat.S_IMODE((out / name).stat().st_mode) == 0o644, name
        # a second run without plots or STL into the same folder, beside a file of the user's
        (out / "notes.txt").write_text("mine")
        job.write_text(text.replace("plots = true", "plots = false").replace("zmap_stl = true", "zmap_stl = false"))
        capsys.readouterr()
        assert main(["run", str(job), "--out", str(out), "--quiet"]) == 0
    finally:
        os.umask(old)
    err = capsys.readouterr().err
    names = sorted(p.name for p in out.iterdir())
    assert "force.png" not in names and "zmap.stl" not in names  # the earlier run's own files: removed
    assert "notes.txt" in names and "notes.txt" in err and "warning" in err  # the user's: reported
    summary = json.loads((out / "summary.json").read_text())
    assert summary["stale_files"] == ["notes.txt"]
    assert set(summary["files"].values()) | {"notes.txt"} == set(names)


def test_run_warns_about_a_grid(tmp_path, capsys):
    job = quick_job(tmp_path, '\n[grid]\n"cutting.feed_scale" = [0.5, 1.0]\n')
    assert main(["run", str(job), "--out", str(tmp_path / "o"), "--quiet"]) == 0
    err = capsys.readouterr().err
    assert "warning" in err and "[grid]" in err and "cutting.feed_scale" in err and "netshape batch" in err
