"""A machine TOML as the current model of a volumetric diagnosis (``diagnose(bundle, machine=FILE)``).

The machine's polynomial components, squareness and spindle tilt become the diagnosis' starting
model (the ISO 230-1 names of a bundle's ``[model]``); its tables, cyclic terms, backlash and thermal
drift stay in the machine and are predicted with it. A component an effect changes that the machine
holds as a table gets the effect's polynomial added to the table's values (exact for the linear
terms the catalogue fits: a table interpolates linearly).
"""

from __future__ import annotations

import copy
import os
from pathlib import Path

import numpy as np

from netshape.machine import description as _desc
from netshape.machine import state_error
from netshape._core import machine as _m

_AXES = "XYZ"
_CONSTANTS = {"EC0Y": "ec0y", "EB0Z": "eb0z", "EA0Z": "ea0z",
              "spindle_tilt_a": "spindle_tilt_a", "spindle_tilt_b": "spindle_tilt_b"}


class MachineModel:
    """The machine file ``path`` (parsed once) as a volumetric model."""

    def __init__(self, path: str | os.PathLike, bundle=None):
        from netshape._text import read_toml

        self.path = Path(path)
        if not self.path.is_file():
            raise FileNotFoundError(2, "No such file or directory", str(self.path))
        self.doc = read_toml(self.path)
        self.base = _desc.machine_from_dict(self.doc, self.path.parent, str(self.path))
        if bundle is not None:
            ts = [_AXES[k] for k in self.base.tool_chain]
            ws = [_AXES[k] for k in self.base.workpiece_chain]
            if ts != bundle.machine["tool_side"] or ws != bundle.machine["workpiece_side"]:
                raise ValueError(
                    f"{self.path}: tool_chain {ts} / workpiece_chain {ws} differ from the bundle's [machine] "
                    f"tool_side {bundle.machine['tool_side']} / workpiece_side {bundle.machine['workpiece_side']}")

    def initial_model(self) -> dict:
        """{ISO 230-1 name: coefficients}: the machine's polynomial components and constants."""
        out = {}
        for k, axis in enumerate(self.base.axes):
            for c, f in enumerate(axis.errors):
                if f.kind == _m.ErrorFunction.Kind.polynomial and f.coefficients:
                    out[f"E{'XYZABC'[c]}{_AXES[k]}"] = [float(v) for v in f.coefficients]
        for name, attr in _CONSTANTS.items():
            v = float(getattr(self.base, attr))
            if v != 0.0:
                out[name] = [v]
        return out

    def build(self, model: dict, tool_length: float):
        """The machine with ``model``'s components and constants and tool length ``tool_length`` [mm]."""
        doc = copy.deepcopy(self.doc)
        doc.setdefault("tool", {})["length_mm"] = tool_length
        m = _desc.machine_from_dict(doc, self.path.parent, str(self.path))
        axes = m.axes
        for name, coef in model.items():
            if name in _CONSTANTS:
                setattr(m, _CONSTANTS[name], float(coef[0]))
                continue
            k, c = _AXES.index(name[2]), "XYZABC".index(name[1])
            errs = axes[k].errors
            f = errs[c]
            if f.kind == _m.ErrorFunction.Kind.table:
                q = np.asarray(f.positions)
                add = np.polynomial.polynomial.polyval(q, coef)
                errs[c] = _m.ErrorFunction.table(list(q), list(np.asarray(f.values) + add), f.out_of_range, name)
            else:
                errs[c] = _m.ErrorFunction.polynomial([float(v) for v in coef], name)
            axes[k].errors = errs
        m.axes = axes
        m.validate()
        return m

    def state(self, experiment) -> np.ndarray:
        """The machine's own backlash and thermal drift at the experiment's points (n, 3) [mm]: every
        axis approaching in the point's ``direction`` (+1 without the column), at ``t_s`` (0 without)."""
        n = len(experiment.points)
        d = np.ones(n) if experiment.directions is None else np.asarray(experiment.directions, float)
        t = np.zeros(n) if experiment.times is None else np.asarray(experiment.times, float)
        return state_error(self.base, np.repeat(d[:, None], 3, axis=1), t)
