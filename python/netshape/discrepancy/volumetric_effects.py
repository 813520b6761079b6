"""Volumetric-error bundles: the machine's known ISO 230-1 components synthesised by netshape.machine
(exact product of homogeneous transforms, C++), extended by the catalogue entries ``squareness``,
``scale_error``, ``thermal_drift``, ``spindle_tilt``, ``backlash`` and ``cyclic_error``.

Parameters (units in the names):

* squareness: ``EC0Y_urad``, ``EB0Z_urad``, ``EA0Z_urad`` (reference axes X, X, Y as in
  netshape.machine), the machine's values after the fit;
* scale_error: ``EXX_um_per_m``, ``EYY_um_per_m``, ``EZZ_um_per_m``: the linear term of each axis'
  positioning error after the fit;
* thermal_drift: the tool tip drifts along ``axis`` by amplitude·(1 − exp(−t/τ)), ``amplitude_mm``,
  ``time_constant_s`` (needs ``t_s``);
* spindle_tilt: ``tilt_a_urad``, ``tilt_b_urad`` about X and Y (its error grows with the tool length,
  so the bundle needs experiments with different ``tool_length_mm`` to tell it from an offset);
* backlash: the moving ``axis`` lands ``reversal_um``/2 further along its approach direction,
  e_axis += direction·reversal/2 (needs ``direction``);
* cyclic_error: a ball-screw's periodic positioning error of ``axis`` against its own position,
  e_axis += amplitude·sin(2π·pos_axis/period + phase), ``period_mm``, ``amplitude_mm``,
  ``phase_deg`` (needs ≥ 8 distinct positions along the axis).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from netshape.machine import machine_from_dict, tip_error

from .catalogue import Effect, EffectFit, register_effect
from .problem import Problem, robust_difference_noise

_AXES = "XYZ"

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


@dataclass(frozen=True)
class VolumetricSpec:
    """A volumetric-error model: ``model`` ((name, coefficients) pairs by ISO 230-1 name, as in the
    bundle: mm or rad, position in mm); ``thermal`` ((axis, amplitude [mm], τ [s]), …); ``backlash``
    ((axis, reversal [mm]), …); ``cyclic`` ((axis, a [mm], b [mm], period [mm]), …: e_axis +=
    a·sin(2π·pos/period) + b·cos(2π·pos/period)); ``additive`` callables (experiment, points (n, 3))
    → (n, 3) [mm]."""

    model: tuple
    thermal: tuple = ()
    backlash: tuple = ()
    additive: tuple = ()
    cyclic: tuple = ()

    def get(self, name, default=None):
        return dict(self.model).get(name, default)

    def set(self, name, coef):
        d = dict(self.model)
        d[name] = tuple(float(c) for c in coef)
        return dataclasses.replace(self, model=tuple(sorted(d.items())))


class VolumetricProblem(Problem):
    kind = "volumetric_error"
    unit = "mm"

    def __init__(self, bundle, machine=None):
        """``machine``: a machine TOML path as the current model instead of the bundle's ``[model]``
        (:class:`volumetric_machine.MachineModel`)."""
        self.bundle = bundle
        self.base = None
        if machine is not None:
            from .volumetric_machine import MachineModel

            self.base = MachineModel(machine, bundle)
        self.experiments = bundle.experiments
        self.measured = [np.asarray(e.errors, float) for e in self.experiments]
        self._machines: dict = {}
        self.notes = []

    def initial_spec(self):
        model = self.bundle.model if self.base is None else self.base.initial_model()
        return VolumetricSpec(model=tuple(sorted((k, tuple(v)) for k, v in model.items())))

    def machine(self, spec, tool_length):
        key = (spec.model, tool_length)
        m = self._machines.get(key)
        if m is not None:
            return m
        if self.base is not None:
            m = self.base.build(dict(spec.model), tool_length)
            self._machines[key] = m
            return m
        mc = self.bundle.machine
        doc = {
            "tool_chain": mc["tool_side"],
            "workpiece_chain": mc["workpiece_side"],
            "tool": {"length_mm": tool_length},
            "spindle": {},
            "squareness": {},
            "axes": {},
        }
        for name, coef in spec.model:
            if name.startswith("spindle_tilt_"):
                doc["spindle"][f"tilt_{name[-1]}_rad"] = coef[0]
            elif name in ("EC0Y", "EB0Z", "EA0Z"):
                doc["squareness"][f"{name}_rad"] = coef[0]
            else:
                unit = "mm" if name[1] in _AXES else "rad"
                doc["axes"].setdefault(name[2], {}).setdefault("polynomials", {})[f"{name}_{unit}"] = list(
                    coef
                )
        m = machine_from_dict(doc, source="[model]")
        if len(self._machines) > 128:
            self._machines.clear()
        self._machines[key] = m
        return m

    def predict(self, spec):
        """The model's tip errors, each (n, 3) [mm], in the measurement's frame: the machine model
        (:meth:`machine_predict`) plus the registered frame (:meth:`frame_of`), fitted to the data
        with every evaluation (its six parameters enter linearly and are profiled out)."""
        pred = self.machine_predict(spec)
        omega, T = self.frame_of(spec, pred)
        return [p + np.cross(omega, e.points) + T for p, e in zip(pred, self.experiments)]

    def frame_of(self, spec, pred=None):
        """The registered measurement frame (ω [rad] (3,), T [mm] (3,)): the data are e_model +
        ω × p + T. ISO 230-1 convention, X primary and Y secondary reference: ω is chosen so that the
        straightness slopes of X (ey and ez against x) and of Y in z (ez against y) are zero, i.e.
        from the residual e − e_model by least squares on ez = tz − ωy·x + ωx·y, then
        ey + ωx·z = ty + ωz·x, then ex − (ωy·z − ωz·y) = tx. The other three cross slopes (ex against
        y and z, ey against z) stay for the squareness EC0Y, EB0Z, EA0Z; a rotation about Z therefore
        never hides a squareness, and ey = c·x (data aligned to Y: the axes at 90° − c) reads as
        ωz = c, EC0Y = −c (netshape.machine: EC0Y > 0 gives ex = −EC0Y·y, the axes at 90° + EC0Y)."""
        if pred is None:
            pred = self.machine_predict(spec)
        r = np.concatenate([m - p for m, p in zip(self.measured, pred)])
        P = np.concatenate([e.points for e in self.experiments])
        if not np.all(np.isfinite(r)) or P.shape[0] < 4:
            return np.zeros(3), np.zeros(3)
        one = np.ones(len(P))
        x, y, z = P.T

        def ls(cols, v):
            A = np.column_stack(cols)
            keep = np.ptp(A, axis=0) > 0
            keep[0] = True
            c = np.zeros(A.shape[1])
            c[keep] = np.linalg.lstsq(A[:, keep], v, rcond=None)[0]
            return c

        tz, c_x, c_y = ls([one, x, y], r[:, 2])
        wy, wx = -c_x, c_y
        ty, wz = ls([one, x], r[:, 1] + wx * z)
        (tx,) = ls([one], r[:, 0] - (wy * z - wz * y))
        return np.array([wx, wy, wz]), np.array([tx, ty, tz])

    def frame(self, spec) -> dict:
        """The registered frame as reported: {rotation_urad: [rx, ry, rz], translation_mm: [tx, ty, tz]}."""
        omega, T = self.frame_of(spec)
        return {"rotation_urad": [float(v) * 1e6 for v in omega], "translation_mm": [float(v) for v in T]}

    def machine_predict(self, spec):
        """The machine model's tip errors without the measurement frame, each (n, 3) [mm]."""
        out = []
        for e in self.experiments:
            p = np.array(tip_error(self.machine(spec, e.tool_length), e.points))
            if self.base is not None:
                p += self.base.state(e)
            for axis, amp, tau in spec.thermal:
                p[:, _AXES.index(axis)] += amp * (1.0 - np.exp(-e.times / tau))
            for axis, rev in spec.backlash:
                p[:, _AXES.index(axis)] += 0.5 * rev * e.directions
            for axis, a, b, period in spec.cyclic:
                i = _AXES.index(axis)
                w = 2.0 * np.pi * e.points[:, i] / period
                p[:, i] += a * np.sin(w) + b * np.cos(w)
            for add in spec.additive:
                p = p + add(e, e.points)
            out.append(p)
        return out

    noise_assumption = (
        "what is left after a flexible smoother (a level per distinct x, y, z; bilinear position "
        "products; per-experiment offsets and a smooth function of measuring order; the direction) is noise"
    )

    def _order(self, e):
        return e.times if e.times is not None else np.arange(len(e.points), dtype=float)

    def noise_estimate(self, spec) -> float:
        """Robust noise of the model residual after a flexible smoother against position and
        measuring order (:func:`structure.smoother_noise`) [mm]. (The second-difference estimate of
        earlier versions absorbed periodic structure: a 4 µm cyclic error read as 2 µm of noise.)"""
        from .structure import smoother_noise

        r = np.concatenate(self.residuals(spec))
        P = np.concatenate([e.points for e in self.experiments])
        order = np.concatenate([self._order(e) for e in self.experiments])
        groups = np.concatenate([np.full(len(e.points), i) for i, e in enumerate(self.experiments)])
        d = None
        if all(e.directions is not None for e in self.experiments):
            d = np.concatenate([e.directions for e in self.experiments])
        return smoother_noise(r, P, order, groups, d)[0]

    def repeat_noise(self, spec):
        """Points measured more than once: same nominal point (to 1 µm), tool length and approach
        direction (ISO 230-2 repeated runs; both directions kept apart so backlash is not noise); a
        smooth drift in t_s between the runs is fitted with the point means, not counted as noise."""
        from .structure import repeat_noise

        keys = []
        for e in self.experiments:
            d = e.directions if e.directions is not None else np.zeros(len(e.points))
            for p, di in zip(np.round(e.points, 3), d):
                keys.append((e.tool_length, *p.tolist(), float(di)))
        t = None
        if all(e.times is not None for e in self.experiments):
            t = np.concatenate([e.times for e in self.experiments])
        return repeat_noise(np.concatenate(self.residuals(spec)), keys, t)

    def structure_covariates(self, spec):
        cov = {
            a: np.concatenate([e.points[:, i] for e in self.experiments]) for i, a in enumerate("xyz")
        }
        if all(e.times is not None for e in self.experiments):
            cov["t"] = np.concatenate([e.times for e in self.experiments])
        else:
            cov["order"] = np.concatenate([np.arange(len(e.points), dtype=float) for e in self.experiments])
        if all(e.directions is not None for e in self.experiments):
            cov["direction"] = np.concatenate([e.directions for e in self.experiments])
        cov["tool_length"] = np.concatenate([np.full(len(e.points), e.tool_length) for e in self.experiments])
        return ["ex", "ey", "ez"], cov

    def localise(self, spec) -> dict:
        """Correlation of each residual component with each position, time, direction and tool length
        (linear structure shows as |r| near 1), and the slope of the strongest pairs."""
        r = np.concatenate(self.residuals(spec))
        cov = {
            f"{a.lower()}_mm": np.concatenate([e.points[:, i] for e in self.experiments])
            for i, a in enumerate(_AXES)
        }
        if all(e.times is not None for e in self.experiments):
            cov["t_s"] = np.concatenate([e.times for e in self.experiments])
        if all(e.directions is not None for e in self.experiments):
            cov["direction"] = np.concatenate([e.directions for e in self.experiments])
        cov["tool_length_mm"] = np.concatenate(
            [np.full(len(e.points), e.tool_length) for e in self.experiments]
        )
        out = {"residual_rms": self.rms(spec), "correlation": {}}
        for name, v in cov.items():
            if np.std(v) == 0:
                continue
            for j, comp in enumerate(("ex", "ey", "ez")):
                if np.std(r[:, j]) > 0:
                    out["correlation"][f"{comp}~{name}"] = float(np.corrcoef(v, r[:, j])[0, 1])
        return out

    def covariates(self, spec) -> dict:
        return {
            "position": [e.points for e in self.experiments],
            "time": [e.times for e in self.experiments],
            "direction": [e.directions for e in self.experiments],
            "tool_length": [np.full(len(e.points), e.tool_length) for e in self.experiments],
        }

    def covariate_vectors(self) -> dict:
        """{catalogue covariate: {name: (n,) values}} over all points, for the identifiability check
        (:func:`workflow.identifiability`)."""
        out = {"position": {a: np.concatenate([e.points[:, i] for e in self.experiments]) for i, a in enumerate("xyz")},
               "tool_length": {"tool_length": np.concatenate(
                   [np.full(len(e.points), e.tool_length) for e in self.experiments])}}
        if all(e.times is not None for e in self.experiments):
            out["time"] = {"t": np.concatenate([e.times for e in self.experiments])}
        if all(e.directions is not None for e in self.experiments):
            out["direction"] = {"direction": np.concatenate([e.directions for e in self.experiments])}
        return out

    def experiment_notes(self, spec) -> list:
        return [{"file": e.file, "tool_length_mm": e.tool_length} for e in self.experiments]


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
    description = "thermal drift of the tool tip along one axis: amplitude·(1 − exp(−t/τ))"

    def applicable(self, problem):
        return None if all(e.times is not None for e in problem.experiments) else "needs the t_s column"

    def _span(self, problem):
        return max(float(np.max(e.times)) for e in problem.experiments) or 1.0

    def physical_bounds(self, problem):
        """τ between the sampling interval (the median step of the sorted times) and 10× the
        measurement's duration; |amplitude| below THERMAL_MAX_MM."""
        t = np.concatenate([e.times for e in problem.experiments])
        dt = min(float(np.median(np.diff(np.sort(e.times)))) for e in problem.experiments)
        return {
            "time_constant_s": (dt, 10.0 * float(t.max() - t.min())),
            "amplitude_mm": (-THERMAL_MAX_MM, THERMAL_MAX_MM),
        }

    def starts(self, problem, spec):
        T = self._span(problem)
        return [np.array([0.0, f * T]) for f in (0.2, 1.0)]

    def bounds(self, problem, spec):
        T = self._span(problem)
        return (np.array([-np.inf, 1e-3 * T]), np.array([np.inf, 50.0 * T]))

    def apply_axis(self, problem, spec, axis, x):
        return dataclasses.replace(spec, thermal=spec.thermal + ((axis, float(x[0]), float(x[1])),))

    def parameters_of_axis(self, axis, x):
        return {"axis": axis, "amplitude_mm": float(x[0]), "time_constant_s": float(x[1])}


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
