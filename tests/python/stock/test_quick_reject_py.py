"""Quick reject of moves above the stock (ZMap.height_bound): such moves visit no node and change
nothing; a move over one remaining high cell still cuts it; the bound tightens after surfacing."""

from __future__ import annotations

import numpy as np

import netshape as ns

Cutter = ns.stock.Cutter


def test_moves_above_the_stock_visit_nothing_but_a_high_cell_is_still_cut():
    h = np.full((100, 100), 5.0)
    h[80, 20] = 10.0
    z = ns.stock.from_heights(h, 0, 20, 0, 20, 0)
    tool = Cutter.ball_end(6.0, 2, 0.5236)
    assert z.height_bound(0, 99) == 10.0
    starts = np.array([[-5, 3, 15], [2, 2, 15], [0, 3, 6]], dtype=float)  # 5 mm above; above the rows' floor
    ends = np.array([[25, 17, 16], [18, 18, 15], [20, 4, 6]], dtype=float)
    st = ns.stock.sweep_lines(z, tool, starts, ends)
    assert (st.moves, st.nodes_visited, st.nodes_lowered) == (3, 0, 0)
    assert np.array_equal(z.heights, h)
    st = ns.stock.sweep_line(z, tool, (0, 16.25, 8), (20, 16.25, 8))
    assert st.nodes_visited > 0 and st.nodes_lowered == 1
    assert 8.0 <= z.heights[80, 20] < 10.0


def test_bound_tightens_after_surfacing():
    z = ns.stock.ZMap(0, 20, 0, 20, 0.25, 10.0, 0.0)
    tool = Cutter.flat_end(4.0, 2, 0.5236)
    ys = np.arange(-1.0, 21.25, 0.5)  # stepover 0.5 mm: each row band is swept about 8 times
    starts = np.column_stack([np.full(ys.size, -3.0), ys, np.full(ys.size, 5.0)])
    ends = np.column_stack([np.full(ys.size, 23.0), ys, np.full(ys.size, 5.0)])
    ns.stock.sweep_lines(z, tool, starts, ends)
    assert z.max_height() == 5.0
    assert ns.stock.sweep_line(z, tool, (-3, 10, 6), (23, 12, 6.5)).nodes_visited == 0
    assert z.height_bound(40, 50) == 5.0  # the bands that move consulted were recomputed
