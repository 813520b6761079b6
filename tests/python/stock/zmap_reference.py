"""A vectorised NumPy implementation of the exact line sweep, the same algorithm as the C++ kernel
(netshape::stock::sweep_line): per node, the foot point τ_q and distance s from the line, the
feasible travel σ ∈ [max(0, τ_q − ρ), min(L, τ_q + ρ)] with ρ = sqrt(R² − s²), then

- flat: z = A_z + m·(lo if m ≥ 0 else hi)
- ball: σ* = clamp(τ_q − m·ρ/sqrt(1 + m²)), z = A_z + m·σ* + R − sqrt(ρ² − (σ* − τ_q)²)
- bull: ramps: bisection on the derivative (vectorised).
- horizontal moves (all cutters): the point of the segment nearest to the node, d² = s² + (τ_q − clamp(τ_q, 0, L))².

It exists to cross-check the C++ kernel and to measure its speed-up (bench/stock_sweep.py); use the
C++ functions in netshape.stock for work. A test oracle: it ships with the tests, not in the package.
"""

from __future__ import annotations

import numpy as np


def _profile(cutter):
    from netshape.stock import TipProfile

    p = TipProfile.of(cutter)
    R, rc, a = float(p.radius), float(p.corner_radius), float(p.flat_radius)
    kind = "flat" if rc == 0.0 else ("ball" if a <= 0.0 else "bull")
    return R, rc, a, kind


def _lift(d, R, rc, a):
    u = np.maximum(np.minimum(d, R) - a, 0.0)
    return np.where(u > 0.0, rc - np.sqrt(np.maximum(rc * rc - u * u, 0.0)), 0.0)


def sweep_line_numpy(heights: np.ndarray, x0: float, y0: float, dx: float, dy: float, bottom: float,
                     cutter, a, b) -> int:
    """Sweep the line a → b over ``heights`` (ny, nx) in place; returns the number of nodes visited."""
    R, rc, fr, kind = _profile(cutter)
    ny, nx = heights.shape
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    lo_x, hi_x = min(a[0], b[0]) - R, max(a[0], b[0]) + R
    lo_y, hi_y = min(a[1], b[1]) - R, max(a[1], b[1]) + R
    j0 = max(int(np.ceil((lo_x - x0) / dx - 0.5)), 0)
    j1 = min(int(np.floor((hi_x - x0) / dx - 0.5)), nx - 1)
    i0 = max(int(np.ceil((lo_y - y0) / dy - 0.5)), 0)
    i1 = min(int(np.floor((hi_y - y0) / dy - 0.5)), ny - 1)
    if j0 > j1 or i0 > i1:
        return 0
    xs = x0 + (np.arange(j0, j1 + 1) + 0.5) * dx
    ys = y0 + (np.arange(i0, i1 + 1) + 0.5) * dy
    qx = xs[None, :] - a[0]
    qy = ys[:, None] - a[1]
    hx, hy = b[0] - a[0], b[1] - a[1]
    L = float(np.hypot(hx, hy))
    if L <= 1e-9:
        d = np.sqrt(qx * qx + qy * qy)
        z = min(a[2], b[2]) + _lift(d, R, rc, fr)
        z = np.where(d <= R, z, np.inf)
    else:
        ex, ey = hx / L, hy / L
        m = (b[2] - a[2]) / L
        tq = qx * ex + qy * ey
        sp = qy * ex - qx * ey
        if m == 0.0:
            # horizontal move: the lowest reach is at the point of the segment nearest to the node
            u = tq - np.clip(tq, 0.0, L)
            d2 = sp * sp + u * u
            if kind == "flat":
                z = np.full(d2.shape, a[2])
            elif kind == "ball":
                z = a[2] + R - np.sqrt(np.maximum(R * R - d2, 0.0))
            else:
                z = a[2] + _lift(np.sqrt(d2), R, rc, fr)
            z = np.where(d2 <= R * R, z, np.inf)
            block = heights[i0 : i1 + 1, j0 : j1 + 1]
            np.minimum(block, np.maximum(z, bottom), out=block)
            return block.size
        rho2 = R * R - sp * sp
        ok = rho2 >= 0.0
        rho = np.sqrt(np.maximum(rho2, 0.0))
        lo = np.maximum(0.0, tq - rho)
        hi = np.minimum(L, tq + rho)
        ok &= lo <= hi
        if kind == "flat":
            z = a[2] + m * (lo if m >= 0.0 else hi)
        elif kind == "ball":
            sig = np.clip(tq - m / np.sqrt(1.0 + m * m) * rho, lo, hi)
            u = sig - tq
            z = a[2] + m * sig + R - np.sqrt(np.maximum(rho2 - u * u, 0.0))
        else:
            if m == 0.0:
                sig = np.clip(tq, lo, hi)
            else:
                sp2 = sp * sp

                def dfdx(s):
                    u = s - tq
                    d = np.sqrt(sp2 + u * u)
                    w = rc * rc - (d - fr) ** 2
                    with np.errstate(divide="ignore", invalid="ignore"):
                        gs = np.where(d <= fr, 0.0, np.where(w > 0, (d - fr) / np.sqrt(np.maximum(w, 1e-300)), np.inf))
                        out = m + np.where(gs == 0.0, 0.0, gs * u / np.where(d > 0, d, 1.0))
                    out = np.where(np.isinf(gs), np.where(u > 0, np.inf, np.where(u < 0, -np.inf, m)), out)
                    return out

                s_lo, s_hi = lo.copy(), hi.copy()
                for _ in range(45):
                    mid = 0.5 * (s_lo + s_hi)
                    neg = dfdx(mid) < 0.0
                    s_lo = np.where(neg, mid, s_lo)
                    s_hi = np.where(neg, s_hi, mid)
                sig = np.where(dfdx(lo) >= 0.0, lo, np.where(dfdx(hi) <= 0.0, hi, 0.5 * (s_lo + s_hi)))
            u = sig - tq
            z = a[2] + m * sig + _lift(np.sqrt(sp * sp + u * u), R, rc, fr)
        z = np.where(ok, z, np.inf)
    block = heights[i0 : i1 + 1, j0 : j1 + 1]
    np.minimum(block, np.maximum(z, bottom), out=block)
    return block.size
