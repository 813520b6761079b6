"""Force element evaluations per second: netshape's C++ flat end mill model (linear edge forces,
helical disks, angular engagement window) against a vectorised NumPy implementation of the same
model, in the same run. Prints the rates and the ratio (target ≥ 20×), then, for information, the
C++ rates of the other kernels (Kline–DeVor coefficients, engagement from a map, ball end mill).

Times are CPU times (time.process_time), best of --repeat runs. Both implementations evaluate
every element at every angle (no element is skipped), so the rates are per-element rates."""

from __future__ import annotations

import argparse
import math
import os
import time

import numpy as np

import netshape.force as nf


def numpy_forces(angles, R, N, beta, ap, dz, c, k, st, ex):
    """The same model in NumPy, vectorised over angles × elements."""
    n = max(1, int(math.ceil(ap / dz - 1e-9)))
    dz = ap / n
    z = (np.arange(n) + 0.5) * dz
    off = (np.arange(N)[None, :] * 2 * math.pi / N - math.tan(beta) / R * z[:, None]).ravel()
    phi = angles[:, None] + off[None, :]
    w = np.mod(phi - st, 2 * math.pi) <= (ex - st)
    s, co = np.sin(phi), np.cos(phi)
    h = np.maximum(c * s, 0.0)
    ft = (k["ktc"] * h + k["kte"]) * dz * w
    fr = (k["krc"] * h + k["kre"]) * dz * w
    fa = (k["kac"] * h + k["kae"]) * dz * w
    return np.column_stack([(-ft * co - fr * s).sum(1), (ft * s - fr * co).sum(1), fa.sum(1)])


def best_of(fn, repeat):
    """Smallest CPU time [s] of `repeat` calls of fn."""
    best = float("inf")
    for _ in range(repeat):
        t0 = time.process_time()
        fn()
        best = min(best, time.process_time() - t0)
    return best


def cpu_has_avx2() -> bool:
    try:
        with open("/proc/cpuinfo") as f:
            return " avx2" in f.read()
    except OSError:
        return False


def main(argv=None) -> dict:
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--angles", type=int, default=3600)
    p.add_argument("--dz", type=float, default=0.02)
    p.add_argument("--repeat", type=int, default=7)
    a = p.parse_args(argv)
    k = dict(ktc=958.8, krc=251.1, kac=146.4, kte=15.8, kre=19.4, kae=18.2)
    R, N, beta, ap, c = 5.0, 4, math.radians(30), 5.0, 0.1
    e = nf.AngularEngagement.from_mode(nf.MillingMode.down, R, 3.0)
    model = nf.FlatEndModel(radius=R, flutes=N, helix=beta, axial_depth=ap, feed_per_tooth=c, engagement=e,
                            linear_edge=nf.LinearEdgeCoefficients(**k), disk_height=a.dz)
    ws = nf.FlatEndWorkspace(model)
    th = nf.rotation_angles(a.angles, 2.0)
    evals = a.angles * ws.elements()
    ref = numpy_forces(th, R, N, beta, ap, a.dz, c, k, e.phi_st, e.phi_ex)
    got = nf.flat_end_forces(model, th, ws)
    err = float(np.abs(ref - got).max() / np.abs(ref).max())
    # interleave the two so that a load change on the shared machine hits both alike
    t_c = t_n = float("inf")
    for _ in range(a.repeat):
        t_c = min(t_c, best_of(lambda: nf.flat_end_forces(model, th, ws), 1))
        t_n = min(t_n, best_of(lambda: numpy_forces(th, R, N, beta, ap, a.dz, c, k, e.phi_st, e.phi_ex), 1))
    out = {"elements": ws.elements(), "angles": a.angles, "cpp_evals_per_s": evals / t_c,
           "numpy_evals_per_s": evals / t_n, "ratio": t_n / t_c, "max_rel_diff": err}

    # the other kernels, C++ only (same element counts)
    kd = nf.FlatEndModel(radius=R, flutes=N, helix=beta, axial_depth=ap, feed_per_tooth=c, engagement=e,
                         coefficient_model=nf.FlatCoefficientModel.kline_devor,
                         kline_devor=nf.KlineDevorCoefficients(kt=800.0, kr=0.3), disk_height=a.dz)
    emap = nf.EngagementMap.from_window(e, ws.disks(), 3600)
    t_kd = best_of(lambda: nf.flat_end_forces(kd, th, ws), a.repeat)
    t_map = best_of(lambda: nf.flat_end_forces(model, th, ws, emap), a.repeat)
    ball = nf.BallEndModel(radius=R, flutes=2, axial_depth=3.0, feed_per_tooth=c,
                           engagement=nf.AngularEngagement.from_mode(nf.MillingMode.slot, R, 2 * R))
    bws = nf.BallEndWorkspace(ball)
    t_ball = best_of(lambda: nf.ball_end_forces(ball, th, bws), a.repeat)
    ball_evals = a.angles * bws.rows() * ball.flutes
    out.update(kline_devor_evals_per_s=evals / t_kd, map_evals_per_s=evals / t_map,
               ball_evals_per_s=ball_evals / t_ball)

    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"force element evaluations: {ws.elements()} elements x {a.angles} angles, CPU time, best of "
          f"{a.repeat} (load average {load:.2f}, CPU AVX2: {'yes' if cpu_has_avx2() else 'no'})")
    print(f"  netshape C++ : {out['cpp_evals_per_s'] / 1e6:8.1f} M evals/s")
    print(f"  NumPy        : {out['numpy_evals_per_s'] / 1e6:8.1f} M evals/s")
    print(f"  ratio        : {out['ratio']:8.1f} x   (same forces within {err:.1e}; target >= 20 x)")
    print("  other C++ kernels (every element evaluated):")
    print(f"    Kline-DeVor coefficients    : {out['kline_devor_evals_per_s'] / 1e6:8.1f} M evals/s")
    print(f"    engagement from a map       : {out['map_evals_per_s'] / 1e6:8.1f} M evals/s")
    print(f"    ball end ({bws.rows()} rows x {ball.flutes} flutes, slot): "
          f"{out['ball_evals_per_s'] / 1e6:8.1f} M evals/s")
    return out


if __name__ == "__main__":
    main()
