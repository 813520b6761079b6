"""Read -> transform -> write keeps every comment and non-motion word (issue 20): the sequence of
commands (comments, M/S/T words, G4 dwells, G43/G49, G54-G59.3, G61/G64, G40, G80, M0/M1, M2/M30)
read back from the output equals the sequence read from the input, for the plain writer and for the
volumetric post-processor with a zero-error machine (motion reproduced to 1e-9 mm) and a real one
(examples/machines/hmc_yang_kweon.toml, motion compensated). Programs: every readable program in
../shared/data/gcode and a seeded random corpus (hypothesis, derandomized)."""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import netshape as ns
from netshape.cli import main as cli_main

tpm = ns.toolpath
REPO = Path(__file__).resolve().parents[3]
HMC = REPO / "examples" / "machines" / "hmc_yang_kweon.toml"
PROGRAMS = ["3D_Chips.ngc", "cds.ngc", "arcspiral.ngc", "tort.ngc"]
# puts the shared programs inside the HMC's travel (X 0-800, Y 0-600, Z 0-500 mm)
HMC_OFFSETS = {"G54": (400.0, 300.0, 250.0), "G55": (380.0, 280.0, 240.0)}


def texts(tp) -> list[str]:
    return [c.text for c in tp.commands]


def pairs(tp) -> list[tuple[int, str]]:
    return tpm.non_motion(tp)


def has_end(tp) -> bool:
    return any(c.kind == tpm.CommandKind.program_end for c in tp.commands)


def expected_texts(tp) -> list[str]:
    """What the writer must give back: the program's commands, plus the M2 it adds when the program
    had no M2/M30."""
    return texts(tp) if has_end(tp) else texts(tp) + ["M2"]


def expected_pairs(tp) -> list[tuple[int, str]]:
    return pairs(tp) if has_end(tp) else pairs(tp) + [(len(tp), "M2")]


def zero_machine():
    return ns.machine.machine_from_dict({"name": "zero error", "tool_chain": ["X", "Y", "Z"],
                                         "workpiece_chain": []})


def reread(text: str, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tpm.GcodeWarning)
        return tpm.parse_gcode(text, **kw)


def header_free(tp):
    """The commands of a compensate_gcode output without its own first comment (the header)."""
    t = texts(tp)
    assert t and t[0].startswith("(netshape volumetric compensation")
    return t[1:]


def check_plain(tp, **kw):
    """Plain writer: same (place, text) sequence and the same blocks (coordinates exact)."""
    back = reread(tpm.format_gcode(tp), **kw)
    assert pairs(back) == expected_pairs(tp)
    assert len(back) == len(tp)
    for a, b in zip(tp.blocks, back.blocks):
        assert a.kind == b.kind
        np.testing.assert_allclose(b.end, a.end, rtol=0, atol=1e-9)
        assert b.feed == pytest.approx(a.feed, rel=1e-12)
    return back


def check_compensated(machine, tp, *, exact_motion: bool, **kw):
    """Volumetric compensation: commands in the same order, each before the first output move of the
    source block it preceded; after writing and reading back, the same command texts."""
    out, _ = ns.compensation.compensate_program(machine, tp, chord_tolerance=0.002)
    assert texts(out) == texts(tp)
    n_in, n_out = len(tp), len(out)
    src_lines = [b.line for b in tp.blocks]
    out_lines = [b.line for b in out.blocks]
    for c_in, c_out in zip(tp.commands, out.commands):
        if c_in.before < n_in:
            assert c_out.before < n_out and out_lines[c_out.before] == src_lines[c_in.before]
            # and it is the first output move of that source block
            assert c_out.before == 0 or out_lines[c_out.before - 1] != src_lines[c_in.before] or \
                src_lines.count(src_lines[c_in.before]) > 1
        else:
            assert c_out.before == n_out
    back = reread(tpm.format_gcode(out, header_comment="h"), **kw)
    assert texts(back)[1:] == expected_texts(tp)
    if exact_motion:
        assert len(back) == len(tp)
        for a, b in zip(tp.blocks, back.blocks):
            assert a.kind == b.kind
            np.testing.assert_allclose(b.start, a.start, rtol=0, atol=1e-9)
            np.testing.assert_allclose(b.end, a.end, rtol=0, atol=1e-9)
            if a.kind == tpm.MotionKind.arc:
                np.testing.assert_allclose(b.center, a.center, rtol=0, atol=1e-9)
    return out


# ---- the issue's example -----------------------------------------------------------------------

ISSUE_PROGRAM = """(issue 20 example)
G21 G90 G17
G64 P0.05 Q0.02
T2 M6
G43 H2
G54
S8000 M3
M8
G0 X0 Y0 Z5
M7
G1 Z-2 F1000000
G4 P0.5
(finish pass)
G1 X10 F450
G2 X20 Y0 R5
M9
M5
G0 Z50
M30
"""


def test_issue_example_keeps_every_word():
    with pytest.warns(tpm.GcodeWarning) as rec:
        tp = tpm.parse_gcode(ISSUE_PROGRAM, source="issue.ngc")
    msgs = [str(w.message) for w in rec]
    assert any(m.startswith("issue.ngc:5: G43 H2") for m in msgs)
    assert any(m.startswith("issue.ngc:6: G54") for m in msgs)
    out = tpm.format_gcode(tp)
    for word in ("G64 P0.05 Q0.02", "G43 H2", "\nG54\n", "M8", "M7", "M9", "M5", "G4 P0.5", "(finish pass)",
                 "\nM30\n", "F1000000\n", "T2\nM6"):
        assert word in out, word
    assert "\nM2\n" not in out and "F1000000.0000" not in out
    # order relative to motion: the dwell sits between the plunge and the cut, M9/M5 after the arc
    lines = out.splitlines()
    assert lines.index("G4 P0.5") == lines.index("G1 Z-2 F1000000") + 1
    assert lines.index("M9") > next(i for i, s in enumerate(lines) if s.startswith("G2 "))
    check_plain(tp)


def test_line_numbers_when_asked(shared_data):
    text = (shared_data / "gcode" / "cds.ngc").read_text()
    tp = reread(text, line_numbers=True)
    t = texts(tp)
    assert t[:3] == ["(Circle Diamond Square Program)", "(Tom Kramer)", "(26-Sep-1994)"]
    numbered = [x for x in t if x.startswith("N")]
    assert len(numbered) > 250 and numbered[0] == "N80"
    assert t[t.index("N150") + 1] == "(MILLING AN ENCLOSED POCKET)"
    back = reread(tpm.format_gcode(tp), line_numbers=True)
    assert pairs(back) == expected_pairs(tp)
    assert "N10" not in texts(reread(text))  # not kept unless asked


# ---- shared programs ---------------------------------------------------------------------------

@pytest.mark.parametrize("name", PROGRAMS)
def test_shared_program_plain_round_trip(shared_data, name):
    tp = reread((shared_data / "gcode" / name).read_text(), source=name)
    assert len(tp.commands) > 0
    check_plain(tp)


@pytest.mark.parametrize("name", PROGRAMS)
def test_shared_program_zero_error_compensation(shared_data, name):
    tp = reread((shared_data / "gcode" / name).read_text(), source=name)
    check_compensated(zero_machine(), tp, exact_motion=True)


@pytest.mark.parametrize("name", PROGRAMS)
def test_shared_program_real_machine_compensation(shared_data, name):
    machine = ns.machine.load_machine(HMC)
    tp = reread((shared_data / "gcode" / name).read_text(), source=name, work_offsets=HMC_OFFSETS)
    out = check_compensated(machine, tp, exact_motion=False, work_offsets=HMC_OFFSETS)
    # the motion was compensated: commanded points moved by the machine's error (tens of µm)
    moved = max(np.abs(np.asarray(a.end) - b.end).max() for a, b in zip(tp.blocks[-50:], out.blocks[-50:]))
    assert moved > 1e-4


def test_cli_volumetric_compensate_keeps_3d_chips_words(shared_data, tmp_path, capsys):
    """The issue's report: M8, M9 and G64 P.1 were lost by `netshape volumetric compensate`."""
    src = shared_data / "gcode" / "3D_Chips.ngc"
    out = tmp_path / "chips_comp.ngc"
    var = tmp_path / "hmc.var"
    var.write_text("5221\t400.0\n5222\t300.0\n5223\t250.0\n")
    code = cli_main(["volumetric", "compensate", str(src), "--machine", str(HMC), "-o", str(out),
                     "--var", str(var), "--tool-table", str(_tool_table(tmp_path))])
    assert code == 0
    text = out.read_text()
    for word in ("\nM8\n", "\nM9\n", "\nG64 P0.1\n", "\nT1\nM6\n", "\nS1600\nM3\n", "\nM2\n"):
        assert word in text, word
    back = reread(text, work_offsets=HMC_OFFSETS)
    ref = reread(src.read_text())
    assert header_free(back) == texts(ref)


def _tool_table(folder: Path) -> Path:
    p = folder / "tool.tbl"
    p.write_text("T1 P1 D10.0 Z0.0 ;10 mm ball\nT2 P2 Z+35.25 D6 ;drill\n")
    return p


# ---- offsets, tool table, warnings ---------------------------------------------------------------

def test_var_file_and_tool_table(tmp_path):
    var = tmp_path / "linuxcnc.var"
    var.write_text("5161\t0.0\n5220\t1.000000\n5221\t10.5\n5222\t-2\n5223\t3\n5241\t100\n5243\t-50\n5381\t7\n")
    w = tpm.read_var_file(var)
    np.testing.assert_array_equal(w[0], [10.5, -2, 3])
    np.testing.assert_array_equal(w[1], [100, 0, -50])
    np.testing.assert_array_equal(w[8], [7, 0, 0])
    assert tpm.read_tool_table(_tool_table(tmp_path)) == {1: 0.0, 2: 35.25}
    prog = "G0 X1 Y1 Z1\nG55\nG0 X1\nT2 M6\nG43\nG0 Z0\nG59.3 G49 G0 X0\n"
    with warnings.catch_warnings():
        warnings.simplefilter("error", tpm.GcodeWarning)  # nothing to warn about: both were given
        tp = tpm.parse_gcode(prog, work_offsets=var, tool_table=tmp_path / "tool.tbl")
    ends = np.array([b.end for b in tp.blocks])
    np.testing.assert_allclose(ends, [[11.5, -1, 4], [101, -1, 4], [101, -1, -50 + 35.25], [7, -1, -50 + 35.25]])
    check_plain(tp, work_offsets=var, tool_table=tmp_path / "tool.tbl")
    # refused: rotation, active G92, malformed lines, a tool without T
    (tmp_path / "rot.var").write_text("5230 15\n")
    with pytest.raises(ValueError, match="5230.*rotation"):
        tpm.read_var_file(tmp_path / "rot.var")
    (tmp_path / "g92.var").write_text("5210 1\n5211 3\n")
    with pytest.raises(ValueError, match="G92"):
        tpm.read_var_file(tmp_path / "g92.var")
    (tmp_path / "bad.var").write_text("5221 1\nfoo\n")
    with pytest.raises(ValueError, match="bad.var:2"):
        tpm.read_var_file(tmp_path / "bad.var")
    (tmp_path / "bad.tbl").write_text("P1 Z3\n")
    with pytest.raises(ValueError, match="bad.tbl:1.*needs T"):
        tpm.read_tool_table(tmp_path / "bad.tbl")
    with pytest.raises(ValueError, match="tool 3 is not in the tool table"):
        tpm.parse_gcode("G43 H3\n", tool_table={1: 2.0})


def test_missing_offsets_warn_once_naming_the_line(tmp_path, capsys):
    prog = tmp_path / "p.ngc"
    prog.write_text("G0 X0\nG55\nG0 X1\nG56\nG43 H1\nG0 Z1\nG43 H2\nG0 Z2\nM2\n")
    assert cli_main(["info", str(prog)]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"netshape info: warning: {prog}:2: G55 selects a work offset but no work offsets were given; "
                   "taken as zero",
                   f"netshape info: warning: {prog}:5: G43 H1 applies a tool length but no tool table was given; "
                   "taken as zero"]
    assert cli_main(["info", str(prog), "--var", str(_var(tmp_path)), "--tool-table",
                     str(_tool_table(tmp_path)), "--json"]) == 0
    cap = capsys.readouterr()
    assert cap.err == ""
    d = json.loads(cap.out)
    assert d["warnings"] == [] and d["bbox_max_mm"][2] == pytest.approx(2 - 1.0 + 35.25)


def _var(folder: Path) -> Path:
    p = folder / "o.var"
    p.write_text("5263\t-1.0\n")  # G56 Z = -1
    return p


@pytest.mark.parametrize("code, word", [("G41 D1", "G41"), ("G42", "G42"), ("G92 X0", "G92"),
                                         ("G93", "G93"), ("G95", "G95")])
def test_geometry_changing_words_are_refused_with_the_line(code, word):
    with pytest.raises(ns.ParseError) as e:
        tpm.parse_gcode(f"G0 X1\n{code}\n")
    assert e.value.line == 2 and word in str(e.value)


# ---- dwells in info and plan -------------------------------------------------------------------

def test_dwells_count_in_info_and_plan(tmp_path, capsys):
    prog = tmp_path / "d.ngc"
    prog.write_text("G4 P1\nG1 X10 F600\nG4 P2.5\nG1 X20\nG4 P0.25\nM2\n")
    assert cli_main(["info", str(prog), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["dwell_time_s"] == 3.75 and d["dwells"] == 3
    assert d["total_time_s"] == pytest.approx(d["feed_time_s"] + 3.75)
    out = tmp_path / "plan.json"
    assert cli_main(["plan", str(prog), "--vmax", "100", "--amax", "1000", "--rule", "vector",
                     "--json", str(out)]) == 0
    p = json.loads(out.read_text())
    assert p["dwell_time_s"] == 3.75
    # independent: the two 10 mm moves at 10 mm/s, each from rest to rest with a = 1000 mm/s^2
    # (trapezoid: t = L/v + v/a), plus the dwells
    one = 10.0 / 10.0 + 10.0 / 1000.0
    assert p["cycle_time_s"] == pytest.approx(2 * one + 3.75, abs=3e-3)
    # the same program without dwells does not stop between the moves: faster than the two pieces
    prog.write_text("G1 X10 F600\nG1 X20\nM2\n")
    assert cli_main(["plan", str(prog), "--vmax", "100", "--amax", "1000", "--rule", "vector",
                     "--json", str(out)]) == 0
    q = json.loads(out.read_text())
    assert q["dwell_time_s"] == 0.0 and q["cycle_time_s"] < 2 * one - 5e-3
    # a Toolpath's dwell commands count the same way
    traj = ns.motion.plan(tpm.parse_gcode("G4 P1\nG1 X10 F600\nG4 P2.5\nG1 X20\nG4 P0.25\n"),
                          ns.motion.AxisLimits.uniform(100, 1000), rule="vector")
    assert traj.stats["cycle_time_s"] == pytest.approx(p["cycle_time_s"], rel=1e-12)
    assert np.all(np.diff(traj.t) > 0) and traj.t[0] == pytest.approx(1.0)


# ---- seeded random corpus ------------------------------------------------------------------------

_WORDS = st.sampled_from([
    "M3", "M4", "M5", "M7", "M8", "M9", "M0", "M1", "M48", "M49", "G40", "G49", "G43 H{t}", "G54", "G55",
    "G59.3", "G61", "G61.1", "G64", "G64 P{p}", "G64 P{p} Q{q}", "G80", "G97", "G98", "G99", "G4 P{p}",
    "S{s}", "T{t}", "T{t} M6", "S{s} M3", "(c {s} ok)", "; semi {t}", "(msg, hello)",
])
_MOVES = st.sampled_from(["G0 X{x} Y{y}", "G1 X{x} Z{z}", "G1 Y{y}", "G2 X{x} Y{y} R{r}", "G3 X{x} Y{y} R{r}",
                          "G0 Z{z}", "X{x}"])
_num = st.integers(-40000, 40000).map(lambda v: v / 1000.0)


@st.composite
def programs(draw):
    lines = ["G21 G90 G17 G0 X0 Y0 Z0 F{f}".format(f=draw(st.integers(1, 100000)))]
    for _ in range(draw(st.integers(1, 25))):
        parts = []
        if draw(st.booleans()):
            parts.append(draw(_WORDS))
        if draw(st.booleans()) or not parts:
            parts.append(draw(_MOVES))
        if draw(st.integers(0, 4)) == 0:
            parts.append(draw(_WORDS).replace(";", "("))  # two records on one line (';' ends it)
        line = " ".join(parts)
        if "(" in line and ")" not in line.split("(")[-1]:
            line += ")"
        vals = dict(x=draw(_num), y=draw(_num), z=draw(_num), r=draw(st.integers(60, 90)),
                    p=draw(st.integers(0, 5000)) / 1000.0, q=draw(st.integers(0, 99)) / 1000.0,
                    s=draw(st.integers(0, 24000)), t=draw(st.integers(0, 9)))
        lines.append(line.format(**vals))
    lines.append(draw(st.sampled_from(["M2", "M30", ""])))
    return "\n".join(lines) + "\n"


# every work offset inside the HMC's travel (X 0-800, Y 0-600, Z 0-500 mm), a little apart
FUZZ_OFFSETS = np.array([[400.0 + 3 * k, 300.0 - 2 * k, 250.0 + k] for k in range(9)])
FUZZ_TOOLS = {t: 10.0 * t for t in range(10)}


def _parse_or_none(text, **kw):
    try:
        return reread(text, tool_table=FUZZ_TOOLS, **kw)
    except ns.ParseError:
        return None  # e.g. a line with two M codes of one group, or an arc the R cannot reach


@settings(derandomize=True, max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(programs())
def test_random_programs_round_trip(text):
    tp = _parse_or_none(text)
    if tp is None or len(tp) == 0:
        return
    kw = dict(tool_table=FUZZ_TOOLS)
    check_plain(tp, **kw)
    check_compensated(zero_machine(), tp, exact_motion=True, **kw)
    # a real machine, with the programs placed in its travel by work offsets
    tpo = _parse_or_none(text, work_offsets=FUZZ_OFFSETS)
    check_plain(tpo, work_offsets=FUZZ_OFFSETS, **kw)
    check_compensated(_HMC(), tpo, exact_motion=False, work_offsets=FUZZ_OFFSETS, **kw)


_HMC_CACHE: list = []


def _HMC():
    if not _HMC_CACHE:
        _HMC_CACHE.append(ns.machine.load_machine(HMC))
    return _HMC_CACHE[0]
