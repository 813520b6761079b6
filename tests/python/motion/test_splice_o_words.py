"""O-words through the reader and `netshape plan --rule smooth --smoothed-gcode` (issue 39 item 5):
a Fanuc program number and LinuxCNC subroutines (`oN sub` … `oN endsub`, `oN call [args]`) read as
the program runs them — a call makes the moves of its body written in its place — and the splice keeps
every o-word line where it was: the program number, the definition as written, a call whose moves are
unchanged; a call whose moves smoothing changed is replaced by the new moves, and read back the
program stays within ε of the original both ways. Control flow is refused naming the line."""

from __future__ import annotations

import numpy as np
import pytest

from netshape import toolpath
from netshape.cli import main


def _wave(amp: str) -> list[str]:
    """A micro-segment wave of amplitude `amp` (a G-code value) along +X from the current point."""
    return [f"G91 G1 X0.25 Y[{amp} * {np.sin(0.2 * k) - np.sin(0.2 * (k - 1)):.6f}] F1200"
            for k in range(1, 121)] + ["G90"]


def _program() -> str:
    return "\n".join(["%", "O1234 (WAVES)", "G21 G90 G17", "o100 sub (wave of amplitude #1)", *_wave("#1"),
                      "o100 endsub", "G0 X0 Y0 Z1", "G1 Z0 F300", "o100 call [2.0] (first)", "G0 Z1",
                      "G0 X0 Y10", "G1 Z0 F300", "o100 call [0.0]", "G0 Z5", "M30", "%"]) + "\n"


def _inlined() -> str:
    wave2 = [ln.replace("#1", "2.0") for ln in _wave("#1")]
    wave0 = [ln.replace("#1", "0.0") for ln in _wave("#1")]
    return "\n".join(["G21 G90 G17", "G0 X0 Y0 Z1", "G1 Z0 F300", *wave2, "G0 Z1", "G0 X0 Y10", "G1 Z0 F300",
                      *wave0, "G0 Z5", "M30"]) + "\n"


def test_calls_make_the_moves_of_the_inlined_program():
    called = toolpath.parse_gcode_arrays(_program())
    inlined = toolpath.parse_gcode_arrays(_inlined())
    for key in ("kind", "start", "end", "feed"):
        assert np.array_equal(called[key], inlined[key]), key
    calls = [n for n, ln in enumerate(_program().splitlines(), 1) if "call" in ln]
    assert set(np.unique(called["line"])) >= set(calls)  # a call line owns the moves it makes


def test_program_number_round_trips_through_the_writer():
    tp = toolpath.parse_gcode(_program())
    text = toolpath.format_gcode(tp)
    assert "O1234" in text.splitlines()
    back = toolpath.parse_gcode(text)
    assert [b.end.tolist() for b in back.blocks] == [b.end.tolist() for b in tp.blocks]


@pytest.fixture
def written(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "p.ngc").write_text(_program())
    assert main(["plan", "p.ngc", "--vmax", "250", "--amax", "3000", "--rule", "smooth",
                 "--tolerance", "0.01", "--json", "o.json", "--smoothed-gcode", "s.ngc",
                 "--smoothed-format", "g1", "--chord-tolerance", "0.001"]) == 0
    return tmp_path


def test_splice_keeps_o_words_in_place(written):
    src = _program().splitlines()
    out = (written / "s.ngc").read_text().splitlines()
    first, last = src.index("o100 sub (wave of amplitude #1)"), src.index("o100 endsub")
    definition = src[first:last + 1]
    at = out.index(definition[0])
    assert out[at:at + len(definition)] == definition  # the definition as written, in place
    assert out.index("O1234 (WAVES)") < at
    assert "o100 call [2.0] (first)" not in out and "(first)" in out  # its moves were smoothed
    assert "o100 call [0.0]" in out  # a straight wave: nothing to smooth, the call kept
    assert out[-2:] == ["M30", "%"]


def test_splice_read_back_within_tolerance(written):
    orig = toolpath.read_gcode_arrays(written / "p.ngc")
    back = toolpath.read_gcode_arrays(written / "s.ngc")
    assert len(back["kind"]) != len(orig["kind"])  # smoothing changed the first call's moves
    pts = lambda a: np.vstack([s + np.linspace(0, 1, 9)[:, None] * (e - s)  # noqa: E731
                               for k, s, e in zip(a["kind"], a["start"], a["end"]) if k != 0])

    def dist(p, a):
        feed = np.asarray(a["kind"]) != 0
        s, e = np.asarray(a["start"])[feed], np.asarray(a["end"])[feed]
        d = e - s
        t = np.clip(((p[:, None, :] - s) * d).sum(2) / np.maximum((d * d).sum(1), 1e-30), 0, 1)
        return np.linalg.norm(p[:, None, :] - (s + t[..., None] * d), axis=2).min(1)

    limit = 0.01 + 0.001 + 1e-6  # ε and the chord tolerance of the written cubics
    assert dist(pts(back), orig).max() <= limit
    assert dist(pts(orig), back).max() <= limit


def test_control_flow_is_refused_naming_the_line(tmp_path, capsys):
    (tmp_path / "w.ngc").write_text("G21\n#1 = 0\no1 while [#1 LT 3]\nG1 X#1 F100\n#1 = [#1 + 1]\n"
                                    "o1 endwhile\n")
    code = main(["plan", str(tmp_path / "w.ngc"), "--vmax", "250", "--amax", "3000", "--rule", "blend",
                 "--json", str(tmp_path / "o.json")])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "w.ngc:3" in err[0] and "'while'" in err[0]
    assert not (tmp_path / "o.json").exists()
