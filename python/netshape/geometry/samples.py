"""Reproducible sample surfaces for tests, benchmarks and examples."""

from __future__ import annotations

import numpy as np

from .._core import geometry as _g


def random_surface(
    rng: np.random.Generator | int,
    degree_u: int = 3,
    degree_v: int = 3,
    count_u: int = 12,
    count_v: int = 12,
) -> _g.NurbsSurface:
    """A random rational NURBS surface over about [0, count_u) × [0, count_v) × [-1, 1] [mm].

    Clamped knot vectors with sorted random interior knots, a control net jittered by ±0.3 mm in x and
    y around the integer grid with random heights in [-1, 1] mm, and weights in [0.5, 2]: the same
    ``rng`` (a ``numpy.random.Generator`` or a seed) gives the same surface.
    """
    if not isinstance(rng, np.random.Generator):
        rng = np.random.default_rng(rng)
    for name, count, degree in (("count_u", count_u, degree_u), ("count_v", count_v, degree_v)):
        if degree < 1 or count <= degree:
            raise ValueError(f"{name} = {count}: needs more control points than the degree ({degree}) and degree >= 1")

    def knots(count: int, degree: int) -> np.ndarray:
        inner = np.sort(rng.uniform(0.05, 0.95, count - degree - 1))
        return np.concatenate([np.zeros(degree + 1), inner, np.ones(degree + 1)])

    ku, kv = knots(count_u, degree_u), knots(count_v, degree_v)
    grid = np.stack(np.meshgrid(np.arange(count_u), np.arange(count_v), indexing="ij"), -1)
    xy = grid.reshape(-1, 2).astype(float)
    cp = np.hstack([xy + rng.uniform(-0.3, 0.3, xy.shape), rng.uniform(-1.0, 1.0, (count_u * count_v, 1))])
    w = rng.uniform(0.5, 2.0, count_u * count_v)
    return _g.NurbsSurface(degree_u, degree_v, ku, kv, cp, w)
