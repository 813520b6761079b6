"""What every bundle kind shares: residuals, the least-squares fit of an effect (SciPy), held-out
prediction error over folds, BIC and a model-free noise estimate.

A problem holds the measurements of one bundle; a *specification* (``spec``) is an immutable
description of a model (the bundle's model plus the effects added so far). ``predict(spec)`` gives
one (n, 3) array per experiment. Some specifications carry *nuisance* parameters of the measurement
itself (the angle of flute 1 at t = 0 of a time series): they are refitted with every effect on all
points and held fixed in the cross-validation folds.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import least_squares as _scipy_least_squares


class Problem:
    """Base class; subclasses set ``experiments``, ``measured`` (list of (n, 3)) and implement
    ``predict``, ``initial_spec``, ``noise_estimate``, ``localise``, ``covariates``."""

    kind = ""
    unit = ""
    experiments: list
    measured: list
    #: the points a fit may see, one boolean mask per experiment (None: all). Set while a held-out
    #: fold is fitted and evaluated: what a model fits from the data besides its parameters (the
    #: volumetric frame, start values read off the residual) is then fitted on these points only.
    fit_mask: list | None = None

    # --- nuisance parameters (none by default) ---------------------------------------------------
    def nuisance_experiments(self) -> list:
        """Indices of experiments with one nuisance parameter each."""
        return []

    def nuisance_of(self, spec) -> np.ndarray:
        return np.zeros(0)

    def with_nuisance(self, spec, values):
        return spec

    # --- noise and structure ---------------------------------------------------------------------
    #: the assumption behind :meth:`noise_estimate` (stated in the diagnosis when it is used)
    noise_assumption = "the residual's scatter after a model-free smoother is noise"

    def repeat_noise(self, spec) -> tuple[float, int]:
        """(σ, dof) from points measured more than once; (0, 0) when the bundle has none."""
        return 0.0, 0

    def noise_info(self, spec) -> tuple[float, str, str]:
        """(σ, source, assumption) in order of preference: ``repeats`` (points measured more than once),
        ``stated`` (the manifest's [noise]), ``estimated`` (:meth:`noise_estimate`)."""
        from .structure import MIN_REPEAT_DOF

        sig, dof = self.repeat_noise(spec)
        if dof >= MIN_REPEAT_DOF and sig > 0:
            return sig, "repeats", (
                f"pooled scatter of repeated points about their means ({dof} degrees of freedom per component)"
            )
        stated = getattr(getattr(self, "bundle", None), "noise", {}) or {}
        if "sigma" in stated:
            return float(stated["sigma"]), "stated", "the instrument uncertainty stated in the manifest's [noise]"
        return self.noise_estimate(spec), "estimated", self.noise_assumption

    def structure_covariates(self, spec) -> tuple[list, dict]:
        """(component names, {covariate name: (n,) values over all points}) searched for unexplained
        structure; the default: the sample order only."""
        n = sum(m.shape[0] for m in self.measured)
        c = self.measured[0].shape[1]
        return [f"c{j}" for j in range(c)], {"order": np.arange(n, dtype=float)}

    # --- residuals ---------------------------------------------------------------------------------
    def predict(self, spec) -> list:
        raise NotImplementedError

    def residuals(self, spec) -> list:
        return [m - p for m, p in zip(self.measured, self.predict(spec))]

    def n_values(self) -> int:
        return int(sum(m.size for m in self.measured))

    def rms(self, spec, masks=None) -> float:
        r = self.residuals(spec)
        if masks is not None:
            r = [ri[mi] for ri, mi in zip(r, masks)]
        sq = sum(float(np.sum(ri**2)) for ri in r)
        cnt = sum(ri.size for ri in r)
        return math.sqrt(sq / max(cnt, 1))

    def fit_rms(self, spec) -> float:
        """rms over the points a fit may see (:attr:`fit_mask`)."""
        return self.rms(spec, self.fit_mask)

    def bic(self, spec, k: int) -> float:
        """n·ln(RSS/n) + k·ln n over all residual values (n = points × 3)."""
        n = self.n_values()
        rss = sum(float(np.sum(ri**2)) for ri in self.residuals(spec))
        return n * math.log(max(rss, 1e-300) / n) + k * math.log(n)

    # --- fitting -----------------------------------------------------------------------------------
    def least_squares(self, make_spec, starts, bounds, train=None, max_nfev=None):
        """Fit internal parameters x of ``make_spec(x)`` (→ spec) by SciPy ``least_squares`` (trf)
        from each start; with ``train`` None the nuisance parameters are fitted jointly, else the fit
        sees the ``train`` points only (:attr:`fit_mask`). Returns (x, spec) of the smallest cost."""
        if train is not None and self.fit_mask is None:
            self.fit_mask = train
            try:
                return self.least_squares(make_spec, starts, bounds, train, max_nfev)
            finally:
                self.fit_mask = None
        nuis = self.nuisance_experiments() if train is None else []
        best = None
        for x0 in starts:
            x0 = np.atleast_1d(np.asarray(x0, float))
            p = x0.size
            lo, hi = (np.broadcast_to(np.asarray(b, float), (p,)) for b in bounds)
            x0 = np.clip(x0, lo, hi)
            base = make_spec(x0)
            z0 = np.concatenate([x0, self.nuisance_of(base)]) if nuis else x0
            zlo = np.concatenate([lo, np.full(len(nuis), -np.inf)]) if nuis else lo
            zhi = np.concatenate([hi, np.full(len(nuis), np.inf)]) if nuis else hi

            def spec_of(z):
                s = make_spec(z[:p])
                return self.with_nuisance(s, z[p:]) if nuis else s

            def fun(z):
                r = self.residuals(spec_of(z))
                if train is not None:
                    r = [ri[mi] for ri, mi in zip(r, train)]
                out = np.concatenate([ri.ravel() for ri in r])
                return np.where(np.isfinite(out), out, 1e6)

            sparsity = None
            if nuis:
                rows = [ri.size for ri in self.measured]
                sparsity = np.zeros((sum(rows), p + len(nuis)), dtype=np.int8)
                sparsity[:, :p] = 1
                offs = np.concatenate([[0], np.cumsum(rows)])
                for col, e in enumerate(nuis):
                    sparsity[offs[e] : offs[e + 1], p + col] = 1
            if z0.size == 0:
                res_x, cost = z0, 0.5 * float(np.sum(fun(z0) ** 2))
            else:
                res = _scipy_least_squares(
                    fun,
                    z0,
                    bounds=(zlo, zhi),
                    method="trf",
                    x_scale="jac",
                    jac_sparsity=sparsity,
                    max_nfev=max_nfev or 30 * (p + 1),
                    xtol=1e-8,
                    ftol=1e-8,
                )
                res_x, cost, status = res.x, float(res.cost), int(res.status)
            if z0.size == 0:
                status = 1
            if best is None or cost < best[0]:
                best = (cost, res_x[:p].copy(), spec_of(res_x), status)
        #: SciPy's status of the kept start: > 0 converged (gtol, ftol, xtol), 0 max_nfev reached,
        #: -1 improper input (read by the workflow, issue 37 item 7)
        self.last_status = best[3]
        return best[1], best[2]

    def folds(self) -> list:
        """Cross-validation folds [(train masks, test masks)]: leave one experiment out when there are
        at least 3 experiments, else 4 contiguous blocks of points of every experiment."""
        n = [m.shape[0] for m in self.measured]
        folds = []
        if len(n) >= 3:
            for e in range(len(n)):
                test = [np.full(k, i == e) for i, k in enumerate(n)]
                folds.append(([~t for t in test], test))
        else:
            for b in range(4):
                test = [(np.arange(k) * 4 // k) == b for k in n]
                folds.append(([~t for t in test], test))
        return folds

    def cv_rms(self, make_spec, x0, bounds) -> float:
        """Held-out rms: for each fold the parameters x of ``make_spec`` are fitted on the training
        points and predict the test points. ``x0``: the start, or a callable evaluated per fold (the
        workflow passes the effect's start on the model without it, never the all-data optimum).
        While a fold is fitted and evaluated :attr:`fit_mask` is its training points.
        ``self.last_cv_not_converged``: the number of folds whose fit did not converge."""
        sq, cnt = 0.0, 0
        self.last_cv_not_converged = 0
        for train, test in self.folds():
            self.fit_mask = train
            try:
                start = np.atleast_1d(np.asarray(x0() if callable(x0) else x0, float))
                x, s = self.least_squares(make_spec, [start], bounds, train=train,
                                          max_nfev=30 * (start.size + 1))
                r = self.residuals(s)
            except ValueError:
                return math.inf
            finally:
                self.fit_mask = None
            self.last_cv_not_converged += self.last_status <= 0
            for ri, ti in zip(r, test):
                sq += float(np.sum(ri[ti] ** 2))
                cnt += int(ti.sum()) * ri.shape[1]
        return math.sqrt(sq / max(cnt, 1))


def robust_difference_noise(residual: np.ndarray, groups: np.ndarray | None = None) -> tuple[float, int]:
    """Noise of a sequence (n, 3) from its second differences, robust to a few jumps: σ =
    1.4826·median|Δ²r|/√6 per column (Δ² of white noise has variance 6σ²). ``groups`` (n,): only
    triples inside one group count. Returns (σ² summed weight form: variance, count)."""
    r = np.asarray(residual, float)
    if r.shape[0] < 3:
        return 0.0, 0
    d2 = r[2:] - 2 * r[1:-1] + r[:-2]
    if groups is not None:
        g = np.asarray(groups)
        keep = (g[2:] == g[1:-1]) & (g[1:-1] == g[:-2])
        d2 = d2[keep]
    if d2.shape[0] == 0:
        return 0.0, 0
    sigma = 1.4826 * np.median(np.abs(d2), axis=0) / math.sqrt(6.0)
    return float(np.mean(sigma**2)), d2.shape[0]
