"""A volumetric diagnosis written into a machine TOML (``netshape diagnose --update MACHINE.toml``).

What the diagnosis changed, from its model before to its model after (so the machine's own values
are kept and the change is added to them; equal to the fitted values when the diagnosis ran
against this machine, ``diagnose(bundle, machine=FILE)``):

* squareness, spindle tilt: ``[squareness] EC0Y_rad …``, ``[spindle] tilt_a_rad …`` (+ the change);
* scale error (and any polynomial component): ``[axes.K.polynomials] EKK_mm`` (+ the change, in the
  key's own unit); a component the machine gives by a table is refused (edit the table);
* backlash: ``[axes.K] backlash_um`` (+ the reversal found);
* cyclic error: a new ``[[axes.K.cyclic]]`` (period_mm, amplitude_mm, phase_deg);
* thermal drift: a new ``[[thermal]]`` (axis, amplitude_mm, time_constant_s).

Every key written has a comment line above it naming the diagnosis (bundle, effect, UTC time).
Everything else in the text stays as it was; the result is parsed and loaded as a machine before it
is returned.
"""

from __future__ import annotations

import datetime
import math

from netshape.machine.description import _ANGLE_UNITS, _LENGTH_UNITS
from netshape.machine.provenance import MARK

from .toml_text import TomlText

_AXES = "XYZ"
#: ISO name → (TOML table, key) of the constants
_CONSTANT_KEYS = {"EC0Y": ("squareness", "EC0Y_rad"), "EB0Z": ("squareness", "EB0Z_rad"),
                  "EA0Z": ("squareness", "EA0Z_rad"), "spindle_tilt_a": ("spindle", "tilt_a_rad"),
                  "spindle_tilt_b": ("spindle", "tilt_b_rad")}


def _num(v: float) -> str:
    return repr(float(v))


def _effect_of(diagnosis, name: str) -> str:
    cat = {"EC0Y": "squareness", "EB0Z": "squareness", "EA0Z": "squareness", "spindle_tilt_a": "spindle_tilt",
           "spindle_tilt_b": "spindle_tilt", "EXX": "scale_error", "EYY": "scale_error", "EZZ": "scale_error"}
    found = {e["effect"] for e in diagnosis.effects}
    return cat.get(name) if cat.get(name) in found else "joint refit"


def changes(diagnosis) -> list:
    """[(kind, data)] the diagnosis changed: ("model", name, delta coefficients), ("backlash", axis,
    reversal mm), ("cyclic", axis, a mm, b mm, period mm), ("thermal", axis, amplitude mm, τ s)."""
    before, after = diagnosis.spec_before, diagnosis.spec_after
    out = []
    b0, a0 = dict(before.model), dict(after.model)
    for name in sorted(set(b0) | set(a0)):
        old, new = list(b0.get(name, ())), list(a0.get(name, ()))
        n = max(len(old), len(new))
        delta = [(new[i] if i < len(new) else 0.0) - (old[i] if i < len(old) else 0.0) for i in range(n)]
        if any(d != 0.0 for d in delta):
            out.append(("model", name, delta))
    for field in ("backlash", "cyclic", "thermal"):
        for t in getattr(after, field)[len(getattr(before, field)):]:
            out.append((field, *t))
    return out


def _axis_key(doc: dict, axis: str) -> str:
    return next((k for k in doc.get("axes", {}) if k.upper() == axis), axis)


def apply_to_machine(diagnosis, text: str, source: str = "<machine>", stamp: str | None = None,
                     base_dir: str = ".") -> str:
    """``text`` (a machine TOML; its CSV tables relative to ``base_dir``) with the changes of
    ``diagnosis`` (a volumetric_error Diagnosis)."""
    from netshape._text import loads_toml
    from netshape.machine import machine_from_dict

    doc = loads_toml(text, source)
    if "tool_chain" not in doc or "workpiece_chain" not in doc:
        raise ValueError(f"{source}: not a machine TOML (no tool_chain / workpiece_chain), "
                         f"but the bundle is {diagnosis.kind}")
    machine_from_dict(doc, base_dir, source)  # a machine that does not load is refused as it is
    stamp = stamp or datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")
    who = f"{MARK} {diagnosis.bundle_path or '<bundle>'} ({stamp})"
    t = TomlText(text)
    for ch in changes(diagnosis):
        kind = ch[0]
        if kind == "model":
            _model_change(t, doc, diagnosis, ch[1], ch[2], who, source, base_dir)
        elif kind == "backlash":
            axis, rev = ch[1], ch[2]
            ak = _axis_key(doc, axis)
            old = doc.get("axes", {}).get(ak, {})
            old_mm = old.get("backlash_mm", 0.0) + old.get("backlash_um", 0.0) * 1e-3
            key = "backlash_mm" if "backlash_mm" in old else "backlash_um"
            new = old_mm + rev
            span = t.table_span(f"axes.{ak}")
            if span is None:
                t.append(f"[axes.{ak}]\n")
                span = t.table_span(f"axes.{ak}")
            t.set_key(span, key, _num(new if key == "backlash_mm" else new * 1e3),
                      f"{who}: backlash, reversal {rev * 1e3:.4g} um added (was {old_mm * 1e3:.4g} um)")
        elif kind == "cyclic":
            axis, a, b, period = ch[1:]
            ak = _axis_key(doc, axis)
            t.append(f"# {who}: cyclic_error of {axis}\n[[axes.{ak}.cyclic]]\nperiod_mm = {_num(period)}\n"
                     f"amplitude_mm = {_num(math.hypot(a, b))}\n"
                     f"phase_deg = {_num(math.degrees(math.atan2(b, a)) % 360.0)}\n")
        elif kind == "thermal":
            axis, amp, tau = ch[1:]
            t.append(f"# {who}: thermal_drift along {axis}\n[[thermal]]\naxis = \"{axis}\"\n"
                     f"amplitude_mm = {_num(amp)}\ntime_constant_s = {_num(tau)}\n")
    out = t.text()
    try:
        machine_from_dict(loads_toml(out, source), base_dir, source)
    except ValueError as exc:
        raise ValueError(f"{source}: the updated machine is not valid: {exc}") from None
    return out


def _model_change(t: TomlText, doc: dict, diagnosis, name: str, delta: list, who: str, source: str,
                  base_dir: str) -> None:
    eff = _effect_of(diagnosis, name)
    if name in _CONSTANT_KEYS:
        table, key = _CONSTANT_KEYS[name]
        old = float(doc.get(table, {}).get(key, 0.0))
        span = t.table_span(table)
        if span is None:
            t.append(f"[{table}]\n")
            span = t.table_span(table)
        t.set_key(span, key, _num(old + delta[0]),
                  f"{who}: {eff}, {delta[0] * 1e6:+.4g} urad (was {_num(old)})")
        return
    axis = name[2]
    ak = _axis_key(doc, axis)
    ad = doc.get("axes", {}).get(ak, {})
    tab = ad.get("table")
    if tab is not None and _table_has(tab, name, base_dir):
        raise ValueError(f"{source}: [axes.{ak}] {name} is given by the table {tab!r}: the {eff} change "
                         f"{delta} cannot be written into a table; add it to the table's values")
    polys = ad.get("polynomials", {})
    key = next((k for k in polys if k.partition("_")[0].upper() == name), None)
    rot = name[1] in "ABC"
    unit = key.partition("_")[2] if key else ("rad" if rot else "mm")
    f = (_ANGLE_UNITS if rot else _LENGTH_UNITS)[unit]
    old = [float(v) for v in polys.get(key, [])] if key else []
    n = max(len(old), len(delta))
    new = [(old[i] if i < len(old) else 0.0) + (delta[i] / f if i < len(delta) else 0.0) for i in range(n)]
    span = t.table_span(f"axes.{ak}.polynomials")
    if span is None:
        t.append(f"[axes.{ak}.polynomials]\n")
        span = t.table_span(f"axes.{ak}.polynomials")
    what = f"slope {delta[1] * 1e6:+.4g} um/m" if len(delta) > 1 and not rot and not any(delta[2:]) else "change"
    t.set_key(span, key or f"{name}_{unit}", "[" + ", ".join(_num(v) for v in new) + "]",
              f"{who}: {eff}, {what} (was {old or 'absent'})")


def _table_has(tab, name: str, base_dir: str) -> bool:
    if isinstance(tab, dict):
        return any(k.partition("_")[0].upper() == name for k in tab)
    from pathlib import Path

    from netshape.machine import read_error_table

    p = Path(tab) if Path(tab).is_absolute() else Path(base_dir) / tab
    return name in read_error_table(p)["components"]
