"""Volumetric-error bundles: the machine's known ISO 230-1 components synthesised by netshape.machine
(exact product of homogeneous transforms, C++), extended by the catalogue entries ``squareness``,
``scale_error``, ``thermal_drift``, ``spindle_tilt``, ``backlash`` and ``cyclic_error``
(:mod:`netshape.discrepancy.volumetric_catalogue`).

Parameters (units in the names):

* squareness: ``EC0Y_urad``, ``EB0Z_urad``, ``EA0Z_urad`` (reference axes X, X, Y as in
  netshape.machine), the machine's values after the fit;
* scale_error: ``EXX_um_per_m``, ``EYY_um_per_m``, ``EZZ_um_per_m``: the linear term of each axis'
  positioning error after the fit;
* thermal_drift: the tool tip drifts along ``axis`` by amplitude·(1 − exp(−t/τ)), ``amplitude_mm``,
  ``time_constant_s``; with τ beyond LINEAR_DRIFT_TAU × the measurement's duration, linearly,
  rate·t, ``rate_mm_per_h`` (needs ``t_s``);
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
from dataclasses import dataclass

import numpy as np

from netshape.machine import machine_from_dict, tip_error

from .problem import Problem

_AXES = "XYZ"


def thermal_drift(t, rate, k):
    """The tip drift rate·(1 − exp(−k·t))/k at times t [s] (rate [mm/s] the initial drift rate, k = 1/τ
    [1/s]; k = 0: the linear drift rate·t, the limit τ → ∞) [mm]."""
    t = np.asarray(t, float)
    return rate * t if k == 0.0 else -rate * np.expm1(-k * t) / k


@dataclass(frozen=True)
class VolumetricSpec:
    """A volumetric-error model: ``model`` ((name, coefficients) pairs by ISO 230-1 name, as in the
    bundle: mm or rad, position in mm); ``thermal`` ((axis, rate [mm/s], k = 1/τ [1/s]), …:
    :func:`thermal_drift`, k = 0 linear); ``backlash`` ((axis, reversal [mm]), …); ``cyclic``
    ((axis, a [mm], b [mm], period [mm]), …: e_axis += a·sin(2π·pos/period) + b·cos(2π·pos/period));
    ``additive`` callables (experiment, points (n, 3)) → (n, 3) [mm]."""

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
        ωz = c, EC0Y = −c (netshape.machine: EC0Y > 0 gives ex = −EC0Y·y, the axes at 90° + EC0Y).
        In a held-out fold (:attr:`fit_mask` set) the frame is fitted on the fold's fitting points."""
        if pred is None:
            pred = self.machine_predict(spec)
        r = np.concatenate([m - p for m, p in zip(self.measured, pred)])
        P = np.concatenate([e.points for e in self.experiments])
        if self.fit_mask is not None:  # a held-out fold: the frame is fitted on its fitting points
            keep = np.concatenate(self.fit_mask)
            r, P = r[keep], P[keep]
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
            for axis, rate, k in spec.thermal:
                p[:, _AXES.index(axis)] += thermal_drift(e.times, rate, k)
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


# the catalogue entries register themselves on import (and are importable from here)
from .volumetric_catalogue import (  # noqa: E402,F401
    LINEAR_DRIFT_TAU, Backlash, CyclicError, ScaleError, SpindleTilt, Squareness, ThermalDrift,
)
