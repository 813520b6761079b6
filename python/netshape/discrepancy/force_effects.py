"""Cutting-force bundles: the linear edge-force model of netshape.force, extended by the catalogue
entries ``runout``, ``edge_forces``, ``size_effect`` and ``structural_mode``.

Evaluation. Every force is computed by the C++ flat end-mill kernel (``flat_end_forces``) on a
uniform grid of M = 512 rotation angles over one revolution and read at the measured angles by periodic
linear interpolation (the steady-state force is 2π-periodic in the angle θ of flute 1 at the tip).
The extensions are written as sums of kernel calls with the linear edge model:

* runout (axis offset ρ at angle λ): flute j (0 … N−1, flute 1 = j 0) cuts at radius
  R_j = R + ρ·cos(λ − j·2π/N) and removes the chip h_j = c·sin φ + R_j − R_{j−1}, clamped at 0.
  With Δ_j = R_j − R_{j−1}: where h_j > 0 the element forces are those of the linear model with edge
  coefficients K_e + Δ_j·K_c, and h_j > 0 ⇔ sin φ > −Δ_j/c. So flute j alone is one kernel call with
  one flute, the angle θ + j·2π/N, the window narrowed to sin φ ≥ −Δ_j/c and those coefficients.
* size effect: the cutting terms follow g(h) = h_ref·(h/h_ref)^p instead of h (p = 1: the linear
  model; p < 1: thin chips cut relatively harder). g is written as its piecewise-linear interpolant
  over knots h_k, Σ_k w_k·max(0, h − h_k), and each max(0, h − h_k) term is again one kernel call
  (window sin φ ≥ (h_k − Δ_j)/c, edge coefficients −(h_k − Δ_j)·K_c). h_ref is the geometric mean of
  the bundle's feeds per tooth (at h_ref the linear model is unchanged).
* structural mode (tool or dynamometer, natural frequency f_n, damping ratio ζ): the measured force
  is the cutting force through H(ω) = ω_n²/(ω_n² − ω² + 2iζω_nω) (unit static gain), applied to each
  harmonic k of the revolution (ω = k·Ω): the periodic steady state, exact.
* edge forces: K_te, K_re, K_ae refitted.

Time series (``time_s``): θ(t) = θ0 + Ω·t. Ω comes from the recording's spectrum (tooth-passing
harmonics, ±3 % around the manifest's spindle_rpm) when it spans ≥ 20 revolutions, else from
spindle_rpm; θ0, the angle of flute 1 at t = 0, is a nuisance parameter found by circular
cross-correlation with the model and refitted with every effect. Which physical flute is "1" cannot
be known from a recording without a spindle encoder: θ0 and the runout angle λ are reported for the
flute the fit calls 1.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from netshape._core import force as _f

from .problem import Problem, robust_difference_noise

GRID = 512  # angles per revolution of the model grid
_KNOTS = np.array([0.0, 0.006, 0.02, 0.05, 0.1, 0.18, 0.3, 0.45, 0.62, 0.8, 1.0])


@dataclass(frozen=True)
class ForceSpec:
    """A cutting-force model: coefficients (6,) [N/mm², N/mm] in the order Ktc Krc Kac Kte Kre Kae;
    runout (ρ [mm], λ [rad]) or None; chip exponent p or None; mode (f_n [Hz], ζ) or None; phases
    (θ0 [rad] per experiment, 0 for angle-based ones); additive terms (callables
    (experiment, angles (n,) [rad]) → (n, 3) [N])."""

    coefficients: tuple
    runout: tuple | None = None
    chip_exponent: float | None = None
    mode: tuple | None = None
    phases: tuple = ()
    additive: tuple = ()

    def key(self):
        return (self.coefficients, self.runout, self.chip_exponent, self.mode)


def _window(base, s: float):
    """base window ∩ {sin φ ≥ s} (φ in [0, π]) as (st, ex), or None when empty."""
    st, ex = base
    if s >= 1.0:
        return None
    if s > 0.0:
        a = math.asin(s)
        st, ex = max(st, a), min(ex, math.pi - a)
    return (st, ex) if ex > st else None


class ForceProblem(Problem):
    kind = "cutting_force"
    unit = "N"

    def __init__(self, bundle):
        tool = bundle.tool
        if tool["type"] != "flat":
            raise ValueError(
                f"{bundle.path}: [tool] type = {tool['type']!r}: the cutting_force workflow "
                "models flat end mills (the linear edge model); ball end mills are not supported"
            )
        self.bundle = bundle
        self.experiments = bundle.experiments
        self.measured = [np.asarray(e.forces, float) for e in self.experiments]
        self.flutes = int(tool["flutes"])
        self.radius = 0.5 * tool["diameter"]
        self.helix = tool["helix"]
        self.grid = 2.0 * math.pi * np.arange(GRID) / GRID
        self.h_ref = float(bundle.model.get("reference_chip_mm")
                           or np.exp(np.mean(np.log([e.feed_per_tooth for e in self.experiments]))))
        self._windows, self._models, self._ws = [], [], []
        for e in self.experiments:
            eng = _f.AngularEngagement.from_mode(
                _f.milling_mode_from_string(e.mode),
                self.radius,
                float(e.radial_depth) if e.mode != "slot" else 0.0,
            )
            self._windows.append((eng.phi_st, eng.phi_ex))
            dz = min(0.05, e.axial_depth / 30.0)
            pair = []
            for n in (self.flutes, 1):
                m = _f.FlatEndModel(
                    radius=self.radius,
                    flutes=n,
                    helix=self.helix,
                    axial_depth=e.axial_depth,
                    feed_per_tooth=e.feed_per_tooth,
                    engagement=eng,
                    disk_height=dz,
                )
                pair.append((m, _f.FlatEndWorkspace(m)))
            self._models.append(pair)
        self.omega = [2 * math.pi * e.spindle_rpm / 60.0 for e in self.experiments]  # [rad/s]
        for i, e in enumerate(self.experiments):
            if e.time_based:
                self.omega[i] = _estimate_speed(e.times, self.measured[i], self.omega[i], self.flutes)
        self._cache: dict = {}
        self.notes = []
        if any(e.time_based for e in self.experiments):
            self.notes.append(
                "time series: the angle of flute 1 at t = 0 was estimated by fitting the model; "
                "which physical flute is '1' cannot be known without a spindle encoder, so the "
                "runout angle lambda_deg refers to the flute the fit calls 1"
            )

    # --- model evaluation ----------------------------------------------------------------------------
    def _kernel(self, i, flutes_one: bool, window, kc, ke, shift):
        if window is None:
            return np.zeros((GRID, 3))
        m, ws = self._models[i][1 if flutes_one else 0]
        m.engagement = _f.AngularEngagement(window[0], window[1])
        m.linear_edge = _f.LinearEdgeCoefficients(kc[0], kc[1], kc[2], ke[0], ke[1], ke[2])
        return _f.flat_end_forces(m, self.grid + shift, ws)

    def grid_forces(self, spec: ForceSpec, i: int) -> np.ndarray:
        """Model forces (GRID, 3) [N] of experiment i over one revolution (θ = grid), no phase."""
        key = (i, spec.key())
        hit = self._cache.get(key)
        if hit is not None:
            return hit
        raw_key = (i, spec.coefficients, spec.runout, spec.chip_exponent, None)
        total = self._cache.get(raw_key)
        if total is None:
            total = self._cutting_grid(spec, i)
            self._store(raw_key, total)
        if spec.mode is not None:
            fn, zeta = spec.mode
            wn = 2 * np.pi * fn
            w = np.arange(GRID // 2 + 1) * self.omega[i]
            H = wn**2 / (wn**2 - w**2 + 2j * zeta * wn * w)
            total = np.fft.irfft(np.fft.rfft(total, axis=0) * H[:, None], n=GRID, axis=0)
        self._store(key, total)
        return total

    def _store(self, key, value):
        if len(self._cache) > 2048:
            self._cache.clear()
        self._cache[key] = value

    def _cutting_grid(self, spec: ForceSpec, i: int) -> np.ndarray:
        """Kernel forces (GRID, 3) [N] of experiment i without the structural mode."""
        e = self.experiments[i]
        c = e.feed_per_tooth
        N = self.flutes
        K = np.asarray(spec.coefficients, float)
        kc, ke = K[:3], K[3:]
        if spec.runout is not None:
            rho, lam = spec.runout
            r = rho * np.cos(lam - 2 * np.pi * np.arange(N) / N)
            groups = [(True, 2 * np.pi * j / N, r[j] - r[(j + 1) % N]) for j in range(N)]
        else:
            groups = [(False, 0.0, 0.0)]
        if spec.chip_exponent is None:
            knots, weights = np.array([0.0]), np.array([1.0])
        else:
            knots = c * _KNOTS
            g = self.h_ref * (np.maximum(knots, 0.0) / self.h_ref) ** spec.chip_exponent
            slopes = np.diff(g) / np.diff(knots)
            weights = np.concatenate([[slopes[0]], np.diff(slopes)])
            knots = knots[:-1]
        total = np.zeros((GRID, 3))
        for one, shift, delta in groups:
            if spec.chip_exponent is None:  # linear model: one call, edge forces where h > 0
                total += self._kernel(
                    i, one, _window(self._windows[i], -delta / c), kc, ke + delta * kc, shift
                )
                continue
            # cached unit terms: the fit of p only re-weights them
            for k, (hk, wk) in enumerate(zip(knots, weights)):
                d = hk - delta
                key = ("term", i, tuple(kc), one, shift, delta, k)
                T = self._cache.get(key)
                if T is None:
                    T = self._kernel(i, one, _window(self._windows[i], d / c), kc, -d * kc, shift)
                    self._store(key, T)
                total += wk * T
            total += self._kernel(i, one, _window(self._windows[i], -delta / c), np.zeros(3), ke, shift)
        return total

    def angles(self, spec: ForceSpec, i: int) -> np.ndarray:
        """Rotation angle θ of flute 1 at the tip at every sample of experiment i [rad]."""
        e = self.experiments[i]
        if not e.time_based:
            return e.angles
        return spec.phases[i] + self.omega[i] * e.times

    def _interpolation(self, spec, i):
        """(lower grid index (n,), weight of the upper (n, 1)) of the measured angles of experiment i."""
        e = self.experiments[i]
        key = ("interp", i) if not e.time_based else ("interp", i, spec.phases[i])
        hit = self._cache.get(key)
        if hit is None:
            pos = np.mod(self.angles(spec, i), 2 * np.pi) * (GRID / (2 * np.pi))
            j0 = np.floor(pos).astype(int)
            hit = (j0 % GRID, (pos - j0)[:, None])
            if not e.time_based:
                self._interp_fixed = getattr(self, "_interp_fixed", {})
                self._interp_fixed[i] = hit
            self._store(key, hit)
        return hit

    def predict(self, spec: ForceSpec) -> list:
        out = []
        for i, e in enumerate(self.experiments):
            G = self.grid_forces(spec, i)
            key = ("step", i, spec.key())
            dG = self._cache.get(key)
            if dG is None:
                dG = np.roll(G, -1, axis=0) - G
                self._store(key, dG)
            fixed = getattr(self, "_interp_fixed", {}).get(i)
            j0, t = fixed if fixed is not None else self._interpolation(spec, i)
            p = G[j0] + t * dG[j0]
            for add in spec.additive:
                p = p + add(e, self.angles(spec, i))
            out.append(p)
        return out

    # --- nuisance: the angle of flute 1 at t = 0 of time series ------------------------------------
    def nuisance_experiments(self) -> list:
        return [i for i, e in enumerate(self.experiments) if e.time_based]

    def nuisance_of(self, spec) -> np.ndarray:
        return np.array([spec.phases[i] for i in self.nuisance_experiments()])

    def with_nuisance(self, spec, values):
        ph = list(spec.phases)
        for i, v in zip(self.nuisance_experiments(), values):
            ph[i] = float(v)
        return dataclasses.replace(spec, phases=tuple(ph))

    def _phase_scan(self, spec, i) -> float:
        """θ0 of time series i by circular cross-correlation of its revolution-synchronous average
        with the model grid (weighted for empty bins)."""
        e = self.experiments[i]
        th = np.mod(self.omega[i] * e.times, 2 * np.pi)
        b = np.minimum((th * GRID / (2 * np.pi)).astype(int), GRID - 1)
        w = np.bincount(b, minlength=GRID).astype(float)
        S = np.stack([np.bincount(b, weights=self.measured[i][:, k], minlength=GRID) for k in range(3)], 1)
        G = self.grid_forces(spec, i)
        # cost(s) = Σ_m w_m |A_m − G_{m+s}|² = const − 2 Σ S_m·G_{m+s} + Σ w_m |G_{m+s}|²
        cross = np.fft.irfft(np.conj(np.fft.rfft(S, axis=0)) * np.fft.rfft(G, axis=0), n=GRID, axis=0).sum(1)
        g2 = np.fft.irfft(np.conj(np.fft.rfft(w)) * np.fft.rfft((G**2).sum(1)), n=GRID)
        s = int(np.argmin(g2 - 2 * cross))
        return 2 * np.pi * s / GRID

    def initial_spec(self) -> ForceSpec:
        m = self.bundle.model
        k = tuple(
            float(m[key])
            for key in (
                "Ktc_N_per_mm2",
                "Krc_N_per_mm2",
                "Kac_N_per_mm2",
                "Kte_N_per_mm",
                "Kre_N_per_mm",
                "Kae_N_per_mm",
            )
        )
        t = self.bundle.tool
        spec = ForceSpec(coefficients=k, phases=tuple(0.0 for _ in self.experiments),
                         runout=(t["runout_rho"], t["runout_lambda"]) if t.get("runout_rho") else None,
                         chip_exponent=m.get("chip_exponent"))
        if self.nuisance_experiments():
            spec = self.with_nuisance(spec, [self._phase_scan(spec, i) for i in self.nuisance_experiments()])
            _, spec = self.least_squares(lambda x: spec, [np.zeros(0)], (np.zeros(0), np.zeros(0)))
        return spec

    # --- noise, localisation, covariates -------------------------------------------------------------
    def _revolutions(self, spec, i):
        th = self.angles(spec, i)
        return (th.max() - th.min()) / (2 * np.pi), th

    noise_assumption = (
        "the residual changes little between neighbouring samples (second differences) where an "
        "experiment spans fewer than 2 revolutions"
    )

    def repeat_noise(self, spec):
        """When every experiment spans ≥ 2 revolutions each angle is measured once per revolution: the
        scatter about the revolution-synchronous mean (:meth:`noise_estimate`) is a repeats estimate."""
        n_all = 0
        for i in range(len(self.experiments)):
            revs, th = self._revolutions(spec, i)
            if not (revs >= 2.0 and int(min(1024, th.size / max(revs, 1e-9))) >= 8):
                return 0.0, 0
            n_all += th.size - int(min(1024, th.size / max(revs, 1e-9)))
        return self.noise_estimate(spec), n_all

    def structure_covariates(self, spec):
        """Components fx, fy, fz; covariates the angle of flute 1 (deg, harmonics of the revolution),
        the time or sample index within the experiment (t), the feed per tooth."""
        ang, t, feed = [], [], []
        for i, e in enumerate(self.experiments):
            ang.append(np.degrees(np.mod(self.angles(spec, i), 2 * np.pi)))
            t.append(e.times - e.times[0] if e.time_based else np.arange(len(e.forces), dtype=float))
            feed.append(np.full(len(e.forces), e.feed_per_tooth))
        return ["fx", "fy", "fz"], {"angle": np.concatenate(ang), "t": np.concatenate(t),
                                    "feed": np.concatenate(feed)}

    def noise_estimate(self, spec) -> float:
        """Part of the measurement no angle-synchronous model can explain [N]: the samples of every
        experiment that spans ≥ 2 revolutions are put in angular bins (as many per revolution as it has
        samples, ≤ 1024) and the scatter about a straight line in θ within each bin is pooled (dof
        counted); other experiments give the robust second-difference estimate of the model residual."""
        num, den = 0.0, 0
        res = self.residuals(spec)
        for i, e in enumerate(self.experiments):
            revs, th = self._revolutions(spec, i)
            n = th.size
            B = int(min(1024, n / max(revs, 1e-9)))
            if revs >= 2.0 and B >= 8:
                ss, dof = binned_scatter(np.mod(th, 2 * np.pi), self.measured[i], B)
                num += ss
                den += dof
            else:
                v, c = robust_difference_noise(res[i])
                num += v * c * 3
                den += c * 3
        return math.sqrt(num / den) if den else 0.0

    def localise(self, spec) -> dict:
        """Where the residual is systematic: its revolution harmonics (once per revolution = flutes
        differ; tooth harmonics; the strongest high harmonic and its frequency), its mean per
        experiment against the feed per tooth (intercept and slope per axis), and its rms against the
        load (correlation of per-experiment rms with the model's mean resultant)."""
        res = self.residuals(spec)
        pred = self.predict(spec)
        N = self.flutes
        power = {}
        total = 0.0
        best = (0.0, 0, 0.0)
        for i, e in enumerate(self.experiments):
            revs, th = self._revolutions(spec, i)
            per_rev = th.size / max(revs, 1e-9)
            H = int(min(60, per_rev // 3))
            if H < 2:
                continue
            p = harmonic_power(np.mod(th, 2 * np.pi), res[i], H)  # power per harmonic k = 1..H
            total += float(np.sum(res[i] ** 2) / th.size)
            for k, v in enumerate(p, start=1):
                power[k] = power.get(k, 0.0) + float(v)
            k_hi = int(np.argmax(p[3 * N - 1 :])) + 3 * N if H > 3 * N else 0
            if k_hi and p[k_hi - 1] > best[0]:
                best = (float(p[k_hi - 1]), k_hi, k_hi * self.omega[i] / (2 * np.pi))
        ks = np.array(sorted(power))
        pw = np.array([power[k] for k in ks]) if ks.size else np.zeros(0)
        tot = max(total, 1e-300)
        out = {
            "residual_rms": self.rms(spec),
            "once_per_revolution_fraction": float(pw[ks % N != 0].sum() / tot) if ks.size else 0.0,
            "tooth_harmonics_fraction": float(pw[ks % N == 0].sum() / tot) if ks.size else 0.0,
            "strongest_high_harmonic": {"harmonic": best[1], "frequency_hz": best[2]},
        }
        feeds = np.array([e.feed_per_tooth for e in self.experiments])
        means = np.array([r.mean(0) for r in res])
        if len(set(feeds)) >= 2:
            A = np.column_stack([np.ones_like(feeds), feeds])
            coef, *_ = np.linalg.lstsq(A, means, rcond=None)
            out["mean_residual_vs_feed"] = {
                "intercept_N": coef[0].tolist(),
                "slope_N_per_mm": coef[1].tolist(),
            }
        load = np.array([np.sqrt((p**2).sum(1)).mean() for p in pred])
        rr = np.array([np.sqrt((r**2).mean()) for r in res])
        if len(rr) >= 3 and np.std(load) > 0 and np.std(rr) > 0:
            out["rms_vs_load_correlation"] = float(np.corrcoef(load, rr)[0, 1])
        return out

    def covariates(self, spec) -> dict:
        return {
            "angle": [np.mod(self.angles(spec, i), 2 * np.pi) for i in range(len(self.experiments))],
            "feed": [e.feed_per_tooth for e in self.experiments],
            "frequency": self.omega,
        }

    def experiment_notes(self, spec) -> list:
        out = []
        for i, e in enumerate(self.experiments):
            d = {"file": e.file}
            if e.time_based:
                d["flute1_angle_at_t0_deg"] = math.degrees(spec.phases[i] % (2 * math.pi))
                d["spindle_rpm_estimated"] = self.omega[i] * 60 / (2 * math.pi)
            out.append(d)
        return out


def harmonic_power(theta, y, H, bins=256):
    """Mean power (H,) of y (n, 3) at revolution harmonics k = 1..H, summed over the columns: the
    FFT of the revolution-synchronous average over ``bins`` angular bins (empty bins interpolated)."""
    B = max(bins, 2 * H + 2)
    b = np.minimum((theta * B / (2 * np.pi)).astype(int), B - 1)
    cnt = np.bincount(b, minlength=B)
    avg = np.stack([np.bincount(b, weights=y[:, k], minlength=B) for k in range(y.shape[1])], 1)
    have = cnt > 0
    avg[have] /= cnt[have, None]
    if not have.all():
        idx = np.arange(B)
        for k in range(avg.shape[1]):
            avg[~have, k] = np.interp(idx[~have], idx[have], avg[have, k], period=B)
    C = np.fft.rfft(avg, axis=0) / B
    return (2 * np.abs(C[1 : H + 1]) ** 2).sum(1)


def binned_scatter(theta, y, bins):
    """Pooled scatter of y (n, k) about a straight line in θ within each of ``bins`` equal angular
    bins of [0, 2π): (sum of squares, degrees of freedom); a bin whose angles coincide uses its mean."""
    w = 2 * np.pi / bins
    b = np.minimum((theta / w).astype(int), bins - 1)
    u = theta - (b + 0.5) * w
    n = np.bincount(b, minlength=bins).astype(float)
    su, suu = np.bincount(b, u, bins), np.bincount(b, u * u, bins)
    ss, dof = 0.0, 0
    with np.errstate(divide="ignore", invalid="ignore"):
        vu = suu - np.where(n > 0, su**2 / n, 0.0)
        line = vu > 1e-12 * w * w * np.maximum(n, 1)
        for k in range(y.shape[1]):
            sy = np.bincount(b, y[:, k], bins)
            syy = np.bincount(b, y[:, k] ** 2, bins)
            suy = np.bincount(b, u * y[:, k], bins)
            r = syy - np.where(n > 0, sy**2 / n, 0.0)
            r = r - np.where(line, (suy - su * sy / np.where(n > 0, n, 1)) ** 2 / np.where(line, vu, 1), 0.0)
            ss += float(np.sum(np.maximum(r, 0.0)))
            dof += int(np.sum(np.maximum(n - np.where(line, 2, 1), 0)))
    return ss, dof


def _estimate_speed(times, forces, omega0, flutes) -> float:
    """Spindle speed Ω [rad/s] from the tooth-passing harmonics of a recording (±3 % of omega0):
    the maximum over Ω of Σ_{k=1..4} Σ_axes |Σ_t F(t)·e^{−ik·N·Ω·t}|²; Ω0 if < 20 revolutions."""
    span = times[-1] - times[0]
    if span * omega0 / (2 * np.pi) < 20:
        return omega0
    t = times - times[0]
    F = forces - forces.mean(0)

    def score(omegas):
        out = np.empty(len(omegas))
        for j, w in enumerate(omegas):
            s = 0.0
            for k in range(1, 5):
                z = np.exp(-1j * k * flutes * w * t)
                s += float(np.sum(np.abs(z @ F) ** 2))
            out[j] = s
        return out

    grid = omega0 * (1 + np.linspace(-0.03, 0.03, 121))
    w = grid[int(np.argmax(score(grid)))]
    fine = w * (1 + np.linspace(-6e-4, 6e-4, 61))
    return float(fine[int(np.argmax(score(fine)))])


# the catalogue entries (runout, edge_forces, size_effect, structural_mode) register themselves on import
from . import force_catalogue as _force_catalogue  # noqa: E402,F401
