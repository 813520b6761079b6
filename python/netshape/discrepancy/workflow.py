"""diagnose(bundle) → Diagnosis: residuals, localisation, catalogue fits, selection, repeat.

Rounds. With the current model (the bundle's model plus the effects added so far):
1. residuals and their localisation (``Diagnosis.localisation``, first round);
2. every applicable catalogue effect of the bundle's kind not yet added is fitted (SciPy
   least_squares), its rms, held-out rms (cross-validation: leave one experiment out with ≥ 3
   experiments, else 4 blocks of points) and BIC = n·ln(RSS/n) + k·ln n (k counts the parameters of
   all effects in the model, n the residual values) are recorded (``candidates``);
3. the effect with the smallest BIC among those that lower the BIC by more than 10 and the held-out
   rms by more than 1 % is added;
4. stop when the rms is within 10 % of the noise estimate (the residual is consistent with the
   noise), when no effect qualifies, or when every effect has been added. No effect added →
   ``effect`` None: "no missing effect found".
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .bundle import Bundle, load_bundle
from .catalogue import catalogue

#: BIC must drop by more than this to add an effect ("very strong" evidence on Kass & Raftery's scale).
BIC_MARGIN = 10.0
#: the held-out rms must drop by more than this fraction.
CV_MARGIN = 0.01
#: the residual counts as noise when its rms is within this factor of the noise estimate.
NOISE_FACTOR = 1.10
#: two covariates "move together" above this |correlation| (issue 37 item 5).
CONFOUND_CORR = 0.95
#: two candidates explain the residual equally when their BICs differ by less than this.
EQUAL_BIC = 2.0
#: the measurement that separates an effect on this covariate from one on another
SEPARATE_BY = {
    "time": "measure in random order (or repeat the grid later), so time does not follow position",
    "position": "measure in random order, so position does not follow time",
    "tool_length": "add an experiment with another tool length",
    "direction": "approach every point from both directions",
    "feed": "add a second feed",
    "angle": "record more revolutions",
}


@dataclass
class Diagnosis:
    """Result of :func:`diagnose`. ``effects``: every effect added, in order ({effect, parameters,
    rms_after}); ``candidates``: first round ({effect, rms, cv_rms, bic}); ``rounds``: the candidates
    of every round; rms and noise in the data's unit (N or mm)."""

    kind: str
    effects: list
    rms_before: float
    rms_after: float
    noise_estimate: float
    candidates: list
    rounds: list = field(default_factory=list)
    localisation: dict = field(default_factory=dict)
    localisation_after: dict = field(default_factory=dict)
    skipped: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)
    experiments: list = field(default_factory=list)
    unit: str = ""
    problem: Any = None
    spec_before: Any = None
    spec_after: Any = None
    noise_source: str = "estimated"
    noise_assumption: str = ""
    unexplained: list = field(default_factory=list)
    #: candidates the bundle cannot tell apart: [{effects, reason, measure}]
    ambiguous: list = field(default_factory=list)
    #: the registered measurement frame after the added effects (volumetric bundles; None otherwise):
    #: {rotation_urad: [rx, ry, rz], translation_mm: [tx, ty, tz]}
    frame: dict | None = None
    #: the bundle's folder (named in the comments of an updated model file)
    bundle_path: str = ""

    @property
    def effect(self) -> str | None:
        return self.effects[0]["effect"] if self.effects else None

    @property
    def parameters(self) -> dict:
        return dict(self.effects[0]["parameters"]) if self.effects else {}

    def apply(self, model):
        """The model with the found effects added: ``model`` is the text of a model file (machine TOML
        for a volumetric bundle, tool TOML for a wall bundle, cutter/coefficients TOML for a force
        bundle) or a path to one; returns the new text (comments name this diagnosis). No effect found:
        the text unchanged. See :func:`netshape.discrepancy.update.apply`."""
        from .update import apply

        return apply(self, model)

    def to_dict(self) -> dict:
        """The machine-readable result (the keys of ``netshape diagnose --json``)."""
        return _clean(
            {
                "kind": self.kind,
                "effect": self.effect,
                "parameters": self.parameters,
                "effects": [dict(e) for e in self.effects],
                "rms_before": self.rms_before,
                "rms_after": self.rms_after,
                "noise_estimate": self.noise_estimate,
                "candidates": [dict(c) for c in self.candidates],
                "noise_source": self.noise_source,
                "noise_assumption": self.noise_assumption,
                "unexplained": [dict(f) for f in self.unexplained],
                "frame": dict(self.frame) if self.frame is not None else None,
                "ambiguous": [dict(a) for a in self.ambiguous],
            }
        )

    def summary(self) -> str:
        u = self.unit
        lines = [
            f"{self.kind}: rms {self.rms_before:.4g} {u} before, {self.rms_after:.4g} {u} after, "
            f"noise {self.noise_estimate:.4g} {u} ({self.noise_source})"
        ]
        if not self.effects and self.rms_after <= NOISE_FACTOR * self.noise_estimate and not self.unexplained:
            lines.append("no missing effect found")
        elif not self.effects:
            lines.append("no catalogue effect found; the residual is not noise")
        for e in self.effects:
            p = ", ".join(
                f"{k} = {v:.4g}" if isinstance(v, float) else f"{k} = {v}" for k, v in e["parameters"].items()
            )
            lines.append(f"  + {e['effect']} ({p}): rms {e['rms_after']:.4g} {u}")
        seen = set()
        for r in self.rounds:
            for c in r:
                if c.get("rejected") and c["effect"] not in seen:
                    seen.add(c["effect"])
                    lines.append(f"  - {c['effect']} not added: {c['rejected']}")
        for f in self.unexplained:
            extra = f", period {f['period']:.4g}" if "period" in f else (f", at {f['at']:.4g}" if "at" in f else "")
            lines.append(
                f"  ? unexplained: {f['component']} {f['form']} against {f['covariate']}{extra}: "
                f"rms {f['rms']:.4g} {u}"
            )
        for a in self.ambiguous:
            lines.append(f"  ! ambiguous: {', '.join(a['effects'])}: {a['reason']}; to separate them: {a['measure']}")
        if self.frame is not None:
            r, t = self.frame["rotation_urad"], self.frame["translation_mm"]
            lines.append(
                "  frame (ISO 230-1, X primary, Y secondary): rotation ["
                + ", ".join(f"{v:.3g}" for v in r) + "] µrad, translation ["
                + ", ".join(f"{v:.3g}" for v in t) + f"] {u}"
            )
        lines += [f"note: {n}" for n in self.notes]
        return "\n".join(lines)


def make_problem(bundle: Bundle, machine=None):
    if bundle.kind == "cutting_force":
        from .force_effects import ForceProblem

        return ForceProblem(bundle)
    if bundle.kind == "volumetric_error":
        from .volumetric_effects import VolumetricProblem

        return VolumetricProblem(bundle, machine)
    if bundle.kind == "wall_error":
        from .wall_effects import WallProblem

        return WallProblem(bundle)
    raise ValueError(f"kind = {bundle.kind!r}: no workflow for it")


def diagnose(bundle, *, effects=None, max_effects: int = 4, machine=None) -> Diagnosis:
    """Find what the bundle's model misses. ``bundle``: a :class:`Bundle` or a path to one;
    ``effects``: names of the catalogue entries to consider (default all of the bundle's kind);
    ``machine``: a machine TOML path, the current model of a volumetric bundle instead of its
    ``[model]`` (the machine's tables, cyclic terms, backlash and thermal drift included)."""
    if not isinstance(bundle, Bundle):
        bundle = load_bundle(bundle)
    if machine is not None and bundle.kind != "volumetric_error":
        raise ValueError(f"machine = {str(machine)!r}: only a volumetric_error bundle is diagnosed against a "
                         f"machine file (this bundle is {bundle.kind})")
    problem = make_problem(bundle, machine)
    from . import force_effects, volumetric_effects, wall_effects  # noqa: F401  (register the built-in catalogue)

    cat = catalogue(bundle.kind)
    if effects is not None:
        unknown = [n for n in effects if n not in cat]
        if unknown:
            raise ValueError(
                f"effects: {unknown[0]!r} is not in the {bundle.kind} catalogue ({', '.join(cat)})"
            )
        cat = {n: cat[n] for n in effects}
    skipped = {}
    for name, eff in list(cat.items()):
        why = eff.applicable(problem)
        if why:
            skipped[name] = why
            del cat[name]
    spec = problem.initial_spec()
    spec0 = spec
    k_nuis = len(problem.nuisance_experiments())
    rms_before = problem.rms(spec)
    noise, noise_source, noise_assumption = problem.noise_info(spec)
    loc = problem.localise(spec)
    added, rounds, chain = [], [], []
    k_total = k_nuis
    rms_cur = rms_before
    cv_cur = rms_before
    bic_cur = problem.bic(spec, k_total)
    fit_notes = []
    ambiguous = []
    while cat and len(added) < max_effects:
        if rounds and rms_cur <= NOISE_FACTOR * noise:
            break
        round_ = []
        for name, eff in cat.items():
            try:
                fit = eff.fit(problem, spec)
            except (ValueError, FloatingPointError) as exc:  # an effect that cannot be fitted here
                skipped[name] = f"fit failed: {exc}"
                continue
            base = problem.with_nuisance(spec, problem.nuisance_of(fit.spec))
            make, x0, bnd = eff.refit(problem, base, fit)
            cv = problem.cv_rms(make, _null_start(eff, problem, base, x0), bnd)
            cv_bad = getattr(problem, "last_cv_not_converged", 0)
            rms = problem.rms(fit.spec)
            bic = problem.bic(fit.spec, k_total + fit.k)
            c = {"effect": name, "rms": rms, "cv_rms": cv, "bic": bic, "_fit": fit,
                 "converged": fit.status is None or fit.status > 0, "cv_folds_not_converged": int(cv_bad)}
            if not c["converged"]:
                fit_notes.append(
                    f"{name}: the fit did not converge (least_squares status {fit.status}"
                    + (": max_nfev reached)" if fit.status == 0 else ")")
                )
            why = eff.implausible(problem, fit, x0, bnd)
            if why:
                c["rejected"] = f"implausible: {why}"
            round_.append(c)
        rounds.append(round_)
        for a in identifiability(problem, cat, round_, bic_cur):
            if all(a["effects"] != b["effects"] for b in ambiguous):
                ambiguous.append(a)
        if rms_cur <= NOISE_FACTOR * noise:
            break
        ok = [
            c
            for c in round_
            if "rejected" not in c and c["bic"] < bic_cur - BIC_MARGIN and c["cv_rms"] < (1 - CV_MARGIN) * cv_cur
        ]
        if not ok:
            break
        best = min(ok, key=lambda c: c["bic"])
        fit = best["_fit"]
        spec = fit.spec
        k_total += fit.k
        rms_cur, cv_cur, bic_cur = best["rms"], best["cv_rms"], best["bic"]
        chain.append((cat[best["effect"]], fit))
        added.append({"effect": best["effect"], "parameters": fit.parameters, "rms_after": rms_cur})
        if len(chain) > 1:  # refit all added effects together: earlier ones were fitted without this one
            chain, spec = _joint_refit(
                problem, problem.with_nuisance(spec0, problem.nuisance_of(spec)), chain
            )
            if getattr(problem, "last_status", 1) <= 0:
                fit_notes.append(
                    f"the joint refit of {', '.join(e['effect'] for e in added)} did not converge "
                    f"(least_squares status {problem.last_status})"
                )
            for entry, (eff, f) in zip(added, chain):
                entry["parameters"] = f.parameters
            rms_cur = problem.rms(spec)
            bic_cur = problem.bic(spec, k_total)
            added[-1]["rms_after"] = rms_cur
        del cat[best["effect"]]
    clean = [[{k: v for k, v in c.items() if k != "_fit"} for c in r] for r in rounds]
    notes = list(getattr(problem, "notes", [])) + fit_notes
    # The residual is consistent with the noise only when its rms is within NOISE_FACTOR of it *and*
    # no trend, step or period stands out of it (a 0.8 µm drift under 1 µm of noise passes the first
    # test alone): the structure search runs whenever the noise is known.
    unexplained = []
    if noise > 0:
        from .structure import find_structure

        comps, covs = problem.structure_covariates(spec)
        r = np.concatenate(problem.residuals(spec))
        unexplained = find_structure(r, comps, covs, noise)
    if noise_source == "estimated":
        notes.append(f"noise estimated from the residual (no repeats, no [noise] in the manifest): assumes {noise_assumption}")
    if not added and rms_before <= NOISE_FACTOR * noise and not unexplained:
        notes.append("no missing effect found (the residual is consistent with the noise)")
    elif not added and rms_before <= NOISE_FACTOR * noise:
        notes.append(
            f"no catalogue effect added: the residual's rms ({rms_before:.4g} {problem.unit}) is near the noise "
            f"({noise:.4g} {problem.unit}) but holds structure (see unexplained)"
        )
    elif not added:
        notes.append(
            f"no catalogue effect explains the residual ({rms_before:.4g} {problem.unit} against noise "
            f"{noise:.4g} {problem.unit}): something the catalogue does not hold remains"
            + (" (see unexplained)" if unexplained else "")
        )
    elif rms_cur > NOISE_FACTOR * noise:
        notes.append(
            f"the residual after the added effects ({rms_cur:.4g} {problem.unit}) is still above the "
            f"noise ({noise:.4g} {problem.unit}): something the catalogue does not hold remains"
            + (" (see unexplained)" if unexplained else "")
        )
    elif unexplained:
        notes.append("the residual after the added effects still holds structure (see unexplained)")
    return Diagnosis(
        kind=bundle.kind,
        effects=added,
        rms_before=rms_before,
        rms_after=rms_cur,
        noise_estimate=noise,
        candidates=clean[0] if clean else [],
        rounds=clean,
        localisation=loc,
        localisation_after=problem.localise(spec) if added else loc,
        skipped=skipped,
        notes=notes,
        experiments=problem.experiment_notes(spec),
        unit=problem.unit,
        problem=problem,
        spec_before=spec0,
        spec_after=spec,
        noise_source=noise_source,
        noise_assumption=noise_assumption,
        unexplained=unexplained,
        frame=problem.frame(spec) if hasattr(problem, "frame") else None,
        ambiguous=ambiguous,
        bundle_path=str(bundle.path),
    )


def identifiability(problem, cat, round_, bic_cur) -> list:
    """Candidates of one round the bundle cannot tell apart (issue 37 item 5):

    * an effect that lowers the BIC by more than BIC_MARGIN (added, rejected or not) and works on a
      covariate that moves with another effect's (|corr| > CONFOUND_CORR between any of their values,
      from ``problem.covariate_vectors()``): the two cannot be told apart by this bundle;
    * two candidates that both qualify and whose BICs differ by less than EQUAL_BIC.

    Returns [{effects, reason, measure}]."""
    out = []
    vecs = problem.covariate_vectors() if hasattr(problem, "covariate_vectors") else {}
    strong = [c for c in round_ if c["bic"] < bic_cur - BIC_MARGIN]
    for c in strong:
        cov_c = cat[c["effect"]].covariate
        for other, cov_o in sorted({(n, e.covariate) for n, e in cat.items()}):
            if other == c["effect"] or cov_o == cov_c or cov_c not in vecs or cov_o not in vecs:
                continue
            best = None
            for na, va in vecs[cov_c].items():
                for nb, vb in vecs[cov_o].items():
                    if np.std(va) == 0 or np.std(vb) == 0:
                        continue
                    r = abs(float(np.corrcoef(va, vb)[0, 1]))
                    if r > CONFOUND_CORR and (best is None or r > best[0]):
                        best = (r, na, nb)
            if best is None:
                continue
            a = {"effects": sorted([c["effect"], other]),
                 "reason": f"{best[1]} and {best[2]} move together (|corr| = {best[0]:.3f})",
                 "measure": SEPARATE_BY.get(cov_c, f"vary {cov_c} independently of {cov_o}")}
            if all(a["effects"] != b["effects"] for b in out):
                out.append(a)
    ok = sorted((c for c in strong if "rejected" not in c), key=lambda c: c["bic"])
    for c in ok[1:]:
        if c["bic"] - ok[0]["bic"] < EQUAL_BIC:
            e0, e1 = cat[ok[0]["effect"]], cat[c["effect"]]
            out.append({"effects": sorted([ok[0]["effect"], c["effect"]]),
                        "reason": f"they explain the residual equally (ΔBIC = {c['bic'] - ok[0]['bic']:.2f})",
                        "measure": SEPARATE_BY.get(e0.covariate if e0.covariate != e1.covariate else "",
                                                   f"vary {e0.covariate} and {e1.covariate} independently")
                        if e0.covariate != e1.covariate else
                        f"measure where {ok[0]['effect']} and {c['effect']} predict different errors"})
    return out


def _null_start(eff, problem, base, x_fit):
    """Start of the cross-validation folds: the effect's first start on the model without it (its
    parameters at their no-effect or catalogue default values), never the all-data optimum
    ``x_fit``, which has seen the test points. Falls back to ``x_fit`` only when the effect's starts
    do not match its refit parameters (a user effect with its own refit)."""
    try:
        x = np.atleast_1d(np.asarray(eff.starts(problem, base)[0], float))
    except Exception:  # noqa: BLE001 (a user effect without starts)
        return x_fit
    x_fit = np.atleast_1d(np.asarray(x_fit, float))
    return x if x.shape == x_fit.shape else x_fit


def _joint_refit(problem, base, chain):
    """Refit the parameters of every effect in ``chain`` [(effect, EffectFit)] together (their
    discrete choices kept), applied in order to ``base``. Returns (new chain, spec)."""
    import numpy as np

    from .catalogue import EffectFit

    parts, x0, lo, hi = [], [], [], []
    s = base
    for eff, fit in chain:
        make, x, (blo, bhi) = eff.refit(problem, s, fit)
        x = np.atleast_1d(np.asarray(x, float))
        parts.append(slice(len(x0), len(x0) + x.size))
        x0 += list(x)
        lo += list(np.broadcast_to(blo, x.shape))
        hi += list(np.broadcast_to(bhi, x.shape))
        s = make(x)

    def make_all(z):
        s = base
        for (eff, fit), sl in zip(chain, parts):
            s = eff.refit(problem, s, fit)[0](z[sl])
        return s

    z, spec = problem.least_squares(make_all, [np.array(x0)], (np.array(lo), np.array(hi)))
    new = []
    for (eff, fit), sl in zip(chain, parts):
        full = np.concatenate([fit.x[: fit.x.size - (sl.stop - sl.start)], z[sl]])
        new.append((eff, EffectFit(eff.parameters_of(full), spec, fit.k, full, problem.last_status)))
    return new, spec


def _clean(v):
    """JSON-safe: non-finite floats → None, NumPy scalars → Python."""
    if isinstance(v, dict):
        return {k: _clean(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_clean(x) for x in v]
    if hasattr(v, "item") and not isinstance(v, str):
        v = v.item()
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v
