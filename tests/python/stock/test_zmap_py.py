"""Z-map from Python: heights round trip and views, bad input, sweeps against the NumPy reference,
program sweeps from G-code, STL export re-read, plots."""

from __future__ import annotations

import math

import numpy as np
import pytest

import netshape as ns
from zmap_reference import sweep_line_numpy

Cutter = ns.stock.Cutter


def test_heights_round_trip_and_live_view():
    rng = np.random.default_rng(1)
    h = 5.0 + rng.random((7, 9))
    z = ns.stock.from_heights(h, 0.0, 9.0, -1.0, 6.0, bottom=0.0)
    assert (z.ny, z.nx) == (7, 9)
    assert z.dx == pytest.approx(1.0) and z.dy == pytest.approx(1.0)
    np.testing.assert_array_equal(z.heights, h)
    v = z.heights
    assert not v.flags.writeable
    with pytest.raises(ValueError):
        v[0, 0] = 1.0
    # zero copy: two views share the ZMap's memory, and a view follows later sweeps
    assert np.shares_memory(v, z.heights)
    ns.stock.sweep_line(z, Cutter.flat_end(2.0, 2, 0.5236), (-1, 2.5, 4.0), (10, 2.5, 4.0))
    assert v.min() == 4.0
    snap = z.heights.copy()
    z2 = ns.stock.from_heights(snap, 0.0, 9.0, -1.0, 6.0, bottom=0.0)
    np.testing.assert_array_equal(z2.heights, z.heights)
    xs, ys = ns.stock.node_coordinates(z)
    assert xs[0] == pytest.approx(0.5) and ys[-1] == pytest.approx(5.5)
    assert z.height_at(xs[3], ys[2]) == pytest.approx(z.heights[2, 3])
    pts = np.column_stack([xs[:5], np.full(5, ys[1]), np.full(5, 4.5)])
    np.testing.assert_array_equal(z.is_material_points(pts), z.heights[1, :5] > 4.5)


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: ns.stock.ZMap(0, 10, 0, 10, 0.0, 1, 0), "zmap.spacing"),
        (lambda: ns.stock.ZMap(0, 10, 0, 10, float("nan"), 1, 0), "zmap.spacing"),
        (lambda: ns.stock.ZMap(0, 1000, 0, 1000, 1e-4, 1, 0), "too many grid nodes"),
        (lambda: ns.stock.ZMap(0, 10, 0, 10, 0.1, 1, 2), "zmap.bottom"),
        (lambda: ns.stock.from_heights(np.full((3, 3), np.inf), 0, 1, 0, 1, 0), "zmap.heights"),
        (lambda: ns.stock.from_heights(np.ones(3), 0, 1, 0, 1, 0), "heights.ndim"),
        (lambda: ns.stock.sweep_line(ns.stock.ZMap(0, 1, 0, 1, 0.1, 1, 0), Cutter.flat_end(2.0, 2, 0.5236),
                                     (0, 0, float("nan")), (1, 1, 1)), "line.start"),
        (lambda: ns.stock.engaged_elements(ns.stock.ZMap(0, 1, 0, 1, 0.1, 1, 0), Cutter.flat_end(2.0, 2, 0.5236),
                                           (0, 0, 0), (0, 0, 1), np.zeros(2), np.zeros(2)), "feed_direction"),
    ],
)
def test_bad_input_names_the_field(call, field):
    with pytest.raises(ValueError, match=field):
        call()


@pytest.mark.parametrize("make", [lambda: Cutter.flat_end(6.0, 2, 0.5236), lambda: Cutter.ball_end(6.0, 2, 0.5236),
                                  lambda: Cutter.bull_nose(6.0, 1.0, 2, 0.5236)])
def test_cpp_sweep_equals_numpy_reference(make):
    cutter = make()
    rng = np.random.default_rng(3)
    z = ns.stock.ZMap(0, 30, 0, 25, 0.1, 10.0, 0.0)
    ref = z.heights.copy()
    for k in range(25):
        a = np.array([30 * rng.random(), 25 * rng.random(), 4 + 6 * rng.random()])
        b = np.array([30 * rng.random(), 25 * rng.random(), 4 + 6 * rng.random()])
        if k % 5 == 0:
            b[:2] = a[:2]  # plunge
        if k % 5 == 1:
            b[2] = a[2]  # horizontal
        ns.stock.sweep_line(z, cutter, a, b)
        sweep_line_numpy(ref, z.x0, z.y0, z.dx, z.dy, z.bottom, cutter, a, b)
    assert np.max(np.abs(z.heights - ref)) <= 1e-12


GCODE = """G21 G90 G17
G0 X-8 Y10 Z12
G1 Z7 F600
G1 X10 Y10
G2 X20 Y10 I5 J0
G3 X30 Y10 Z6 I5 J0
G1 X48
G0 Z12
M30
"""


def test_program_sweep_from_gcode_and_stl_export(tmp_path):
    prog = ns.toolpath.parse_gcode(GCODE)
    # the reader starts at the origin: keep the block clear of the first rapid from (0, 0, 0)
    z = ns.stock.ZMap(5, 45, 0, 20, 0.1, 10.0, 2.0)
    tool = Cutter.ball_end(6.0, 2, 0.5236)
    st = ns.stock.sweep(z, tool, prog)
    assert st.rapids_cutting == 0 and st.nodes_lowered > 0
    v0 = 40 * 20 * 8.0
    assert z.volume() == pytest.approx(v0 - st.removed_volume, rel=1e-12)
    # the G2 half circle (centre (15, 10), r = 5, clockwise from (10,10) to (20,10)) passes y = 15 at x = 15
    assert z.cell_height(15.0, 15.0) == pytest.approx(7.0, abs=0.01)
    # the bottom of the lower half of the ball at the start of the G1 X10 line
    # (the node of that cell is at (8.05, 10.05): 0.05 mm off the path)
    assert z.cell_height(8.0, 10.0) == pytest.approx(7.0 + 3.0 - math.sqrt(9.0 - 0.05**2), abs=1e-12)

    path = tmp_path / "zmap.stl"
    z.to_stl(path)
    normals, tris = ns.stock.read_stl(path)
    assert len(tris) == ns.stock.stl_triangle_count(z) == 2 * 399 * 199 + 6 * (399 + 199)
    lo, hi = tris.reshape(-1, 3).min(axis=0), tris.reshape(-1, 3).max(axis=0)
    np.testing.assert_allclose(lo, [5.05, 0.05, 2.0], atol=1e-5)
    np.testing.assert_allclose(hi, [44.95, 19.95, 10.0], atol=1e-5)
    # closed: every directed edge appears once and its reverse once
    v = tris.reshape(-1, 3)
    _, inv = np.unique(v, axis=0, return_inverse=True)
    ids = inv.reshape(-1, 3)
    e = np.concatenate([ids[:, [0, 1]], ids[:, [1, 2]], ids[:, [2, 0]]])
    key = e[:, 0].astype(np.int64) * (ids.max() + 1) + e[:, 1]
    rkey = e[:, 1].astype(np.int64) * (ids.max() + 1) + e[:, 0]
    assert len(np.unique(key)) == len(key)
    assert np.all(np.isin(rkey, key))
    # outward: the divergence theorem gives the (positive) enclosed volume, close to the Z-map's
    a, b, c = tris[:, 0].astype(float), tris[:, 1].astype(float), tris[:, 2].astype(float)
    vol = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0
    # the solid under the two triangles per grid square, from node to node
    h = z.heights - z.bottom
    h00, h01, h10, h11 = h[:-1, :-1], h[:-1, 1:], h[1:, :-1], h[1:, 1:]
    expect = (z.dx * z.dy / 6.0) * np.sum(2 * h00 + h01 + 2 * h11 + h10)
    assert vol == pytest.approx(expect, rel=1e-5)

    # atomic: a missing folder is an error and leaves nothing behind
    with pytest.raises(ValueError, match="folder"):
        z.to_stl(tmp_path / "missing" / "x.stl")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["zmap.stl"]


def test_plot_returns_a_figure():
    z = ns.stock.ZMap(0, 20, 0, 10, 0.2, 5.0, 0.0)
    ns.stock.sweep_line(z, Cutter.ball_end(4.0, 2, 0.5236), (-3, 5, 3.5), (23, 5, 3.5))
    fig = z.plot(title="slot")
    assert fig.axes[0].get_title() == "slot"
    assert math.isclose(fig.axes[0].images[0].get_array().min(), z.min_height())
    assert z.min_height() == pytest.approx(3.5 + 2 - math.sqrt(4 - 0.1**2))  # nodes 0.1 mm off the path
