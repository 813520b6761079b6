"""One stock format (netshape.stock.config): a STOCK.toml read by `--stock` and a job's [stock] table
give the same Z-map, with heights files and pre-cuts, and a bad key is refused naming file and key."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from netshape.job.spec import JobError, load_job
from netshape.job.stages import stage_stock
from netshape.stock.config import load_stock

NOTHING = "[predict]\nforces = false\ndeflection = false\nvolumetric = false\nfeed_plan = false\n"
TOOL = 'kind = "flat"\ndiameter_mm = 6.0\nflutes = 3\nhelix_deg = 30.0\nflute_length_mm = 20.0\nstick_out_mm = 30.0\n'


def _files(tmp_path):
    h = np.full((21, 41), 10.0)
    h[:, 20:] = 8.0  # a 2 mm step: the casting the heights file describes
    np.save(tmp_path / "casting.npy", h)
    (tmp_path / "tool.toml").write_text(TOOL)
    (tmp_path / "rough.ngc").write_text("G0 X-5 Y5 Z9\nG1 X45 F600\nM30\n")
    (tmp_path / "stock.toml").write_text(
        'min_mm = [0.0, 0.0, 0.0]\nmax_mm = [40.0, 20.0, 12.0]\nheights = "casting.npy"\n'
        '[[pre_cut]]\nprogram = "rough.ngc"\ntool = "tool.toml"\n')
    (tmp_path / "part.ngc").write_text("G0 X0 Y0 Z20\nM30\n")
    return tmp_path / "stock.toml"


def test_stock_file_and_job_table_give_the_same_zmap(tmp_path):
    f = _files(tmp_path)
    z = load_stock(f)
    h = np.asarray(z.heights)
    # the casting's step, and the pre-cut's 6 mm slot at y = 5 lowering both sides to z 9
    assert h.shape == (21, 41)
    assert h[10, 5] == pytest.approx(10.0) and h[10, 30] == pytest.approx(8.0)
    assert h[5, 5] == pytest.approx(9.0) and h[5, 30] == pytest.approx(8.0)
    job = tmp_path / "job.toml"
    job.write_text('program = "part.ngc"\ntool = "tool.toml"\nstock = "stock.toml"\n' + NOTHING)
    zj = stage_stock(load_job(job))
    np.testing.assert_array_equal(np.asarray(zj.heights), h)


@pytest.mark.parametrize("text, key", [
    ("min_mm = [0.0, 0.0, 0.0]\nmax_mm = [40.0, 20.0, 12.0]\nspacing_mm = -1.0\n", "spacing_mm = -1.0"),
    ("min_mm = [0.0, 0.0, 0.0]\nmax_mm = [40.0, 20.0, 12.0]\nspacing = 1.0\n", "spacing = 1.0: unknown key"),
    ("min_mm = [0.0, 0.0, 0.0]\nmax_mm = [40.0, 0.0, 12.0]\nspacing_mm = 1.0\n", "max_mm[1] = 0.0"),
    ("min_mm = [0.0, 0.0, 0.0]\nmax_mm = [40.0, 20.0, 12.0]\nheights = \"h.txt\"\n", "heights = 'h.txt'"),
])
def test_bad_stock_file_names_file_and_key(tmp_path, text, key):
    (tmp_path / "h.txt").write_text("1,2\n3,4\n")
    f = tmp_path / "stock.toml"
    f.write_text(text)
    with pytest.raises(ValueError) as e:
        load_stock(f)
    assert str(e.value).startswith(str(f)) and key in str(e.value), str(e.value)
    # the same file under a job is a JobError naming the file and the job's key
    (tmp_path / "part.ngc").write_text("G0 X0 Y0 Z20\nM30\n")
    (tmp_path / "tool.toml").write_text(TOOL)
    (tmp_path / "job.toml").write_text('program = "part.ngc"\ntool = "tool.toml"\nstock = "stock.toml"\n')
    with pytest.raises(JobError, match=str(f).replace("\\", "\\\\")):
        load_job(tmp_path / "job.toml")


def test_deflection_cli_reads_a_heights_stock(tmp_path):
    """`netshape deflection predict --stock` takes the job's format, heights included (it refused
    `heights` as an unknown key when it had a format of its own)."""
    f = _files(tmp_path)
    (tmp_path / "wall.ngc").write_text("G0 X-5 Y17 Z20\nG0 Z6\nG1 X45 F300\nG0 Z20\nM30\n")
    r = subprocess.run([sys.executable, "-m", "netshape", "deflection", "predict", str(tmp_path / "wall.ngc"),
                        "--tool", str(tmp_path / "tool.toml"), "--stock", str(f), "--rpm", "6000",
                        "--coefficients", "leekunhwee_flat_slot"],
                       capture_output=True, text=True, timeout=120)
    assert "unknown key" not in r.stderr, r.stderr
    assert r.returncode == 0, r.stderr
