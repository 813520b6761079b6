"""Property-based checks of the G-code reader and writer (hypothesis, derandomized, bounded examples).

Properties (independent of how the reader and writer work inside):
- round trip: read → write → read gives the same blocks (kind, end points exactly, arc centres and
  feeds to rounding) and the same command texts, and writing the re-read program gives the same text
  again (the writer's output is a fixed point), for lines, rapids, arcs in the three planes in I/J/K
  and R form, helices, incremental moves and inch input;
- work offsets: a program read with work offsets equals the program read without them moved by the
  offset in force at each block (G54 … G59.3), and writing it and reading it back with the same
  offsets gives the same machine positions.
"""

from __future__ import annotations

import warnings

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import netshape as ns

tpm = ns.toolpath
FAST = settings(derandomize=True, max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
_num = st.integers(-50000, 50000).map(lambda v: v / 1000.0)  # [mm], 3 decimals as CAM writes them


def _read(text, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tpm.GcodeWarning)
        try:
            return tpm.parse_gcode(text, **kw)
        except ns.ParseError:
            return None  # e.g. an R arc whose end is farther than 2R


@st.composite
def motion_programs(draw):
    """Programs of rapids, lines, arcs (I/J/K or R, G17/G18/G19, helical, P turns), G91 stretches,
    G20 inch stretches, feeds, spindle and coolant words and comments."""
    plane = draw(st.sampled_from(["G17", "G18", "G19"]))
    lines = [f"G21 G90 {plane} F{draw(st.integers(10, 20000))}", "G0 X0 Y0 Z0"]
    for _ in range(draw(st.integers(1, 20))):
        kind = draw(st.sampled_from(["G0", "G1", "G2", "G3", "G2", "G3", "plane", "mode", "word"]))
        x, y, z = draw(_num), draw(_num), draw(_num)
        if kind in ("G0", "G1"):
            lines.append(f"{kind} X{x} Y{y} Z{z}" + (f" F{draw(st.integers(10, 20000))}" if draw(st.booleans()) else ""))
        elif kind in ("G2", "G3"):
            if draw(st.booleans()):
                # centre form, a full circle (no end point; P turns) with a helical lead along the normal
                u, v = {"G17": "IJ", "G18": "KI", "G19": "JK"}[plane]
                lead = {"G17": "Z", "G18": "Y", "G19": "X"}[plane]
                turns = draw(st.sampled_from(["", "", " P2"]))
                lines.append(f"{kind} {u}{x} {v}{y} {lead}{z}{turns}")
            else:
                a, b = {"G17": "XY", "G18": "ZX", "G19": "YZ"}[plane]
                r = draw(st.integers(30, 90))  # ends within ±50 mm: always reachable
                lines.append(f"{kind} {a}{x} {b}{y} R{r}")
        elif kind == "plane":
            plane = draw(st.sampled_from(["G17", "G18", "G19"]))
            lines.append(plane)
        elif kind == "mode":
            lines.append(draw(st.sampled_from(["G91", "G90", "G20", "G21"])))
        else:
            lines.append(draw(st.sampled_from(["M3 S1200", "M5", "M8", "M9", "(note)", "G64 P0.01", "T2 M6"])))
    lines.append("M2")
    return "\n".join(lines) + "\n"


def _same_blocks(a, b):
    assert len(a) == len(b)
    for x, y in zip(a.blocks, b.blocks):
        assert x.kind == y.kind
        np.testing.assert_array_equal(y.end, x.end)
        np.testing.assert_allclose(y.start, x.start, rtol=0, atol=1e-12)
        if x.kind == tpm.MotionKind.arc:  # (plane and direction are modal state only arcs use)
            assert x.plane == y.plane and x.clockwise == y.clockwise and x.turns == y.turns
            np.testing.assert_allclose(y.center, x.center, rtol=0, atol=1e-9)
        assert y.feed == np.float64(x.feed) or abs(y.feed - x.feed) <= 1e-12 * x.feed
        assert y.spindle_rpm == x.spindle_rpm and y.tool == x.tool


@FAST
@given(motion_programs())
def test_read_write_read_gives_the_same_program(text):
    tp = _read(text, source="p.ngc")
    if tp is None:
        return
    out = tpm.format_gcode(tp)
    back = _read(out, source="back.ngc")
    assert back is not None, out
    _same_blocks(tp, back)
    assert [c.text for c in back.commands] == [c.text for c in tp.commands]
    assert tpm.format_gcode(back) == out  # the writer's output is a fixed point


OFFSETS = st.lists(st.tuples(_num, _num, _num), min_size=9, max_size=9).map(np.array)
CODES = ("G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3")


@st.composite
def offset_programs(draw):
    lines = ["G21 G90 G17 F600", "G0 X0 Y0 Z0"]
    for _ in range(draw(st.integers(1, 15))):
        if draw(st.integers(0, 2)) == 0:
            lines.append(draw(st.sampled_from(CODES)))
        move = draw(st.sampled_from(["G0", "G1", "G2"]))
        x, y, z = draw(_num), draw(_num), draw(_num)
        lines.append(f"{move} X{x} Y{y} Z{z}" + (f" R{draw(st.integers(60, 90))}" if move == "G2" else ""))
    lines.append("M30")
    return "\n".join(lines) + "\n"


@FAST
@given(offset_programs(), OFFSETS)
def test_work_offsets_move_each_block_by_the_offset_in_force(text, offsets):
    plain = _read(text)
    moved = _read(text, work_offsets=offsets)
    if plain is None or moved is None:
        return
    assert len(plain) == len(moved)
    # the offset in force at each block: the last G54 … G59.3 command before it (G54 at the start)
    active = np.zeros(len(plain), dtype=int)
    current, cmds = 0, [c for c in plain.commands if c.kind == tpm.CommandKind.work_offset]
    k = 0
    for i in range(len(plain)):
        while k < len(cmds) and cmds[k].before <= i:
            current = int(cmds[k].value)
            k += 1
        active[i] = current
    for i, (a, b) in enumerate(zip(plain.blocks, moved.blocks)):
        np.testing.assert_allclose(np.asarray(b.end) - a.end, offsets[active[i]], rtol=0, atol=1e-9)
    # written in program coordinates and read back with the same offsets: the same machine positions
    back = _read(tpm.format_gcode(moved), work_offsets=offsets)
    assert back is not None and len(back) == len(moved)
    for a, b in zip(moved.blocks, back.blocks):
        np.testing.assert_allclose(b.end, a.end, rtol=0, atol=1e-9)
