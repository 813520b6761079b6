"""The test programs of Lee & Lee §4, rebuilt from the paper's text (the figures give no coordinates).

Reconstruction (stated in docs/motion.md):
- Fig. 12: four 20 mm single-axis blocks at right angles (a square: +X, +Y, −X, −Y), F5000 mm/min,
  allowable speed difference 100 mm/min.
- Fig. 13–15: two long blocks, three semicircles of radii 30, 10 and 5 mm each split into chords of
  about 0.025 mm chordal error (39 + 22 + 16 = 77 micro-blocks), then a third long block; F4000 mm/min.
  With eq. 4 the corner feed of a semicircle of n chords is Acc·Ts/(1 − cos(π/n)); the printed
  ~3000(3200), ~1100 and ~550 mm/min fix Acc·Ts1 ≈ 0.18 mm/s. We take Ts1 = 0.4 ms, Ts2 = 0.1 ms and
  Acc = 450 mm/s² (Acc·Ts1 = 0.18 mm/s), which also lets the 20 mm blocks of Fig. 12 reach F5000.
"""

from __future__ import annotations

import numpy as np

#: reconstructed machine and loop constants of Lee & Lee §4
ACC = 450.0          # [mm/s^2], every axis
TS1 = 4e-4           # rough loop period [s]
TS2 = 1e-4           # fine loop period [s]
ALLOWABLE = 100.0 / 60.0  # allowable speed difference [mm/s]
RADII = (30.0, 10.0, 5.0)  # [mm]
CHORDS = (39, 22, 16)      # chords per semicircle (77 in all)


def square_program() -> np.ndarray:
    """(5, 3) corner points of the Fig. 12 path: four 20 mm blocks at right angles [mm]."""
    return np.array([[0, 0, 0], [20, 0, 0], [20, 20, 0], [0, 20, 0], [0, 0, 0]], dtype=float)


def semicircle_program() -> np.ndarray:
    """(81, 3) points of the Fig. 13 path: 2 long blocks, 3 chorded semicircles (77 chords), 1 long block."""
    pts = [np.array([0.0, 40.0, 0.0]), np.array([0.0, 0.0, 0.0]), np.array([40.0, 0.0, 0.0])]
    x0 = 40.0
    up = True
    for r, n in zip(RADII, CHORDS):
        c = x0 + r
        # over the top (clockwise, +Y first) then under (counter-clockwise, −Y first), alternating
        ang = np.linspace(np.pi, 0.0, n + 1)[1:]
        ys = r * np.sin(ang) * (1 if up else -1)
        for a, y in zip(ang, ys):
            pts.append(np.array([c + r * np.cos(a), y, 0.0]))
        x0 = c + r
        up = not up
    pts.append(np.array([x0, 40.0 if not up else -40.0, 0.0]))
    return np.array(pts)
