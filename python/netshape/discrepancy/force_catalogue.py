"""The cutting-force catalogue entries ``runout``, ``edge_forces``, ``size_effect`` and
``structural_mode`` (how each extends the linear edge-force model is described in
:mod:`netshape.discrepancy.force_effects`); importing this module registers them."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .catalogue import Effect, EffectFit, register_effect
from .force_effects import GRID


# Physical ranges (issue 37 item 4): a fit at or beyond one is rejected as implausible; generous
# limits for end milling, not tuned on any test case.
#: radial runout of the cutter [mm]
RUNOUT_MAX_MM = 0.1
#: edge (ploughing) coefficients Kte, Kre, Kae [N/mm]
EDGE_RANGE_N_PER_MM = (-200.0, 500.0)
#: chip-thickness exponent of the size effect
CHIP_EXPONENT_RANGE = (0.3, 1.5)
#: damping ratio of a tool or dynamometer mode
DAMPING_RANGE = (0.003, 0.5)


class Runout(Effect):
    name, kind = "runout", "cutting_force"
    parameters = ("rho_mm", "lambda_deg")
    covariate = "angle"
    description = (
        "cutter runout: the tool axis offset by rho at angle lambda, flute j cuts at radius "
        "R + rho·cos(lambda − j·2π/N) (chip h_j = c·sin φ + R_j − R_{j−1}, clamped at 0); with 2 "
        "flutes the chip offsets are ±2·rho·cos(lambda), so only rho·cos(lambda) is identifiable and "
        "it is reported as lambda = 0 or 180 deg"
    )

    def applicable(self, problem):
        return None if problem.flutes >= 2 else "runout needs at least 2 flutes"

    def starts(self, problem, spec):
        c = min(e.feed_per_tooth for e in problem.experiments)
        if problem.flutes == 2:
            return [np.array([0.1 * c]), np.array([-0.1 * c])]
        return [np.array([0.2 * c, lam]) for lam in np.radians([0.0, 90.0, 180.0, 270.0])]

    def bounds(self, problem, spec):
        if problem.flutes == 2:
            return (np.array([-2.0]), np.array([2.0]))
        return (np.array([0.0, -4 * np.pi]), np.array([2.0, 4 * np.pi]))

    def physical_bounds(self, problem):
        return {"rho_mm": (-1e-9, RUNOUT_MAX_MM)}

    def apply(self, problem, spec, x):
        if len(x) == 1:  # 2 flutes: x = ρ·cos λ
            return dataclasses.replace(spec, runout=(abs(float(x[0])), 0.0 if x[0] >= 0 else math.pi))
        return dataclasses.replace(spec, runout=(float(x[0]), float(x[1])))

    def fit(self, problem, spec, train=None):
        """The least-squares fit, then, for time series, the flute each recording calls 1 is made the
        same physical flute: each recording's θ0 is tried at its N equivalent values θ0 + m·2π/N
        (equal without runout, different with it) and the fit is repeated from the best."""
        f = super().fit(problem, spec, train)
        nuis = problem.nuisance_experiments()
        if train is not None or not nuis:
            return f
        for _ in range(3):
            s = f.spec
            phases = list(problem.nuisance_of(s))
            changed = False
            for col, i in enumerate(nuis):
                costs = []
                for m in range(problem.flutes):
                    trial = problem.with_nuisance(
                        s,
                        [
                            p + (2 * np.pi * m / problem.flutes if c == col else 0.0)
                            for c, p in enumerate(phases)
                        ],
                    )
                    costs.append(float(np.sum((problem.measured[i] - problem.predict(trial)[i]) ** 2)))
                m = int(np.argmin(costs))
                if m and costs[m] < 0.999 * costs[0]:
                    phases[col] += 2 * np.pi * m / problem.flutes
                    changed = True
            if not changed:
                break
            base = problem.with_nuisance(spec, phases)
            x, new = problem.least_squares(
                lambda x: self.apply(problem, base, x), [f.x], self.bounds(problem, base)
            )
            f = EffectFit(self.parameters_of(x), new, len(x), x, problem.last_status)
        return f

    def parameters_of(self, x):
        if len(x) == 1:
            return {"rho_mm": abs(float(x[0])), "lambda_deg": 0.0 if x[0] >= 0 else 180.0}
        return {"rho_mm": float(x[0]), "lambda_deg": float(np.degrees(x[1]) % 360.0)}


class EdgeForces(Effect):
    name, kind = "edge_forces", "cutting_force"
    parameters = ("Kte_N_per_mm", "Kre_N_per_mm", "Kae_N_per_mm")
    covariate = "feed"
    description = (
        "edge (ploughing) forces: Kte, Kre, Kae refitted (the forces per unit edge length that do "
        "not grow with the chip)"
    )

    def physical_bounds(self, problem):
        return {k: EDGE_RANGE_N_PER_MM for k in self.parameters}

    def starts(self, problem, spec):
        return [np.asarray(spec.coefficients[3:], float)]

    def apply(self, problem, spec, x):
        return dataclasses.replace(
            spec, coefficients=tuple(spec.coefficients[:3]) + tuple(float(v) for v in x)
        )

    def parameters_of(self, x):
        return {k: float(v) for k, v in zip(self.parameters, x)}


class SizeEffect(Effect):
    name, kind = "size_effect", "cutting_force"
    parameters = ("chip_exponent",)
    covariate = "feed"
    description = (
        "chip-size effect: cutting forces grow as h_ref·(h/h_ref)^p instead of h (p < 1: thin "
        "chips cut relatively harder; h_ref the geometric mean feed per tooth of the bundle)"
    )

    def physical_bounds(self, problem):
        return {"chip_exponent": CHIP_EXPONENT_RANGE}

    def starts(self, problem, spec):
        return [np.array([0.8]), np.array([1.2])]

    def bounds(self, problem, spec):
        return (np.array([0.1]), np.array([2.0]))

    def apply(self, problem, spec, x):
        return dataclasses.replace(spec, chip_exponent=float(x[0]))

    def parameters_of(self, x):
        return {"chip_exponent": float(x[0])}


class StructuralMode(Effect):
    name, kind = "structural_mode", "cutting_force"
    parameters = ("frequency_hz", "damping_ratio")
    covariate = "frequency"
    description = (
        "a lightly damped mode of the tool or dynamometer: the measured force is the cutting force "
        "through ω_n²/(ω_n² − ω² + 2iζω_nω)"
    )

    def _range(self, problem):
        # tooth-passing frequency … the highest harmonic both the grid and the sampling resolve
        f_tooth = max(w for w in problem.omega) * problem.flutes / (2 * np.pi)
        f_hi = []
        for i, e in enumerate(problem.experiments):
            f_rev = problem.omega[i] / (2 * np.pi)
            if e.time_based:
                f_hi.append(0.45 / float(np.median(np.diff(e.times))))
            else:
                per_rev = 2 * np.pi / float(np.median(np.abs(np.diff(e.angles))))
                f_hi.append(0.45 * per_rev * f_rev)
            f_hi.append(0.45 * GRID * f_rev)
        return 1.5 * f_tooth, min(f_hi)

    def applicable(self, problem):
        lo, hi = self._range(problem)
        return (
            None if hi > 1.2 * lo else "sampling too coarse to see a mode above the tooth-passing frequency"
        )

    def starts(self, problem, spec):
        lo, hi = self._range(problem)
        best = []
        for f in np.geomspace(lo, hi, 30):
            for z in (0.03, 0.12):
                s = dataclasses.replace(spec, mode=(float(f), z))
                best.append((problem.fit_rms(s), f, z))
        best.sort()
        return [np.array([f, z]) for _, f, z in best[:2]]

    def physical_bounds(self, problem):
        return {"damping_ratio": DAMPING_RANGE}

    def bounds(self, problem, spec):
        lo, hi = self._range(problem)
        return (np.array([0.5 * lo, 0.002]), np.array([1.2 * hi, 0.7]))

    def apply(self, problem, spec, x):
        return dataclasses.replace(spec, mode=(float(x[0]), float(x[1])))

    def parameters_of(self, x):
        return {"frequency_hz": float(x[0]), "damping_ratio": float(x[1])}


for _e in (Runout(), EdgeForces(), SizeEffect(), StructuralMode()):
    register_effect(_e, replace=True)
