"""The element chip of the deflection model beyond the linear edge-force model
(``DeflectionModel.chip``, netshape.force.RunoutSizeEffect): the tool's runout and the cutting
coefficients' chip-size effect, read from the files ``netshape diagnose --update`` writes.

* the tool TOML's ``runout_rho_mm`` and ``runout_lambda_deg`` (netshape.cutter: ``Cutter.runout_rho``,
  ``Cutter.runout_lambda``): flute j cuts at R + ρ·cos(λ − j·2π/N);
* a coefficient TOML: the six linear edge-force coefficients under the names of a cutting-force
  bundle's ``[model]`` (at the top level, or in a ``[model]`` table), and optionally
  ``chip_exponent`` p and ``reference_chip_mm`` h_ref: the cutting terms follow h_ref·(h/h_ref)^p
  instead of h (h_ref absent: the feed per tooth)::

      Ktc_N_per_mm2 = 2000.0
      Krc_N_per_mm2 = 800.0
      Kac_N_per_mm2 = 0.0
      Kte_N_per_mm = 40.0
      Kre_N_per_mm = 30.0
      Kae_N_per_mm = 0.0
      chip_exponent = 0.75
      reference_chip_mm = 0.05
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import Any

from .._core import force as _f

#: the linear edge-force coefficients of a coefficient TOML [N/mm², N/mm], in LinearEdgeCoefficients order
COEFFICIENT_KEYS = ("Ktc_N_per_mm2", "Krc_N_per_mm2", "Kac_N_per_mm2", "Kte_N_per_mm", "Kre_N_per_mm",
                    "Kae_N_per_mm")
#: the optional chip-size-effect keys of a coefficient TOML
SIZE_EFFECT_KEYS = ("chip_exponent", "reference_chip_mm")


@dataclass(frozen=True)
class SizeEffectCoefficients:
    """Linear edge-force ``coefficients`` with the chip-size effect: exponent p (1: none) and the
    reference chip h_ref [mm] (0: the feed per tooth). Accepted wherever the deflection model takes
    coefficients (:func:`netshape.deflection.make_model`, ``setup_path``, the CLI's
    ``--coefficients FILE.toml``)."""

    coefficients: Any
    chip_exponent: float = 1.0
    reference_chip: float = 0.0


def load_coefficients(path: str | os.PathLike) -> SizeEffectCoefficients:
    """A coefficient TOML (module docstring) → SizeEffectCoefficients. ValueError naming the file and
    the key on a missing, unknown or bad value."""
    from .._text import read_toml

    src = os.fspath(path)
    doc = read_toml(path)
    table = doc["model"] if isinstance(doc.get("model"), dict) else doc
    where = f"{src}: [model]" if table is not doc else src
    known = COEFFICIENT_KEYS + SIZE_EFFECT_KEYS
    for k in table:
        if k not in known:
            raise ValueError(f"{where}: unknown key {k!r} (known: {', '.join(known)})")
    vals = {}
    for k in known:
        if k not in table:
            if k in COEFFICIENT_KEYS:
                raise ValueError(f"{where}: {k}: missing (required: {', '.join(COEFFICIENT_KEYS)})")
            continue
        v = table[k]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise ValueError(f"{where}: {k} = {v!r}: must be a finite number")
        vals[k] = float(v)
    p = vals.get("chip_exponent", 1.0)
    if not 0.0 < p <= 2.0:
        raise ValueError(f"{where}: chip_exponent = {p!r}: must be in (0, 2]")
    href = vals.get("reference_chip_mm", 0.0)
    if "reference_chip_mm" in vals and not href > 0.0:
        raise ValueError(f"{where}: reference_chip_mm = {href!r}: must be > 0 [mm]")
    k = _f.LinearEdgeCoefficients(*(vals[key] for key in COEFFICIENT_KEYS))
    return SizeEffectCoefficients(k, p, href)


def chip_of(coefficients, chip=None, cutter=None):
    """(plain coefficients, RunoutSizeEffect or None): ``coefficients`` without their size effect,
    and the chip that carries it together with ``chip`` (a RunoutSizeEffect given by the caller) or,
    without one, ``cutter``'s runout. None when the chip is the linear model's."""
    size = coefficients if isinstance(coefficients, SizeEffectCoefficients) else None
    plain = size.coefficients if size is not None else coefficients
    if chip is None and cutter is not None and cutter.runout_rho > 0.0:
        chip = _f.RunoutSizeEffect(runout_rho=cutter.runout_rho, runout_lambda=cutter.runout_lambda)
    if size is not None and size.chip_exponent != 1.0:
        base = chip if chip is not None else _f.RunoutSizeEffect()
        chip = _f.RunoutSizeEffect(runout_rho=base.runout_rho, runout_lambda=base.runout_lambda,
                                   chip_exponent=size.chip_exponent, reference_chip=size.reference_chip)
    return plain, chip
