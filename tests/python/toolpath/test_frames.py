"""A program's frames and sampler (Toolpath.to_machine / to_program / work_offset_index / sample, the
writer's work_offset_word): the machine frame is program point + the work offset in force at each block,
the sampler gives the points of an independent NumPy sampler bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

from netshape import toolpath as tpm

# the programs select G55 without the reader being given offsets: the frames here are the test's own
pytestmark = pytest.mark.filterwarnings("ignore::netshape.toolpath.GcodeWarning")

PROGRAM = ("G21 G90 G17 G94\nG0 Z5\nG0 X-10 Y-5\nG1 Z-1 F300\nG1 X10 F900\nG2 X10 Y5 I0 J5\nG0 Z5\n"
           "G55\nG0 X-10 Y-5\nG1 Z-1 F300\nG3 X10 Y5 I10 J5\nG54\nG1 X0 Y0\nM30\n")


def _offsets():
    o = np.zeros((9, 3))
    o[0], o[1] = [-150.0, 80.0, -300.0], [120.0, -60.0, -280.0]
    return o


def _numpy_sample(tp, spacing):
    """Points every <= spacing along the feed moves (arcs as chords within 1e-4 mm) and their distance."""
    split = [b for b in tp.split_arcs(1e-4).blocks if b.kind != tpm.MotionKind.rapid]
    a = np.array([b.start for b in split], float)
    b = np.array([b.end for b in split], float)
    L = np.linalg.norm(b - a, axis=1)
    n = np.maximum(1, np.ceil(L / spacing).astype(np.int64))
    seg = np.repeat(np.arange(len(a)), n)
    first = np.concatenate([[0], np.cumsum(n)[:-1]])
    t = (np.arange(seg.size) - np.repeat(first, n)) / np.repeat(n, n)
    s0 = np.concatenate([[0.0], np.cumsum(L)[:-1]])
    pts = np.vstack([a[seg] + t[:, None] * (b[seg] - a[seg]), b[-1:]])
    return pts, np.concatenate([s0[seg] + t * L[seg], [s0[-1] + L[-1]]])


def test_machine_frame_is_program_point_plus_offset_in_force():
    tp = tpm.parse_gcode(PROGRAM, source="two.ngc")
    idx = np.asarray(tp.work_offset_index())
    assert list(idx) == [0] * 6 + [1] * 3 + [0]
    m = tp.to_machine(_offsets())
    ends = np.array([b.end for b in tp.blocks])
    assert np.array_equal(np.array([b.end for b in m.blocks]), ends + _offsets()[idx])
    assert np.array_equal(np.asarray(m.block_offsets()), _offsets()[idx])
    back = m.to_program()
    assert np.allclose(np.array([b.center for b in back.blocks]), [b.center for b in tp.blocks], atol=1e-12)
    assert not np.asarray(back.work_offsets).any()
    with pytest.raises(ValueError, match="already in machine coordinates"):
        m.to_machine(_offsets())


def test_stock_frame_keeps_g54_blocks_bit_for_bit():
    tp = tpm.parse_gcode(PROGRAM, source="two.ngc")
    st = tp.to_machine(_offsets() - _offsets()[0])
    for k, (b, c) in enumerate(zip(tp.blocks, st.blocks)):
        if k < 6:
            assert np.array_equal(b.start, c.start) and np.array_equal(b.end, c.end)


@pytest.mark.parametrize("spacing", [0.25, 0.7, 3.0])
def test_sample_equals_the_numpy_sampler(spacing):
    tp = tpm.parse_gcode(PROGRAM, source="two.ngc").to_machine(_offsets())
    pts, s = tp.sample(spacing)
    ref_pts, ref_s = _numpy_sample(tp, spacing)
    assert np.array_equal(pts, ref_pts) and np.array_equal(s, ref_s)
    all_pts, _ = tp.sample(spacing, feeds_only=False)
    assert len(all_pts) > len(pts)


def test_writer_names_g54_when_the_program_selects_none_first():
    bare = tpm.parse_gcode("G1 X1 Y2 F60\n", source="bare.ngc")
    assert tpm.format_gcode(bare, work_offset_word=True) == "G21 G90 G17 G94 G91.1\nG54\nG1 X1 Y2 F60\nM2\n"
    tp = tpm.parse_gcode(PROGRAM, source="two.ngc")
    assert tpm.format_gcode(tp, work_offset_word=True).count("G54") == 2  # its own word, and the one written
    g55 = tpm.parse_gcode("G55\nG1 X1 F60\n", source="g55.ngc")
    assert tpm.format_gcode(g55, work_offset_word=True) == tpm.format_gcode(g55)
