"""`netshape plan --rule smooth --smoothed-gcode`: the program's own text with the smoothed moves in
place (netshape.motion.gcode_splice, issue 39 item 5). Round trip: every line without a move is in
the output in order and as written (M30, coolant, work offset, comments), lines whose moves did not
change are kept as written, the output makes the program's rapids and no other, and read back (with
the same work offsets) it stays within ε + the chord tolerance of the program both ways."""

from __future__ import annotations

import numpy as np
import pytest

import netshape.motion as nm
from netshape import toolpath
from netshape.cli import main
from netshape.motion.gcode_splice import _words


def _program() -> str:
    lines = ["(splice test part)", "G21 G90 G17", "G54", "T1 M6", "S8000 M3", "M8", "G0 X20 Y0 Z5",
             "N10 G1 Z0 F600"]
    for k, a in enumerate(np.radians(np.arange(2, 272, 2))):
        lines.append(f"N{20 + k} X{20 * np.cos(a):.4f} Y{20 * np.sin(a) + 0.3 * np.sin(5 * a):.4f}")
    lines += ["G1 X0 Y-40 (a long line)", "G0 Z5", "M9", "G0 X30 Y0", "G1 Z-1 F300"]
    for a in np.radians(np.arange(2, 182, 2)):
        lines.append(f"G1 Y{15 * np.sin(a):.4f} Z{-16 + 15 * np.cos(a):.4f} F900")
    lines += ["G0 Z5", "M5", "M30"]
    return "\n".join(lines) + "\n"


VAR = "5221\t10.0\n5222\t-5.0\n5223\t0.0\n"


@pytest.fixture
def written(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "p.ngc").write_text(_program())
    (tmp_path / "m.var").write_text(VAR)
    assert main(["plan", "p.ngc", "--vmax", "250", "--amax", "3000", "--rule", "smooth",
                 "--tolerance", "0.01", "--json", "o.json", "--var", "m.var", "--smoothed-gcode", "s.ngc",
                 "--smoothed-format", "g1", "--chord-tolerance", "0.001"]) == 0
    return tmp_path


def _samples(arr, step=0.05):
    pts = []
    for k, s, e in zip(arr["kind"], arr["start"], arr["end"]):
        if k == 0:
            continue
        n = max(1, int(np.ceil(np.linalg.norm(e - s) / step)))
        pts.append(s + np.linspace(0, 1, n + 1)[:, None] * (e - s))
    return np.vstack(pts)


def _distance(points, arr):
    """Distance of each point to the feed moves (lines) of arr [mm]."""
    feed = np.asarray(arr["kind"]) != 0
    a, b = np.asarray(arr["start"])[feed], np.asarray(arr["end"])[feed]
    d = b - a
    dd = np.maximum((d * d).sum(1), 1e-30)
    best = np.full(len(points), np.inf)
    for i0 in range(0, len(points), 2000):
        p = points[i0:i0 + 2000, None, :]
        t = np.clip(((p - a) * d).sum(2) / dd, 0, 1)
        best[i0:i0 + 2000] = np.linalg.norm(p - (a + t[..., None] * d), axis=2).min(1)
    return best


def test_lines_without_moves_stay_in_place(written):
    src = _program().splitlines()
    out = (written / "s.ngc").read_text().splitlines()
    kept = [ln for ln in src if not any(a in "XYZ" for a, _ in _words(ln)[0])]
    it = iter(out)
    assert all(any(o == ln for o in it) for ln in kept), "a line without a move is missing or moved"
    assert out[-1] == "M30" and "M2" not in out
    assert "G0 X30 Y0" in out and "G0 Z5" in out  # unchanged moves as written


def test_no_move_the_program_did_not_make(written):
    orig = toolpath.read_gcode_arrays(written / "p.ngc", work_offsets=written / "m.var")
    back = toolpath.read_gcode_arrays(written / "s.ngc", work_offsets=written / "m.var")
    assert np.array_equal(back["start"][0], orig["start"][0]) and np.allclose(back["end"][0], orig["end"][0])
    rapids = lambda a: np.asarray(a["end"])[np.asarray(a["kind"]) == 0]  # noqa: E731
    assert np.allclose(rapids(back), rapids(orig), atol=1e-6)
    assert np.allclose(back["end"][-1], orig["end"][-1], atol=1e-6)


def test_read_back_within_tolerance_both_ways(written):
    orig = toolpath.read_gcode_arrays(written / "p.ngc", work_offsets=written / "m.var")
    back = toolpath.read_gcode_arrays(written / "s.ngc", work_offsets=written / "m.var")
    assert np.any(np.asarray(orig["start"])[:, 0] > 25)  # the G54 shift was applied to both
    limit = 0.01 + 0.001 + 1e-6
    assert _distance(_samples(back), orig).max() <= limit
    assert _distance(_samples(orig), back).max() <= limit
    # smoothing did change the moves (the test is not of an unchanged copy)
    assert len(back["kind"]) != len(orig["kind"])
    assert nm.smooth_path(orig, 0.01)[3]["runs_smoothed"] >= 2
