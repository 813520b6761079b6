"""netshape.cutter — flat, ball and bull-nose end mills, read from and written to TOML.

TOML keys (units in the names)::

    kind = "bull"              # "flat", "ball" or "bull"
    diameter_mm = 10.0
    corner_radius_mm = 1.0     # flat: 0 (may be left out); ball: = diameter/2 (may be left out)
    flutes = 3
    helix_deg = 30.0
    flute_length_mm = 22.0
    stick_out_mm = 40.0
    youngs_modulus_MPa = 600000.0   # optional (carbide by default)

Optional keys of the tool as it runs in its holder (the catalogue effects of ``netshape diagnose``,
written by :func:`netshape.discrepancy.update_tool.apply_to_tool`)::

    holder_compliance_um_per_N = 0.05   # clamp/holder/spindle compliance: the tool translates by c*F
    runout_rho_mm = 0.005               # radial runout: offset of the tool axis [mm]
    runout_lambda_deg = 30.0            # its angle: flute j cuts at R + rho*cos(lambda - j*360/N)

Optional keys of the cutter assembly, read by netshape.posture (lengths measured from the tip)::

    shank_diameter_mm = 6.0
    shank_length_mm = 35.0     # tip to the end of the shank (where the holder starts)
    holder_diameter_mm = 20.0
    holder_length_mm = 80.0    # tip to the end of the holder
    holder_profile_mm = [[35.0, 5.0], [45.0, 10.0], [80.0, 10.0]]   # or (z, r) pairs: a taper, a neck
"""

from __future__ import annotations

import math
import os

from .._atomic import atomic_write
from .._config import load_toml, number
from .._core import cutter as _cutter


Cutter = _cutter.Cutter
CutterKind = _cutter.CutterKind
check_flutes = _cutter.check_flutes  # the one 1..64 check (C++), with the caller's field name

#: The spindle's limits the tool runs under (read by feed scheduling, docs/feeds.md), optional.
SPINDLE_KEYS = ("max_power_W", "max_torque_Nm")

_KEYS = ("kind", "diameter_mm", "corner_radius_mm", "flutes", "helix_deg", "flute_length_mm", "stick_out_mm",
         "youngs_modulus_MPa", "shank_diameter_mm", "shank_length_mm", "holder_diameter_mm", "holder_length_mm",
         "holder_profile_mm", "holder_compliance_um_per_N", "runout_rho_mm", "runout_lambda_deg",
         *SPINDLE_KEYS)
_REQUIRED = ("kind", "diameter_mm", "flutes", "helix_deg", "flute_length_mm", "stick_out_mm")


def cutter_from_dict(d: dict, *, source: str = "cutter") -> Cutter:
    """A validated Cutter from a dict with the TOML keys (see the module docstring)."""
    if not isinstance(d, dict):
        raise ValueError(f"{source}: must be a table of keys, got {type(d).__name__}")
    for key in d:
        if key not in _KEYS:
            raise ValueError(f"{source}: {key} = {d[key]!r}: unknown key (known: {', '.join(_KEYS)})")
    for key in _REQUIRED:
        if key not in d:
            raise ValueError(f"{source}: {key}: missing (required: {', '.join(_REQUIRED)})")
    kind_name = d["kind"]
    if not isinstance(kind_name, str):
        raise ValueError(f"kind = {kind_name!r}: must be \"flat\", \"ball\" or \"bull\"")
    c = Cutter()
    c.kind = _cutter.cutter_kind_from_string(kind_name)  # ValueError naming the value
    c.radius = 0.5 * number(None, "diameter_mm", d["diameter_mm"])
    if "corner_radius_mm" in d:
        c.corner_radius = number(None, "corner_radius_mm", d["corner_radius_mm"])
    else:
        c.corner_radius = c.radius if c.kind == CutterKind.ball else 0.0
    flutes = d["flutes"]
    if isinstance(flutes, bool) or not isinstance(flutes, int):
        raise ValueError(f"flutes = {flutes!r}: must be an integer")
    if not -2**31 <= flutes < 2**31:  # beyond the core's int: its one 1..64 check on the nearest int, this value named
        near = 2**31 - 1 if flutes > 0 else -2**31
        try:
            check_flutes(near, "flutes")
        except ValueError as exc:
            raise ValueError(str(exc).replace(str(near), str(flutes))) from None
    c.flutes = flutes  # 1..64: checked by validate() below
    c.helix = math.radians(number(None, "helix_deg", d["helix_deg"]))
    c.flute_length = number(None, "flute_length_mm", d["flute_length_mm"])
    c.stick_out = number(None, "stick_out_mm", d["stick_out_mm"])
    if "youngs_modulus_MPa" in d:
        c.youngs_modulus = number(None, "youngs_modulus_MPa", d["youngs_modulus_MPa"])
    if "holder_compliance_um_per_N" in d:
        v = number(None, "holder_compliance_um_per_N", d["holder_compliance_um_per_N"])
        if v < 0:
            raise ValueError(f"holder_compliance_um_per_N = {v!r}: must be ≥ 0 [µm/N]")
        c.holder_compliance = 1e-3 * v
    if "runout_rho_mm" in d:
        c.runout_rho = number(None, "runout_rho_mm", d["runout_rho_mm"])
    if "runout_lambda_deg" in d:
        c.runout_lambda = math.radians(number(None, "runout_lambda_deg", d["runout_lambda_deg"]))
    spindle_limits(d)  # checked here too, so a bad value fails wherever the tool is read
    c.validate()  # ValueError "cutter.<field> = value: requirement"
    return c


def tool_table(source: str, base, where: str, v, *, known=None, error: type = ValueError) -> dict:
    """The cutter keys of a tool given as a TOML path string, or as a table of cutter keys with an
    optional ``file`` (a cutter TOML, relative to ``base``) whose keys the table's override. Checked by
    :func:`cutter_from_dict`; ``known`` limits the table's keys (default: every cutter key and ``file``).
    Errors are ``error("SOURCE: WHERE.KEY = VALUE: WHY")``."""
    from .._config import check_keys, file_path

    if isinstance(v, (str, os.PathLike)):
        v = {"file": os.fspath(v)}
    t = check_keys(source, where, v, known if known is not None else {"file", *_KEYS}, error)
    d: dict = {}
    if "file" in t:
        p = file_path(source, base, f"{where}.file", t["file"], error=error)
        d = load_toml(p, str(p))
    d.update({k: x for k, x in t.items() if k != "file"})
    try:
        cutter_from_dict(d, source=where)
    except ValueError as exc:
        msg = str(exc)
        raise error(f"{source}: {msg if msg.startswith(where) else f'{where}: {msg}'}") from None
    return d


def spindle_limits(d: dict) -> dict[str, float]:
    """The optional spindle limits of a tool's TOML keys (``max_power_W``, ``max_torque_Nm``), each > 0."""
    out = {}
    for key in SPINDLE_KEYS:
        if key in d:
            out[key] = number(None, key, d[key], positive=True)
    return out


def cutter_to_dict(c: Cutter) -> dict:
    """The TOML keys of a cutter (inverse of :func:`cutter_from_dict`)."""
    c.validate()
    return {
        "kind": _cutter_kind_name(c.kind),
        "diameter_mm": 2.0 * c.radius,
        "corner_radius_mm": c.corner_radius,
        "flutes": int(c.flutes),
        "helix_deg": math.degrees(c.helix),
        "flute_length_mm": c.flute_length,
        "stick_out_mm": c.stick_out,
        "youngs_modulus_MPa": c.youngs_modulus,
        **({"holder_compliance_um_per_N": 1e3 * c.holder_compliance} if c.holder_compliance else {}),
        **({"runout_rho_mm": c.runout_rho, "runout_lambda_deg": math.degrees(c.runout_lambda)}
           if c.runout_rho else {}),
    }


def _cutter_kind_name(k) -> str:
    return {CutterKind.flat: "flat", CutterKind.ball: "ball", CutterKind.bull: "bull"}[k]


def load_cutter(path: str | os.PathLike) -> Cutter:
    """Read a cutter from a TOML file. Unknown keys and bad values raise ValueError naming key and value."""
    data = load_toml(path)
    try:
        return cutter_from_dict(data, source=os.fspath(path))
    except ValueError as exc:
        msg = str(exc)
        raise ValueError(msg if msg.startswith(os.fspath(path)) else f"{os.fspath(path)}: {msg}") from None


def save_cutter(cutter: Cutter, path: str | os.PathLike) -> None:
    """Write a cutter as TOML, whole or not at all."""
    import tomli_w

    text = tomli_w.dumps(cutter_to_dict(cutter))
    with atomic_write(path, "w") as fh:
        fh.write(text)


__all__ = ["Cutter", "CutterKind", "check_flutes", "cutter_from_dict", "cutter_to_dict", "load_cutter", "save_cutter"]
