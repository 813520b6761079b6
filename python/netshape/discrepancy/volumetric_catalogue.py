"""The volumetric-error catalogue entries ``squareness``, ``scale_error``, ``thermal_drift``,
``spindle_tilt``, ``backlash`` and ``cyclic_error`` (their models and parameters are described in
:mod:`netshape.discrepancy.volumetric_effects`); importing this module registers them."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .catalogue import Effect, EffectFit, register_effect
from .volumetric_effects import _AXES


# Physical ranges (issue 37 item 4): a fit at or beyond one is rejected as implausible. Generous
# limits for a machine tool in working order, not tuned on any test case.
#: out-of-squareness [µrad] (0.5 mm/m: far beyond any acceptance test)
SQUARENESS_MAX_URAD = 500.0
#: linear positioning (scale) error [µm/m] (≈ 40 K of steel expansion)
SCALE_MAX_UM_PER_M = 500.0
#: thermal drift amplitude of the tool tip [mm]
THERMAL_MAX_MM = 0.2
#: spindle tilt [µrad]
TILT_MAX_URAD = 1000.0
#: reversal (backlash) [µm]
BACKLASH_MAX_UM = 200.0
#: cyclic (ball-screw periodic) error amplitude [mm]
CYCLIC_MAX_MM = 0.1
#: a thermal time constant beyond this multiple of the measurement's duration makes the drift linear
#: over it: amplitude and τ are then not separately determined, only their ratio, the drift rate
LINEAR_DRIFT_TAU = 10.0


class Squareness(Effect):
    name, kind = "squareness", "volumetric_error"
    parameters = ("EC0Y_urad", "EB0Z_urad", "EA0Z_urad")
    covariate = "position"
    description = "out-of-squareness of the axes (ISO 230-1 EC0Y, EB0Z, EA0Z)"

    def physical_bounds(self, problem):
        return {k: (-SQUARENESS_MAX_URAD, SQUARENESS_MAX_URAD) for k in self.parameters}

    def starts(self, problem, spec):
        return [np.array([(spec.get(n, (0.0,))[0]) * 1e6 for n in ("EC0Y", "EB0Z", "EA0Z")])]

    def apply(self, problem, spec, x):
        for n, v in zip(("EC0Y", "EB0Z", "EA0Z"), x):
            spec = spec.set(n, [v * 1e-6])
        return spec

    def parameters_of(self, x):
        return {k: float(v) for k, v in zip(self.parameters, x)}


class ScaleError(Effect):
    name, kind = "scale_error", "volumetric_error"
    parameters = ("EXX_um_per_m", "EYY_um_per_m", "EZZ_um_per_m")
    covariate = "position"
    description = "scale (linear positioning) error of each axis: the linear term of EXX, EYY, EZZ"

    def physical_bounds(self, problem):
        return {k: (-SCALE_MAX_UM_PER_M, SCALE_MAX_UM_PER_M) for k in self.parameters}

    def starts(self, problem, spec):
        out = []
        for n in ("EXX", "EYY", "EZZ"):
            c = spec.get(n, ())
            out.append(c[1] * 1e6 if len(c) > 1 else 0.0)
        return [np.array(out)]

    def apply(self, problem, spec, x):
        for n, v in zip(("EXX", "EYY", "EZZ"), x):
            c = list(spec.get(n, ())) + [0.0] * 2
            c = c[: max(2, len(spec.get(n, ())))]
            c[1] = v * 1e-6
            spec = spec.set(n, c)
        return spec

    def parameters_of(self, x):
        return {k: float(v) for k, v in zip(self.parameters, x)}


class _PerAxis(Effect):
    """An effect with a categorical ``axis``: fitted for X, Y and Z, the smallest cost kept."""

    def fit(self, problem, spec, train=None):
        best = None
        for axis in _AXES:
            x, s = problem.least_squares(
                lambda x, a=axis: self.apply_axis(problem, spec, a, x),
                self.starts(problem, spec),
                self.bounds(problem, spec),
                train=train,
            )
            cost = problem.rms(s, train)
            if best is None or cost < best[0]:
                best = (cost, axis, x, s, getattr(problem, "last_status", None))
        _, axis, x, s, status = best
        return EffectFit(
            self.parameters_of_axis(axis, x), s, len(x) + 1, np.concatenate([[_AXES.index(axis)], x]), status
        )

    def apply(self, problem, spec, x):  # x = [axis index, ...] as returned by fit
        return self.apply_axis(problem, spec, _AXES[int(round(x[0]))], x[1:])

    def parameters_of(self, x):  # x = [axis index, ...]
        return self.parameters_of_axis(_AXES[int(round(x[0]))], x[1:])

    def refit(self, problem, spec, fit):
        axis = _AXES[int(round(fit.x[0]))]
        return (lambda x: self.apply_axis(problem, spec, axis, x)), fit.x[1:], self.bounds(problem, spec)


class ThermalDrift(_PerAxis):
    name, kind = "thermal_drift", "volumetric_error"
    parameters = ("axis", "amplitude_mm", "time_constant_s")
    covariate = "time"
    description = (
        "thermal drift of the tool tip along one axis: amplitude·(1 − exp(−t/τ)); with τ beyond "
        f"{LINEAR_DRIFT_TAU:g}× the measurement's duration the drift is linear over it and is reported "
        "as its rate, rate·t (parameters axis, rate_mm_per_h)"
    )

    def applicable(self, problem):
        return None if all(e.times is not None for e in problem.experiments) else "needs the t_s column"

    def _duration(self, problem):
        t = np.concatenate([e.times for e in problem.experiments])
        return float(t.max() - t.min()) or 1.0

    def physical_bounds(self, problem):
        """τ between the sampling interval (the median step of the sorted times) and 10× the
        measurement's duration; |amplitude| below THERMAL_MAX_MM; the linear form's drift over the
        measurement (rate × duration) below THERMAL_MAX_MM."""
        D = self._duration(problem)
        dt = min(float(np.median(np.diff(np.sort(e.times)))) for e in problem.experiments)
        rate = THERMAL_MAX_MM / D * 3600.0
        return {
            "time_constant_s": (dt, LINEAR_DRIFT_TAU * D),
            "amplitude_mm": (-THERMAL_MAX_MM, THERMAL_MAX_MM),
            "rate_mm_per_h": (-rate, rate),
        }

    def starts(self, problem, spec):
        """[rate [mm/s], k = 1/τ [1/s]] from zero drift: τ = D/5, τ = D, and the linear form k = 0."""
        D = self._duration(problem)
        return [np.array([0.0, 5.0 / D]), np.array([0.0, 1.0 / D]), np.array([0.0, 0.0])]

    def bounds(self, problem, spec):
        return (np.array([-np.inf, 0.0]), np.array([np.inf, 1e3 / self._duration(problem)]))

    def fit(self, problem, spec, train=None):
        """The exponential fit over rate and k = 1/τ ≥ 0 (k = 0: the linear form); a fit with τ beyond
        LINEAR_DRIFT_TAU × the duration is refitted as the linear form, rate·t (the same number of
        parameters counted, since the form was chosen by the fit)."""
        f = super().fit(problem, spec, train)
        ai, r, k = int(round(f.x[0])), float(f.x[1]), float(f.x[2])
        if k * LINEAR_DRIFT_TAU * self._duration(problem) >= 1.0:
            return f
        axis = _AXES[ai]
        x, s = problem.least_squares(lambda x: self.apply_axis(problem, spec, axis, x), [np.array([r])],
                                     (-np.inf, np.inf), train=train)
        return EffectFit(self.parameters_of_axis(axis, x), s, f.k, np.concatenate([[ai], x]),
                         getattr(problem, "last_status", None))

    def refit(self, problem, spec, fit):
        axis = _AXES[int(round(fit.x[0]))]
        x = fit.x[1:]
        bnd = self.bounds(problem, spec) if x.size == 2 else (np.full(1, -np.inf), np.full(1, np.inf))
        return (lambda x: self.apply_axis(problem, spec, axis, x)), x, bnd

    def fold_start(self, problem, spec, x):
        return np.zeros(1) if np.size(x) == 1 else self.starts(problem, spec)[0]

    def apply_axis(self, problem, spec, axis, x):
        k = float(x[1]) if len(x) > 1 else 0.0
        return dataclasses.replace(spec, thermal=spec.thermal + ((axis, float(x[0]), k),))

    def parameters_of_axis(self, axis, x):
        if len(x) == 1 or float(x[1]) == 0.0:
            return {"axis": axis, "rate_mm_per_h": float(x[0]) * 3600.0}
        return {"axis": axis, "amplitude_mm": float(x[0]) / float(x[1]), "time_constant_s": 1.0 / float(x[1])}


class SpindleTilt(Effect):
    name, kind = "spindle_tilt", "volumetric_error"
    parameters = ("tilt_a_urad", "tilt_b_urad")
    covariate = "tool_length"
    description = "tilt of the spindle axis about X (a) and Y (b); the tip error grows with the tool length"

    def applicable(self, problem):
        L = {e.tool_length for e in problem.experiments}
        return (
            None
            if len(L) >= 2
            else "needs experiments with different tool_length_mm (else a tilt is an offset)"
        )

    def physical_bounds(self, problem):
        return {k: (-TILT_MAX_URAD, TILT_MAX_URAD) for k in self.parameters}

    def starts(self, problem, spec):
        return [
            np.array(
                [spec.get("spindle_tilt_a", (0.0,))[0] * 1e6, spec.get("spindle_tilt_b", (0.0,))[0] * 1e6]
            )
        ]

    def apply(self, problem, spec, x):
        return spec.set("spindle_tilt_a", [x[0] * 1e-6]).set("spindle_tilt_b", [x[1] * 1e-6])

    def parameters_of(self, x):
        return {"tilt_a_urad": float(x[0]), "tilt_b_urad": float(x[1])}


class Backlash(_PerAxis):
    name, kind = "backlash", "volumetric_error"
    parameters = ("axis", "reversal_um")
    covariate = "direction"
    description = (
        "reversal (backlash) error of one axis: it lands reversal/2 further along its approach direction"
    )

    def applicable(self, problem):
        if not all(e.directions is not None for e in problem.experiments):
            return "needs the direction column"
        if np.unique(np.concatenate([e.directions for e in problem.experiments])).size < 2:
            return "every point is approached from one direction (a reversal would be an offset)"
        return None

    def physical_bounds(self, problem):
        return {"reversal_um": (-BACKLASH_MAX_UM, BACKLASH_MAX_UM)}

    def starts(self, problem, spec):
        return [np.zeros(1)]

    def apply_axis(self, problem, spec, axis, x):
        return dataclasses.replace(spec, backlash=spec.backlash + ((axis, float(x[0]) * 1e-3),))

    def parameters_of_axis(self, axis, x):
        return {"axis": axis, "reversal_um": float(x[0])}


def _axis_levels(problem, i):
    return np.unique(np.round(np.concatenate([e.points[:, i] for e in problem.experiments]), 6))


def _period_range(problem, i):
    """(low, high) periods [mm] a grid along axis i can show: 2 median level spacings (Nyquist) to
    half the axis' range (two full cycles)."""
    lv = _axis_levels(problem, i)
    return 2.0 * float(np.median(np.diff(lv))), 0.5 * float(lv[-1] - lv[0])


def _periodogram(pos, r, lo, hi):
    """Least-squares (Lomb-Scargle) periodogram of r against pos over periods (lo, hi) [mm]: the
    sinusoid a·sin + b·cos (+ mean) that lowers the residual sum of squares most, on a frequency grid
    of spacing 1/(4·range) refined ×40 around its peak. Returns (period, a, b)."""
    span = float(pos.max() - pos.min())
    yc = r - r.mean()

    def best(freqs):
        out = (-1.0, None, 0.0, 0.0)
        for f in freqs:
            w = 2 * np.pi * pos * f
            A = np.column_stack([np.sin(w), np.cos(w)])
            A = A - A.mean(axis=0)
            c, *_ = np.linalg.lstsq(A, yc, rcond=None)
            d = float(yc @ (A @ c))
            if d > out[0]:
                out = (d, f, float(c[0]), float(c[1]))
        return out

    df = 1.0 / (4.0 * span)
    d, f, a, b = best(np.arange(1.0 / hi, 1.0 / lo, df))
    if f is None:
        return None
    fine = f + np.linspace(-df, df, 41)
    d2, f2, a2, b2 = best(fine[(fine > 1.0 / hi) & (fine < 1.0 / lo)])
    if f2 is not None and d2 > d:
        f, a, b = f2, a2, b2
    return 1.0 / f, a, b


class CyclicError(_PerAxis):
    name, kind = "cyclic_error", "volumetric_error"
    parameters = ("axis", "period_mm", "amplitude_mm", "phase_deg")
    covariate = "position"
    description = (
        "periodic positioning error of one axis against its own position (ball-screw pitch, encoder "
        "interpolation): amplitude·sin(2π·pos/period + phase); period from the residual's periodogram"
    )

    def applicable(self, problem):
        if max(_axis_levels(problem, i).size for i in range(3)) < 8:
            return "no axis has 8 distinct positions (too few to see a period)"
        return None

    def physical_bounds(self, problem):
        """amplitude below CYCLIC_MAX_MM; the period within what the grid can show (see
        :func:`_period_range`; the optimiser is held there too, so a fit ending at it is rejected)."""
        return {"amplitude_mm": (0.0, CYCLIC_MAX_MM)}

    def implausible(self, problem, fit, x=None, bounds=None):
        why = super().implausible(problem, fit)
        if why or x is None or bounds is None:
            return why
        P, (lo, hi) = float(np.atleast_1d(x)[-1]), (float(bounds[0][-1]), float(bounds[1][-1]))
        if not lo * (1 + 1e-6) < P < hi * (1 - 1e-6):
            return f"period_mm = {P:.4g} ended at the edge of what the grid shows ({lo:.4g}, {hi:.4g})"
        return None

    def _starts_axis(self, problem, spec, axis):
        """[a, b, period]: from zero amplitude at the periodogram's period (first: the start of the
        cross-validation folds), then at the periodogram's amplitude."""
        i = _AXES.index(axis)
        lo, hi = _period_range(problem, i)
        if not hi > lo:
            return None
        r = np.concatenate(problem.residuals(spec))[:, i]
        pos = np.concatenate([e.points[:, i] for e in problem.experiments])
        if problem.fit_mask is not None:  # a held-out fold: the periodogram of its fitting points
            keep = np.concatenate(problem.fit_mask)
            r, pos = r[keep], pos[keep]
        pg = _periodogram(pos, r, lo, hi)
        if pg is None:
            return None
        P, a, b = pg
        return [np.array([0.0, 0.0, P]), np.array([a, b, P])]

    def starts(self, problem, spec):
        axis = getattr(self, "_axis", None) or _AXES[
            int(np.argmax([_axis_levels(problem, i).size for i in range(3)]))]
        return self._starts_axis(problem, spec, axis) or [np.array([0.0, 0.0, 1.0])]

    def _bounds_axis(self, problem, axis):
        lo, hi = _period_range(problem, _AXES.index(axis))
        return (np.array([-np.inf, -np.inf, lo]), np.array([np.inf, np.inf, hi]))

    def fit(self, problem, spec, train=None):
        best = None
        for axis in _AXES:
            if _axis_levels(problem, _AXES.index(axis)).size < 8:
                continue
            starts = self._starts_axis(problem, spec, axis)
            if starts is None:
                continue
            bnd = self._bounds_axis(problem, axis)
            x, s = problem.least_squares(
                lambda x, a=axis: self.apply_axis(problem, spec, a, x), starts, bnd, train=train
            )
            cost = problem.rms(s, train)
            if best is None or cost < best[0]:
                best = (cost, axis, x, s, getattr(problem, "last_status", None))
        if best is None:
            raise ValueError("no axis has a period range (2 spacings < half the range)")
        _, axis, x, s, status = best
        self._axis = axis  # the cross-validation folds start on this axis' periodogram
        return EffectFit(
            self.parameters_of_axis(axis, x), s, len(x) + 1, np.concatenate([[_AXES.index(axis)], x]), status
        )

    def refit(self, problem, spec, fit):
        axis = _AXES[int(round(fit.x[0]))]
        return (lambda x: self.apply_axis(problem, spec, axis, x)), fit.x[1:], self._bounds_axis(problem, axis)

    def apply_axis(self, problem, spec, axis, x):
        return dataclasses.replace(spec, cyclic=spec.cyclic + ((axis, float(x[0]), float(x[1]), float(x[2])),))

    def parameters_of_axis(self, axis, x):
        a, b, P = (float(v) for v in x)
        return {
            "axis": axis,
            "period_mm": P,
            "amplitude_mm": math.hypot(a, b),
            "phase_deg": math.degrees(math.atan2(b, a)) % 360.0,
        }


for _e in (Squareness(), ScaleError(), ThermalDrift(), SpindleTilt(), Backlash(), CyclicError()):
    register_effect(_e, replace=True)
