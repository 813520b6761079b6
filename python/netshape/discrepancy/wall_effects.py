"""Wall-error bundles: the surface-generation wall error of a steady straight cut predicted by
netshape.deflection (C++: the cantilever tool under the flat end mill force at the instant the wall at
height z is generated), extended by the catalogue entries ``holder_compliance`` and ``runout``.

Models (error e [mm], + where material is left; n the wall normal from the tool axis to the wall):

* base: e₀(z) = −δ(z)·n, δ the cantilever deflection at height z when flute 1 passes the wall angle
  (netshape.deflection.wall_errors);
* holder_compliance: a translational spring of stiffness k at the holder/spindle carries the cutting
  force F(z) of that same instant, so the whole tool translates rigidly by F/k:
  e = e₀(z) − (F(z)·n)/k. Parameters ``stiffness_N_per_um`` (k) and ``compliance_um_per_N`` (1/k);
* runout: the tool axis is offset by ρ at angle λ, flute j (0 = flute 1) cuts at radius
  R_j = R + r_j, r_j = ρ·cos(λ − j·2π/N) (the cutting-force convention). Flute 1 generates the wall at
  height z at the feed positions x₁(z) + m·N·c (x₁(z) = N·c·k_β·z/2π, c the feed per tooth,
  k_β = tan β / R), flute j at x₁(z) + (j + m·N)·c; each pass leaves a circular arc of radius R_j,
  and the wall is the deepest of them: e = e₀(z) − max_passes [r_j − (x − x_pass)²/(2R_j)]. The
  change of the chip loads, and so of the deflection, by the runout is not modelled. With N ≤ 2
  only ρ·cos λ is identifiable; it is reported as λ = 0 or 180°. Parameters ``rho_mm``, ``lambda_deg``.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from .bundle import WallContourExperiment
from .catalogue import Effect, register_effect
from .problem import Problem, robust_difference_noise


@dataclass(frozen=True)
class WallSpec:
    """A wall-error model: the bundle's deflection model plus ``compliance`` [mm/N] of a holder
    spring, ``runout`` (ρ [mm], λ [rad]) or None, and ``additive`` callables
    (experiment, points (n, 2) of x, z [mm]) → (n, 1) [mm]."""

    compliance: float = 0.0
    runout: tuple | None = None
    additive: tuple = ()


#: heights per point at which the contour prediction gives the wall error (bottom to top of the cut)
PROFILE_LEVELS = 21


def contour_arc_length(nominal: np.ndarray) -> np.ndarray:
    """Distance along the polyline ``nominal`` (n, 3) from its first point, in XY [mm] (the x_mm of a
    contour experiment)."""
    step = np.hypot(np.diff(nominal[:, 0]), np.diff(nominal[:, 1]))
    return np.concatenate([[0.0], np.cumsum(step)])


def contour_wall_model(e, model: dict):
    """The deflection prediction along a contour experiment's program: (s (n,) arc length [mm],
    profile (n, L) wall error at z_k = A·k/(L − 1) [mm], A (n,) axial depth [mm], F·n (n,) force on
    the cutter along the wall normal at the middle level's generating instant [N], engaged (n,) bool,
    feed per tooth [mm]). The program, tool and stock are read here (netshape.deflection.setup_path /
    predict_path: the Z-map engagement and the cantilever deflection are C++)."""
    from netshape import deflection as d
    from netshape.deflection import load_stock
    from netshape.toolpath import read_gcode

    where = f"{e.file}: program {e.program!r}"
    try:
        stock = load_stock(e.stock)
        prog = read_gcode(e.program)
        setup = d.setup_path(prog, e.cutter, stock, coefficients=model["coefficients"], rpm=e.spindle_rpm,
                             spacing=e.spacing, inertia=model["inertia"], load=model["load"], side=e.side,
                             profile_levels=PROFILE_LEVELS)
        r = d.predict_path(setup)
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None
    nominal = np.asarray(setup.nominal, float)
    normals = np.asarray(d.wall_normals(nominal, setup.side), float)
    fn = np.sum(np.asarray(r.force, float) * normals, axis=1)
    feed = float(prog.blocks[setup.first].feed)
    c = feed * 60.0 / (e.spindle_rpm * e.cutter.flutes)
    return (contour_arc_length(nominal), np.asarray(r.profile, float), np.asarray(r.depth, float), fn,
            np.asarray(r.engaged) > 0, c)


def _contour_model(e, model: dict):
    """(e₀ (n,) [mm], F·n (n,) [N], z (n,) [mm], feed per tooth [mm]) at a contour experiment's
    measured points: linear in x between the prediction's points and in z between its profile levels;
    z NaN is the middle of the cut."""
    s, profile, depth, fn, engaged, c = contour_wall_model(e, model)
    x = e.x
    if x.max() > s[-1] + 1e-9:
        j = int(np.argmax(x > s[-1] + 1e-9))
        raise ValueError(f"{e.file}: line {j + 2}, column 'x_mm': {float(x[j])!r} lies beyond the contour's "
                         f"end ({s[-1]:.6g} mm along it)")
    k = np.clip(np.searchsorted(s, x, side="right") - 1, 0, len(s) - 2)
    t = np.clip((x - s[k]) / np.maximum(s[k + 1] - s[k], 1e-300), 0.0, 1.0)
    off = ~(engaged[k] & engaged[k + 1])
    if off.any():
        j = int(np.argmax(off))
        raise ValueError(f"{e.file}: line {j + 2}, column 'x_mm': {float(x[j])!r}: the tool does not cut "
                         "there (no wall is generated at this distance along the contour)")
    A = (1 - t) * depth[k] + t * depth[k + 1]
    z = np.where(np.isnan(e.z), 0.5 * A, e.z)
    high = z > A * (1 + 1e-9)
    if high.any():
        j = int(np.argmax(high))
        raise ValueError(f"{e.file}: line {j + 2}: z_mm = {float(z[j])!r} lies above the cut "
                         f"(axial depth {float(A[j]):.6g} mm there)")
    L = profile.shape[1]
    f = np.clip(z / np.maximum(A, 1e-300) * (L - 1), 0.0, L - 1)
    lo = np.minimum(np.floor(f).astype(int), L - 2)
    u = f - lo
    prof = (1 - t)[:, None] * profile[k] + t[:, None] * profile[k + 1]
    rows = np.arange(len(x))
    base = (1 - u) * prof[rows, lo] + u * prof[rows, lo + 1]
    return base, (1 - t) * fn[k] + t * fn[k + 1], z, c


class WallProblem(Problem):
    kind = "wall_error"
    unit = "mm"

    def __init__(self, bundle):
        from netshape import deflection as d

        self.bundle = bundle
        self.experiments = bundle.experiments
        self.measured = [np.asarray(e.errors, float).reshape(-1, 1) for e in self.experiments]
        t = bundle.tool
        self.radius = 0.5 * t["diameter"]
        self.flutes = int(t["flutes"])
        self.k_beta = math.tan(math.radians(t["helix_deg"])) / self.radius
        self.notes = []
        # per experiment: e₀, F·n, height z of each point, feed per tooth, flute 1's pass position
        self._base, self._fn, self._z, self._c, self._shift = [], [], [], [], []
        for e in self.experiments:
            if isinstance(e, WallContourExperiment):
                base, fn, z, c = _contour_model(e, bundle.model)
                self._base.append(base)
                self._fn.append(fn)
                self._z.append(z)
                self._c.append(c)
                self._shift.append(self.flutes * c * self.k_beta * z / (2 * math.pi))
                continue
            self._z.append(np.asarray(e.z, float))
            m = d.make_model(
                diameter=t["diameter"], flutes=self.flutes, helix_deg=t["helix_deg"], stick_out=t["stick_out"],
                youngs_modulus=t["youngs_modulus"], feed_per_tooth=e.feed_per_tooth, ap=e.axial_depth,
                ae=e.radial_depth, mode=e.mode, coefficients=bundle.model["coefficients"],
                inertia=bundle.model["inertia"], load=bundle.model["load"],
                holder_compliance=t.get("holder_compliance", 0.0),
            )
            zu, inv = np.unique(e.z, return_inverse=True)
            w = d.wall_errors(m, d.DeflectionWorkspace(m), getattr(d.WallSide, e.side), zu)
            ny = 1.0 if e.side == "left" else -1.0
            self._base.append(np.asarray(w.error, float)[inv])
            self._fn.append(np.asarray(w.force, float)[inv, 1] * ny)  # F·n [N] at the generating instant
            self._c.append(e.feed_per_tooth)
            # feed position of flute 1's generating pass at height z [mm]
            self._shift.append(self.flutes * e.feed_per_tooth * self.k_beta * e.z / (2 * math.pi))

    def initial_spec(self):
        """The bundle's model: its tool's holder compliance is inside e₀ (C++), its runout here."""
        t = self.bundle.tool
        return WallSpec(runout=(t["runout_rho"], t["runout_lambda"]) if t.get("runout_rho") else None)

    def runout_term(self, i, rho, lam) -> np.ndarray:
        """−max over passes of the reach r_j − d²/(2R_j) at the points of experiment i [mm]."""
        e = self.experiments[i]
        N, c, R = self.flutes, self._c[i], self.radius
        r = rho * np.cos(lam - 2 * np.pi * np.arange(N) / N)
        s = e.x - self._shift[i]
        # passes farther than D from a point cannot be the deepest (see the module docstring)
        D = math.sqrt(4 * R * abs(rho) + (0.5 * N * c) ** 2)
        K = math.ceil(D / c) + 1
        m = np.rint(s / c)[:, None] + np.arange(-K, K + 1)[None, :]
        j = np.mod(m, N).astype(int)
        rj = r[j]
        reach = rj - (s[:, None] - m * c) ** 2 / (2 * (R + rj))
        return -reach.max(axis=1)

    def predict(self, spec):
        out = []
        for i, e in enumerate(self.experiments):
            p = self._base[i] - spec.compliance * self._fn[i]
            if spec.runout is not None:
                p = p + self.runout_term(i, *spec.runout)
            p = p[:, None]
            for add in spec.additive:
                p = p + np.asarray(add(e, np.column_stack([e.x, self._z[i]])), float).reshape(-1, 1)
            out.append(p)
        return out

    def _order(self, i):
        e = self.experiments[i]
        return np.lexsort((e.x, self._z[i]))

    noise_assumption = (
        "the residual changes little between neighbouring points along x at one height (robust second "
        "differences): structure with a period of a few point spacings would be read as noise"
    )

    def structure_covariates(self, spec):
        """Component error; covariates x, z [mm], the revolution phase (deg) and the normal force [N]."""
        return ["error"], {
            "x": np.concatenate([np.asarray(e.x, float) for e in self.experiments]),
            "z": np.concatenate(self._z),
            "revolution_phase": np.concatenate([self.revolution_phase(i) for i in range(len(self.experiments))]),
            "normal_force": np.concatenate(self._fn),
        }

    def noise_estimate(self, spec) -> float:
        """Robust second-difference noise of the model residual along x within each height z [mm]."""
        num, den = 0.0, 0
        for i, r in enumerate(self.residuals(spec)):
            o = self._order(i)
            v, c = robust_difference_noise(r[o], self._z[i][o])
            num += v * c
            den += c
        return math.sqrt(num / den) if den else 0.0

    def revolution_phase(self, i) -> np.ndarray:
        """Angle of the spindle revolution [deg] at which each point's wall was generated by flute 1's
        position (0 where flute 1 generates it)."""
        e = self.experiments[i]
        return np.degrees(np.mod(2 * np.pi * (e.x - self._shift[i]) / (self.flutes * self._c[i]), 2 * np.pi))

    def localise(self, spec) -> dict:
        """Mean residual per experiment, correlation of the residual with the normal force at the
        generating instant and with z, and the amplitude of its once-per-revolution harmonic along x
        (runout shows there; a holder spring follows the force)."""
        res = self.residuals(spec)
        r = np.concatenate([ri[:, 0] for ri in res])
        out = {"residual_rms": self.rms(spec), "mean_per_experiment_mm": [float(ri.mean()) for ri in res]}
        corr = {}
        for name, v in (("normal_force_N", np.concatenate(self._fn)),
                        ("z_mm", np.concatenate(self._z))):
            if np.std(v) > 0 and np.std(r) > 0:
                corr[f"error~{name}"] = float(np.corrcoef(v, r)[0, 1])
        out["correlation"] = corr
        amps = []
        for i, ri in enumerate(res):
            ph = np.radians(self.revolution_phase(i))
            A = np.column_stack([np.ones_like(ph), np.cos(ph), np.sin(ph)])
            coef, *_ = np.linalg.lstsq(A, ri[:, 0], rcond=None)
            amps.append(float(math.hypot(coef[1], coef[2])))
        out["per_revolution_amplitude_mm"] = amps
        return out

    def covariates(self, spec) -> dict:
        return {
            "normal_force": list(self._fn),
            "revolution_phase": [self.revolution_phase(i) for i in range(len(self.experiments))],
        }

    def experiment_notes(self, spec) -> list:
        out = []
        for i, e in enumerate(self.experiments):
            if isinstance(e, WallContourExperiment):
                out.append({"file": e.file, "program": e.program, "side": e.side, "spindle_rpm": e.spindle_rpm,
                            "feed_per_tooth_mm": self._c[i]})
            else:
                out.append({"file": e.file, "mode": e.mode, "side": e.side,
                            "feed_per_tooth_mm": e.feed_per_tooth, "axial_depth_mm": e.axial_depth, "radial_depth_mm": e.radial_depth})
        return out


# Physical ranges (issue 37 item 4); a fit at or beyond one is rejected as implausible.
#: stiffness of the holder/spindle spring at the tool [N/µm]
HOLDER_STIFFNESS_RANGE_N_PER_UM = (0.2, 2000.0)
#: radial runout of the cutter [mm]
RUNOUT_MAX_MM = 0.1


class HolderCompliance(Effect):
    name, kind = "holder_compliance", "wall_error"
    parameters = ("stiffness_N_per_um", "compliance_um_per_N")
    covariate = "normal_force"
    description = (
        "a translational spring k at the holder/spindle: the tool translates rigidly by F/k, "
        "e = e₀ − (F·n)/k with F the force at the instant the wall is generated"
    )

    def physical_bounds(self, problem):
        return {"stiffness_N_per_um": HOLDER_STIFFNESS_RANGE_N_PER_UM}

    def starts(self, problem, spec):
        return [np.array([0.05])]

    def bounds(self, problem, spec):
        return (np.zeros(1), np.full(1, np.inf))

    def apply(self, problem, spec, x):
        return dataclasses.replace(spec, compliance=spec.compliance + float(x[0]) * 1e-3)

    def parameters_of(self, x):
        c = float(x[0])
        return {"stiffness_N_per_um": 1.0 / c if c > 0 else math.inf, "compliance_um_per_N": c}


class WallRunout(Effect):
    name, kind = "runout", "wall_error"
    parameters = ("rho_mm", "lambda_deg")
    covariate = "revolution_phase"
    description = (
        "cutter runout: flute j cuts at radius R + rho·cos(lambda − j·2π/N); the wall is the deepest "
        "arc left by the flute passes, e = e₀ − max(r_j − d²/2R_j)"
    )

    def physical_bounds(self, problem):
        return {"rho_mm": (-1e-9, RUNOUT_MAX_MM)}

    def starts(self, problem, spec):
        rho0 = max(2.0 * problem.rms(spec), 1e-3)
        if problem.flutes <= 2:
            return [np.array([rho0]), np.array([-rho0])]
        return [np.array([rho0, a]) for a in np.linspace(0, 2 * np.pi, 2 * problem.flutes, endpoint=False)]

    def bounds(self, problem, spec):
        lim = 0.2 * problem.radius
        if problem.flutes <= 2:
            return (np.full(1, -lim), np.full(1, lim))
        return (np.array([0.0, -np.inf]), np.array([lim, np.inf]))

    def apply(self, problem, spec, x):
        if len(x) == 1:  # ρ·cos λ signed, λ = 0
            return dataclasses.replace(spec, runout=(float(x[0]), 0.0))
        return dataclasses.replace(spec, runout=(float(x[0]), float(x[1])))

    def parameters_of(self, x):
        if len(x) == 1:
            return {"rho_mm": abs(float(x[0])), "lambda_deg": 0.0 if x[0] >= 0 else 180.0}
        return {"rho_mm": float(x[0]), "lambda_deg": float(np.degrees(x[1]) % 360.0)}


for _e in (HolderCompliance(), WallRunout()):
    register_effect(_e, replace=True)
