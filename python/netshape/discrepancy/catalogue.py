"""The catalogue of candidate effects: an open registry of named model extensions.

An effect is a named, physically parametrised extension of the current model of one bundle kind
(``cutting_force``, ``volumetric_error``, ``wall_error``). It knows its parameter names (units in the names), whether
a bundle carries what it needs, and how to fit itself: :meth:`Effect.fit` returns the fitted
parameters and the extended model specification. Most effects only describe a parametrisation
(:meth:`Effect.starts`, :meth:`Effect.bounds`, :meth:`Effect.apply`, :meth:`Effect.parameters_of`)
and leave the fit to the problem's :meth:`least_squares` (SciPy ``least_squares``).

A user adds an effect by subclassing :class:`Effect` and calling :func:`register_effect`::

    import numpy as np, dataclasses
    from netshape import discrepancy as nd

    class ProbeOffset(nd.Effect):
        name, kind, parameters = "probe_offset", "volumetric_error", ("dx_um",)
        covariate = "position"
        def starts(self, problem, spec):
            return [np.zeros(1)]
        def apply(self, problem, spec, x):
            first = problem.experiments[0].file  # the probe shifted along X after the first experiment
            add = lambda exp, pts: np.outer(np.ones(len(pts)), [x[0] * 1e-3 * (exp.file != first), 0, 0])
            return dataclasses.replace(spec, additive=spec.additive + (add,))
        def parameters_of(self, x):
            return {"dx_um": float(x[0])}

    nd.register_effect(ProbeOffset())

``additive`` terms are functions ``(experiment, points_or_angles) -> (n, 3)`` added to the prediction
(every specification type has the field; for wall errors the points are (n, 2) x, z [mm] and the
result (n, 1) [mm]).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass
class EffectFit:
    """Result of :meth:`Effect.fit`: parameters (name → value, units in the names), the extended
    specification, the number of free parameters k, and the internal vector x."""

    parameters: dict
    spec: Any
    k: int
    x: np.ndarray
    #: SciPy least_squares status of the fit (> 0 converged, 0 max_nfev reached, -1 improper input;
    #: None when unknown)
    status: int | None = None


class Effect:
    """Base class of a catalogue entry. Subclasses set ``name``, ``kind``, ``parameters`` (tuple of
    names), ``covariate`` (where the effect shows: ``angle``, ``feed``, ``frequency`` for forces;
    ``position``, ``time``, ``direction``, ``tool_length`` for volumetric errors; ``normal_force``,
    ``revolution_phase`` for wall errors) and ``description``."""

    name: str = ""
    kind: str = ""
    parameters: tuple = ()
    covariate: str = ""
    description: str = ""

    def applicable(self, problem) -> str | None:
        """None if the bundle carries what the effect needs, else the reason it is skipped."""
        return None

    def physical_bounds(self, problem) -> dict:
        """{parameter name: (low, high)}: the physically plausible open range of each named
        parameter (its unit in its name). A fit that ends at or beyond one is not added: it stays in
        ``candidates`` with ``rejected: "implausible: …"``. Default: none declared."""
        return {}

    def implausible(self, problem, fit: EffectFit, x=None, bounds=None) -> str | None:
        """Why ``fit`` is not physical, or None: a named parameter at or beyond its
        :meth:`physical_bounds`, or an internal parameter ``x`` (of :meth:`refit`) at one of the fit's
        finite ``bounds`` (the optimum lies outside what the fit was allowed)."""
        for name, (lo, hi) in self.physical_bounds(problem).items():
            v = fit.parameters.get(name)
            if isinstance(v, (int, float)) and not lo < v < hi:
                return f"{name} = {v:.4g} is outside ({lo:.4g}, {hi:.4g})"
        if x is not None and bounds is not None:
            x = np.atleast_1d(np.asarray(x, float))
            names = [p for p in self.parameters if p != "axis"]
            for side, b in (("lower", bounds[0]), ("upper", bounds[1])):
                b = np.broadcast_to(np.asarray(b, float), x.shape)
                at = np.isfinite(b) & (np.abs(x - b) <= 1e-9 + 1e-6 * np.abs(b))
                if at.any():
                    i = int(np.argmax(at))
                    label = names[i] if len(names) == x.size else f"parameter {i + 1}"
                    return f"{label} ended at the fit's {side} bound ({float(b[i]):.4g} internal units)"
        return None

    def starts(self, problem, spec) -> list:
        """Start vectors of the internal parameters x (one fit from each, the best kept)."""
        raise NotImplementedError

    def bounds(self, problem, spec) -> tuple:
        """(lower, upper) bounds of x (arrays or ±inf)."""
        return (-np.inf, np.inf)

    def apply(self, problem, spec, x):
        """The specification with this effect added at internal parameters x."""
        raise NotImplementedError

    def parameters_of(self, x) -> dict:
        """Named physical parameters of internal vector x."""
        raise NotImplementedError

    def fit(self, problem, spec, train=None) -> EffectFit:
        """Fit the effect on the ``train`` points (None: all) of ``problem`` starting from ``spec``."""
        x, new = problem.least_squares(
            lambda x: self.apply(problem, spec, x),
            self.starts(problem, spec),
            self.bounds(problem, spec),
            train=train,
        )
        return EffectFit(self.parameters_of(x), new, len(x), x, getattr(problem, "last_status", None))

    def fold_start(self, problem, spec, x):
        """Start of a held-out fold's fit of the :meth:`refit` parameters shaped like ``x``: the
        effect's first start on ``spec``, the model without it (computed under the fold's
        ``problem.fit_mask``, so a start read from the data sees the fitting points only); None when
        the first start has another shape (the fold then starts from ``x``)."""
        s = np.atleast_1d(np.asarray(self.starts(problem, spec)[0], float))
        return s if s.shape == np.shape(x) else None

    def refit(self, problem, spec, fit: EffectFit) -> tuple:
        """(make_spec, x0, bounds) to refit this effect on part of the points (cross-validation),
        starting from ``fit``; discrete choices of the fit stay fixed."""
        return (lambda x: self.apply(problem, spec, x)), fit.x, self.bounds(problem, spec)


_REGISTRY: dict[str, dict[str, Effect]] = {}


def register_effect(effect: Effect, *, replace: bool = False) -> Effect:
    """Add ``effect`` to the catalogue of its kind (ValueError if the name is taken and not
    ``replace``). Returns the effect."""
    if not isinstance(effect, Effect):
        raise ValueError(f"effect = {effect!r}: must be an instance of netshape.discrepancy.Effect")
    if not effect.name or not effect.kind:
        raise ValueError(f"effect {effect!r}: name and kind must be set")
    kind = _REGISTRY.setdefault(effect.kind, {})
    if effect.name in kind and not replace:
        raise ValueError(f"effect name = {effect.name!r}: already in the {effect.kind} catalogue")
    kind[effect.name] = effect
    return effect


def unregister_effect(kind: str, name: str) -> None:
    """Remove an effect from the catalogue (KeyError-free: ValueError if absent)."""
    if name not in _REGISTRY.get(kind, {}):
        raise ValueError(f"effect name = {name!r}: not in the {kind} catalogue")
    del _REGISTRY[kind][name]


def catalogue(kind: str | None = None) -> dict:
    """{kind: {name: Effect}} or, with ``kind``, {name: Effect} of that kind (registration order)."""
    if kind is None:
        return {k: dict(v) for k, v in _REGISTRY.items()}
    return dict(_REGISTRY.get(kind, {}))
