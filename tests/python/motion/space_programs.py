"""Seeded runs in space for rule `smooth` (issue 39 item 2): helices, conical and spherical spirals of
micro-segments in no coordinate plane, with a feed and a tolerance each. Shared by
test_smooth_space_family.py and bench/motion_space_family.py; anything tuned on them is tuned on even
seeds, and odd seeds are the ones reported."""

from __future__ import annotations

import numpy as np

import netshape.motion as nm

KINDS = ("helix", "cone", "sphere")


def space_program(seed: int, max_points: int = 400):
    """Program arrays and a description for member `seed`: radius 2–50 mm, pitch 0.01–0.5 mm per
    radian, moves 0.1–2 mm long (at most max_points points), feed 50–250 mm/s, ε 0.003–0.03 mm
    (log-uniform), coordinates rounded to 1 µm on every other member (as CAM output is)."""
    rng = np.random.default_rng(seed)
    kind = KINDS[seed % len(KINDS)]
    r = float(np.exp(rng.uniform(np.log(2.0), np.log(50.0))))
    pitch = float(np.exp(rng.uniform(np.log(0.01), np.log(0.5))))
    step = float(np.exp(rng.uniform(np.log(0.1), np.log(2.0))))  # move length [mm]
    feed = float(rng.uniform(50.0, 250.0))
    eps = float(np.exp(rng.uniform(np.log(0.003), np.log(0.03))))
    turns = float(rng.uniform(0.5, 3.0))
    dth = step / r
    n = int(min(max_points, max(8, turns * 2 * np.pi / dth)))
    t = np.arange(n) * dth
    if kind == "helix":
        rad, z = np.full(n, r), pitch * t
    elif kind == "cone":  # radius shrinking by up to half over the run
        rad, z = r * (1.0 - 0.5 * t / max(t[-1], 1e-9)), pitch * t
    else:  # on a sphere of radius r, from its equator up
        phi = np.minimum(pitch * t / r, 1.2)
        rad, z = r * np.cos(phi), r * np.sin(phi)
    pts = np.column_stack([rad * np.cos(t), rad * np.sin(t), z])
    if seed % 2:
        pts = np.round(pts, 3)
    desc = f"{kind} s{seed}: r {r:.2f} pitch {pitch:.3f} step {step:.2f} n {n} feed {feed:.0f} eps {eps:.4f}"
    return nm.polyline_arrays(pts, feed), eps, desc
