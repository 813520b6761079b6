"""Seeded 3-axis finishing programs over free-form surfaces, as CAM systems write them (for the
smoothing tests in this folder and bench/motion_family.py).

A program is the block arrays of netshape.motion (kind 0 rapid / 1 line, start, end, feed [mm/s], …).
Four strategies, each over one of four surfaces z = f(x, y) on a 60 × 60 mm patch:

- ``spiral``: an Archimedean spiral in XY from the centre out, z on the surface (moves in XYZ);
- ``raster``: zig-zag passes along X at constant Y, joined by stepover moves (moves in XZ planes);
- ``waterline``: closed contours at constant Z (moves in XY planes), a ramp down between levels;
- ``pencil``: passes along a wavy valley curve at a few offsets, z on the surface (XYZ), rapids between.

The tool path (a dense sample of the exact curve) is cut into chords the way a CAM post does it: a
vertex where the accumulated ∫√(κ / 8δ) ds reaches 1 (so each chord's sag κl²/8 is about the chord
tolerance δ), and no chord longer than `max_chord`; coordinates are rounded to 0.1 µm as written.
Seeds choose the surface, its parameters, δ ∈ [0.001, 0.01] mm and the feed ∈ [3, 15] m/min. Seeds
with ``seed % 2 == 0`` are the tuning half, odd seeds the held-out half (``family(half=...)``).
"""

from __future__ import annotations

import math

import numpy as np

STRATEGIES = ("spiral", "raster", "waterline", "pencil")
SURFACES = ("dome", "waves", "bumps", "saddle")
SIZE = 60.0  # side of the patch [mm], centred at the origin


def surface(name: str, rng: np.random.Generator):
    """z = f(x, y) [mm] of the named free-form surface with seeded parameters (vectorised)."""
    if name == "dome":
        h, r, a = rng.uniform(8, 15), rng.uniform(40, 55), rng.uniform(0.02, 0.08)
        return lambda x, y: h * (1 - (x * x + y * y) / (r * r)) + a * x
    if name == "waves":
        a, lx, ly = rng.uniform(2, 5), rng.uniform(15, 30), rng.uniform(18, 35)
        ph = rng.uniform(0, 2 * math.pi)
        return lambda x, y: a * np.sin(x / lx * math.pi + ph) * np.cos(y / ly * math.pi)
    if name == "bumps":
        c = rng.uniform(-20, 20, (3, 2))
        h, s = rng.uniform(3, 8, 3), rng.uniform(8, 15, 3)

        def f(x, y):
            z = np.zeros_like(np.asarray(x, dtype=float))
            for k in range(3):
                z = z + h[k] * np.exp(-((x - c[k, 0]) ** 2 + (y - c[k, 1]) ** 2) / (2 * s[k] ** 2))
            return z
        return f
    if name == "saddle":
        a, b = rng.uniform(0.004, 0.01), rng.uniform(0.5, 2.0)
        return lambda x, y: a * (x * x - y * y) + b * np.sin(0.08 * (x + y))
    raise ValueError(f"surface = {name!r}: must be one of {', '.join(SURFACES)}")


def chords(p: np.ndarray, tol: float, max_chord: float = 2.0) -> np.ndarray:
    """Vertices of chords through a dense polyline p (m, 3) [mm] within about `tol` [mm] of it."""
    d = np.diff(p, axis=0)
    ds = np.linalg.norm(d, axis=1)
    t = d / np.maximum(ds, 1e-12)[:, None]
    kappa = np.zeros(len(p))
    turn = np.linalg.norm(np.diff(t, axis=0), axis=1)
    kappa[1:-1] = turn / np.maximum(0.5 * (ds[:-1] + ds[1:]), 1e-12)
    rate = np.sqrt(kappa[:-1] / (8.0 * tol)) + 1.0 / max_chord  # vertices per mm
    acc = np.concatenate([[0.0], np.cumsum(rate * ds)])
    idx = np.unique(np.concatenate([[0], np.searchsorted(acc, np.arange(1.0, acc[-1], 1.0)), [len(p) - 1]]))
    return np.round(p[idx], 4)


def _pass_arrays(passes, feed: float, clearance: float) -> dict:
    """Block arrays: a rapid to above the first point, down at feed, the passes (joined by rapids over
    `clearance` when a pass does not start where the last ended), and a rapid up at the end."""
    starts, ends, kinds = [], [], []

    def move(k, a, b):
        if np.linalg.norm(b - a) > 1e-9:
            kinds.append(k), starts.append(a), ends.append(b)

    cur = np.array([passes[0][0, 0], passes[0][0, 1], clearance])
    for q in passes:
        if np.linalg.norm(q[0] - cur) > 1e-9:
            up = np.array([cur[0], cur[1], clearance])
            over = np.array([q[0, 0], q[0, 1], clearance])
            move(0, cur, up), move(0, up, over), move(1, over, q[0])
        for a, b in zip(q[:-1], q[1:]):
            move(1, a, b)
        cur = q[-1]
    move(0, cur, np.array([cur[0], cur[1], clearance]))
    n = len(kinds)
    return dict(kind=np.asarray(kinds, np.int32), start=np.asarray(starts), end=np.asarray(ends),
                center=np.zeros((n, 3)), clockwise=np.zeros(n, np.int32), plane=np.zeros(n, np.int32),
                turns=np.ones(n, np.int32), feed=np.full(n, feed))


def program(strategy: str, seed: int, scale: float = 1.0) -> tuple[dict, dict]:
    """(block arrays, description) of one seeded program; `scale` (≤ 1) shrinks the pass count and
    lengths for fast tests (1: full-size programs of a few thousand moves)."""
    if strategy not in STRATEGIES:
        raise ValueError(f"strategy = {strategy!r}: must be one of {', '.join(STRATEGIES)}")
    rng = np.random.default_rng([seed, STRATEGIES.index(strategy)])
    sname = SURFACES[int(rng.integers(len(SURFACES)))]
    f = surface(sname, rng)
    tol = float(rng.uniform(0.001, 0.01))
    feed = float(rng.uniform(3000, 15000)) / 60.0
    half = 0.5 * SIZE * scale
    step = float(rng.uniform(0.4, 1.0))  # stepover [mm]
    dense = 0.02  # sample spacing of the exact curves [mm]
    passes = []
    if strategy == "spiral":
        turns = max(2.0, half / step)
        length = 2 * math.pi * turns * (1.0 + 0.5 * step * turns)  # ∫ r dθ
        th = np.linspace(0.0, 2 * math.pi * turns, int(length / dense) + 2)
        r = 1.0 + step * th / (2 * math.pi)
        x, y = r * np.cos(th), r * np.sin(th)
        passes.append(np.column_stack([x, y, f(x, y)]))
    elif strategy == "raster":
        xs = np.linspace(-half, half, int(2 * half / dense) + 1)
        for j, yv in enumerate(np.arange(-half, half + 1e-9, step)):
            x = xs if j % 2 == 0 else xs[::-1]
            y = np.full_like(x, yv)
            pts = np.column_stack([x, y, f(x, y)])
            if passes:  # the stepover at the pass end, along the surface
                passes[-1] = np.vstack([passes[-1], pts[:1]])
                pts = pts[1:]
            passes.append(pts)
        passes = [np.vstack(passes)]
    elif strategy == "waterline":
        # contours of a radial surface r(θ, z) = R(θ)·√(1 − z/h): closed curves at constant z
        h = float(rng.uniform(8, 15))
        r0, a, k = 0.45 * SIZE * scale, rng.uniform(0.05, 0.2), int(rng.integers(2, 5))
        ph = rng.uniform(0, 2 * math.pi)
        zstep = float(rng.uniform(0.2, 0.5)) * scale
        levels = np.arange(h - zstep, 0.0, -zstep)[: max(3, int(40 * scale))]
        for z in levels:
            rr = r0 * math.sqrt(1 - z / h)
            th = np.linspace(0.0, 2 * math.pi, int(2 * math.pi * rr * 1.3 / dense) + 2)
            rad = rr * (1 + a * np.cos(k * th + ph))
            passes.append(np.column_stack([rad * np.cos(th), rad * np.sin(th), np.full_like(th, z)]))
        sname = "radial"
    else:  # pencil: passes along a wavy valley at a few offsets
        amp, lam = rng.uniform(3, 10), rng.uniform(20, 45)
        xs = np.linspace(-half, half, int(2 * half * 1.2 / dense) + 1)
        for j in range(max(2, int(8 * scale))):
            off = (j - 0.5 * max(2, int(8 * scale))) * step
            y = amp * np.sin(2 * math.pi * xs / lam) + off
            x = xs if j % 2 == 0 else xs[::-1]
            y = y if j % 2 == 0 else y[::-1]
            passes.append(np.column_stack([x, y, f(x, y)]))
    passes = [chords(q, tol) for q in passes]
    clearance = float(max(q[:, 2].max() for q in passes)) + 5.0
    desc = dict(strategy=strategy, seed=seed, surface=sname, chord_tolerance_mm=round(tol, 4),
                feed_mm_min=round(feed * 60.0), half="tune" if seed % 2 == 0 else "held-out")
    return _pass_arrays(passes, feed, clearance), desc


def family(half: str, seeds: int = 4, scale: float = 1.0):
    """The programs of one half ("tune": even seeds, "held-out": odd), `seeds` per strategy."""
    if half not in ("tune", "held-out"):
        raise ValueError(f"half = {half!r}: must be 'tune' or 'held-out'")
    first = 0 if half == "tune" else 1
    for strategy in STRATEGIES:
        for s in range(seeds):
            yield program(strategy, first + 2 * s, scale)
