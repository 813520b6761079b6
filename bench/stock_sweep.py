"""Z-map sweep benchmark (issue 3): cell updates per second of the exact C++ sweep and its ratio to
a vectorised NumPy implementation of the same exact algorithm (tests/python/stock/zmap_reference.py), measured (process CPU time, so that other load on the machine counts less)
in the same run on the same moves; and the time to sweep a 10 000-block surfacing program on a
0.1 mm grid (100 x 100 mm block = 1000 x 1000 nodes).

The C++ side sweeps the 300 moves with one `sweep_lines` call (arrays of starts and ends: a
program's straight moves in one call, no Python call per move); the NumPy reference
(`sweep_line_numpy`) is called once per move, as that is the reference algorithm.

    PYTHONPATH=python python bench/stock_sweep.py [--quick]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

import netshape as ns

# the NumPy oracle lives with the tests (tests/python/stock/zmap_reference.py)
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests" / "python" / "stock"))
from zmap_reference import sweep_line_numpy  # noqa: E402


def random_moves(n: int, rng: np.random.Generator, top: float) -> list[tuple[np.ndarray, np.ndarray]]:
    moves = []
    for _ in range(n):
        a = np.array([10 + 80 * rng.random(), 10 + 80 * rng.random(), top - 3 * rng.random()])
        ang = 2 * np.pi * rng.random()
        length = 5 + 15 * rng.random()
        b = a + [length * np.cos(ang), length * np.sin(ang), -rng.random()]
        moves.append((a, b))
    return moves


def throughput(cutter, moves, spacing: float, repeats: int = 3) -> dict:
    """Best-of-`repeats` process CPU time of the same moves on a fresh block, C++ and NumPy."""
    t_cpp = t_np = float("inf")
    for _ in range(repeats):
        z = ns.stock.ZMap(0, 100, 0, 100, spacing, 20.0, 0.0)
        ref = z.heights.copy()
        starts = np.array([a for a, _ in moves])
        ends = np.array([b for _, b in moves])
        t0 = time.process_time()
        # C++: one call for all moves; visited = the nodes of each row inside the stadium of each move
        visited = ns.stock.sweep_lines(z, cutter, starts, ends).nodes_visited
        t_cpp = min(t_cpp, time.process_time() - t0)
        t0 = time.process_time()
        visited_np = 0  # NumPy reference: every node of each move's bounding box
        for a, b in moves:
            visited_np += sweep_line_numpy(ref, z.x0, z.y0, z.dx, z.dy, z.bottom, cutter, a, b)
        t_np = min(t_np, time.process_time() - t0)
        err = float(np.max(np.abs(ref - z.heights)))
    return {
        "moves": len(moves),
        "cpp_s": t_cpp,
        "numpy_s": t_np,
        "cpp_nodes": visited,
        "numpy_nodes": visited_np,
        "cpp_node_updates_per_s": visited / t_cpp,
        "numpy_node_updates_per_s": visited_np / t_np,
        "ratio": t_np / t_cpp,
        "max_abs_diff_mm": err,
    }


def surfacing_gcode(blocks: int = 10_000, rows: int = 50, size: float = 100.0, depth: float = 1.0) -> tuple[str, int]:
    per_row = blocks // rows
    step = size / per_row
    lines = ["G21 G90 G17", "G0 X0 Y0 Z25", f"G1 Z{20 - depth:.3f} F2000"]
    n = 0
    for r in range(rows):
        y = (r + 0.5) * size / rows
        xs = np.arange(1, per_row + 1) * step
        if r % 2:
            xs = size - xs
        if r:
            lines.append(f"G1 Y{y:.4f}")  # step over (a block too: counted below)
            n += 1
        for x in xs[: per_row - (1 if r else 0)]:
            lines.append(f"G1 X{x:.4f} Y{y:.4f}")
            n += 1
    lines.append("G0 Z25")
    lines.append("M30")
    return "\n".join(lines) + "\n", n


def surfacing(cutter, spacing: float = 0.1, numpy_reference: bool = False) -> dict:
    text, n = surfacing_gcode()
    prog = ns.toolpath.parse_gcode(text, source="surfacing")
    out = {"feed_blocks": n, "program_blocks": len(prog)}
    if numpy_reference:
        # the same program block by block with the NumPy implementation of the same exact sweep
        z = ns.stock.ZMap(0, 100, 0, 100, spacing, 20.0, 0.0)
        ref = z.heights.copy()
        blocks = [(np.array(b.start), np.array(b.end)) for b in prog.blocks]
        t0 = time.process_time()
        for a, b in blocks:
            sweep_line_numpy(ref, z.x0, z.y0, z.dx, z.dy, z.bottom, cutter, a, b)
        out["numpy_per_block_s"] = time.process_time() - t0
        ns.stock.sweep(z, cutter, prog)
        out["numpy_max_abs_diff_mm"] = float(np.max(np.abs(ref - z.heights)))
    for merge in (False, True):
        z = ns.stock.ZMap(0, 100, 0, 100, spacing, 20.0, 0.0)
        opt = ns.stock.SweepOptions()
        opt.merge_collinear = merge
        t0 = time.process_time()
        st = ns.stock.sweep(z, cutter, prog, opt)
        dt = time.process_time() - t0
        key = "merged" if merge else "per_block"
        out[f"{key}_s"] = dt
        out[f"{key}_moves"] = st.moves
        out[f"{key}_node_updates_per_s"] = st.nodes_visited / dt
        out["grid"] = f"{z.ny}x{z.nx}"
        out[f"{key}_removed_mm3"] = st.removed_volume
    return out


def main(argv=None) -> dict:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="fewer moves (a smoke run)")
    p.add_argument("--repeats", type=int, default=3, help="best of this many runs (CPU time)")
    p.add_argument("--no-numpy-program", action="store_true", help="skip the NumPy run of the 10 000-block program")
    args = p.parse_args(argv)
    results: dict = {}
    rng = np.random.default_rng(0)
    n = 40 if args.quick else 300
    moves = random_moves(n, rng, 20.0)
    print("Z-map exact sweep, 0.1 mm grid, random 3-D lines of 5-20 mm (C++ sweep_lines, one call, vs NumPy "
          "per move, same algorithm); "
          f"load average {os.getloadavg()[0]:.1f}")
    for name, cutter in [("flat D10", ns.stock.Cutter.flat_end(10.0, 2, 0.5236)), ("ball D10", ns.stock.Cutter.ball_end(10.0, 2, 0.5236)),
                         ("bull D10 r2", ns.stock.Cutter.bull_nose(10.0, 2.0, 2, 0.5236))]:
        r = throughput(cutter, moves, 0.1, repeats=args.repeats)
        results[f"ramps {name}"] = r
        print(f"  {name:12s} C++ {r['cpp_node_updates_per_s'] / 1e6:7.1f} M node updates/s (stadium rows)  "
              f"NumPy {r['numpy_node_updates_per_s'] / 1e6:6.1f} M/s (bounding box, {r['numpy_nodes'] / r['cpp_nodes']:.2f}x the nodes)  "
              f"time ratio {r['ratio']:6.1f}x  (CPU best of {args.repeats}: C++ {r['cpp_s']:.3f} s, NumPy {r['numpy_s']:.3f} s, "
              f"max |diff| {r['max_abs_diff_mm']:.1e} mm)", flush=True)
    # the same moves lifted to 5 mm above the block: the quick reject returns before visiting any row
    z = ns.stock.ZMap(0, 100, 0, 100, 0.1, 20.0, 0.0)
    starts = np.array([a for a, _ in moves]) + [0.0, 0.0, 5.0 + 3.0]
    ends = np.array([b for _, b in moves]) + [0.0, 0.0, 5.0 + 4.0]
    ball = ns.stock.Cutter.ball_end(10.0, 2, 0.5236)
    t_batch = t_one = float("inf")
    for _ in range(args.repeats):
        t0 = time.process_time()
        st = ns.stock.sweep_lines(z, ball, starts, ends)
        t_batch = min(t_batch, time.process_time() - t0)
        t0 = time.process_time()
        for a, b in zip(starts, ends):
            ns.stock.sweep_line(z, ball, a, b)
        t_one = min(t_one, time.process_time() - t0)
    print(f"  moves >= 5 mm above the stock (ball D10, {len(moves)} moves): {t_batch / len(moves) * 1e6:.2f} us per move "
          f"in one sweep_lines call, {t_one / len(moves) * 1e6:.2f} us per sweep_line call; nodes visited {st.nodes_visited}")
    if args.quick:
        return results
    print("10 000-block raster surfacing program (G1 0.5 mm blocks, 50 rows, stepover 2 mm), 100 x 100 mm, 0.1 mm grid")
    for name, cutter in [("ball D10", ns.stock.Cutter.ball_end(10.0, 2, 0.5236)), ("flat D10", ns.stock.Cutter.flat_end(10.0, 2, 0.5236))]:
        r = surfacing(cutter, numpy_reference=not args.no_numpy_program)
        results[f"surfacing {name}"] = r
        print(f"  {name:9s} grid {r['grid']}, {r['feed_blocks']} feed blocks: per block {r['per_block_s']:.3f} s "
              f"({r['per_block_node_updates_per_s'] / 1e6:.0f} M node updates/s); collinear runs merged "
              f"{r['merged_s']:.3f} s ({r['merged_moves']} moves)")
        if "numpy_per_block_s" in r:
            print(f"  {'':9s} NumPy reference block by block {r['numpy_per_block_s']:.2f} s: ratio "
                  f"{r['numpy_per_block_s'] / r['per_block_s']:.1f}x per block, "
                  f"{r['numpy_per_block_s'] / r['merged_s']:.0f}x with merging "
                  f"(max |diff| {r['numpy_max_abs_diff_mm']:.1e} mm)")
    return results


if __name__ == "__main__":
    main()
