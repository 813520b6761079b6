"""Write a diagnosis back into the model files that predictions and compensation read: the tool TOML
(holder compliance, runout) and the cutting-coefficient TOML (edge forces, chip-size effect).

Both functions take the TOML text and return the new text: every line they do not change is kept as
it was (comments, order, formatting); a changed key keeps its line and gets a comment naming the
diagnosis, the time and the value it replaces; a new key is appended to its table under such a comment.
The result is parsed again and checked to hold exactly the old keys and values plus the written ones.

Where the terms go (key, unit, and how the found value combines with the file's):

* tool (a cutter TOML, or the ``[tool]`` table of a bundle manifest):
  ``holder_compliance_um_per_N`` [µm/N], the file's value plus the found ``compliance_um_per_N``
  (the diagnosis fits the compliance missing from the model that already held the file's);
  ``runout_rho_mm`` [mm] and ``runout_lambda_deg`` [deg], replaced (the fit is of the whole runout).
* coefficients (a TOML with the force bundle's ``[model]`` keys at the top level, or the ``[model]``
  table of a cutting-force manifest): ``Kte_N_per_mm``, ``Kre_N_per_mm``, ``Kae_N_per_mm`` replaced by the
  refitted edge coefficients; ``chip_exponent`` replaced and ``reference_chip_mm`` [mm] written
  (h_ref of g(h) = h_ref·(h/h_ref)^p: the file's value when it has one, else the bundle's).

``diagnosis`` is a :class:`~netshape.discrepancy.workflow.Diagnosis` or its ``to_dict()``; a dict has no
bundle, so a size effect from a dict needs ``reference_chip_mm`` in the file or its parameters.
"""

from __future__ import annotations

import datetime as _dt
import math
import re
import tomllib

#: catalogue effects whose parameters live in the tool TOML / in the coefficient TOML
TOOL_EFFECTS = ("holder_compliance", "runout")
COEFFICIENT_EFFECTS = ("edge_forces", "size_effect")
_HEADER = re.compile(r"^\s*\[")


def apply_to_tool(diagnosis, text: str, *, source: str | None = None, now: _dt.datetime | None = None) -> str:
    """``text`` (a tool TOML or a bundle manifest with ``[tool]``) with the diagnosis' tool terms."""
    return _apply(diagnosis, text, "tool", TOOL_EFFECTS, _tool_terms, _label(diagnosis, source, now))


def apply_to_coefficients(diagnosis, text: str, *, source: str | None = None,
                          now: _dt.datetime | None = None) -> str:
    """``text`` (a coefficient TOML or a cutting-force manifest with ``[model]``) with the diagnosis'
    coefficient terms."""
    return _apply(diagnosis, text, "model", COEFFICIENT_EFFECTS, _coefficient_terms,
                  _label(diagnosis, source, now))


def _tool_terms(diagnosis, effect: str, p: dict, old: dict) -> dict:
    """{key: value} of one tool effect; ``old`` the table's current keys."""
    if effect == "holder_compliance":
        base = _float(old.get("holder_compliance_um_per_N", 0.0), "holder_compliance_um_per_N")
        return {"holder_compliance_um_per_N": base + _float(p["compliance_um_per_N"], "compliance_um_per_N")}
    return {"runout_rho_mm": _float(p["rho_mm"], "rho_mm"), "runout_lambda_deg": _float(p["lambda_deg"], "lambda_deg")}


def _coefficient_terms(diagnosis, effect: str, p: dict, old: dict) -> dict:
    """{key: value} of one coefficient effect; ``old`` the table's current keys."""
    if effect == "edge_forces":
        return {k: _float(p[k], k) for k in ("Kte_N_per_mm", "Kre_N_per_mm", "Kae_N_per_mm")}
    href = old.get("reference_chip_mm", p.get("reference_chip_mm"))
    if href is None:
        href = getattr(getattr(diagnosis, "problem", None), "h_ref", None)
    if href is None:
        raise ValueError("size_effect: reference_chip_mm unknown (give the Diagnosis object, or a file "
                         "that has reference_chip_mm)")
    return {"chip_exponent": _float(p["chip_exponent"], "chip_exponent"),
            "reference_chip_mm": _float(href, "reference_chip_mm")}


def _apply(diagnosis, text: str, table_name: str, names: tuple, terms, label: str) -> str:
    """The effects ``names`` of the diagnosis written into ``table_name`` of ``text`` (a manifest) or its
    top level (a tool or coefficient file), ``terms`` giving each effect's keys."""
    target = "tool" if table_name == "tool" else "coefficients"
    doc = _parse(text, f"{target} TOML")
    table = table_name if isinstance(doc.get(table_name), dict) else None
    old = doc.get(table_name, {}) if table else doc
    values = {}
    for e in _effects(diagnosis, names, target):
        values.update({k: (v, e["effect"]) for k, v in terms(diagnosis, e["effect"], e["parameters"], old).items()})
    return _write(text, doc, table, values, label)


# --- helpers -----------------------------------------------------------------------------------------
def _parse(text: str, what: str) -> dict:
    if not isinstance(text, str):
        raise ValueError(f"{what}: expected the file's text, got {type(text).__name__}")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{what}: not valid TOML ({exc})") from None


def _float(v, name: str) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise ValueError(f"{name} = {v!r}: must be a finite number")
    return float(v)


def _effects(diagnosis, names: tuple, target: str) -> list:
    """The diagnosis' added effects that belong in ``target`` ({effect, parameters}); ValueError when
    it found none of them."""
    effects = diagnosis.get("effects") if isinstance(diagnosis, dict) else getattr(diagnosis, "effects", None)
    if effects is None:
        raise ValueError(f"diagnosis: {type(diagnosis).__name__} has no 'effects' (a Diagnosis or its to_dict())")
    mine = [e for e in effects if e.get("effect") in names]
    if not mine:
        found = ", ".join(str(e.get("effect")) for e in effects) or "no effect"
        raise ValueError(f"diagnosis: effect = {found}: nothing to write into the {target} file "
                         f"(it holds {', '.join(names)})")
    return mine


def _label(diagnosis, source, now) -> str:
    if source is None:
        problem = getattr(diagnosis, "problem", None)
        bundle = getattr(problem, "bundle", None)
        source = getattr(bundle, "path", None)
    now = now or _dt.datetime.now(_dt.timezone.utc)
    where = f" of {source}" if source else ""
    return f"netshape diagnose{where}, {now.strftime('%Y-%m-%d %H:%M UTC')}"


def _toml_float(v: float) -> str:
    s = repr(float(v))
    return s if any(ch in s for ch in ".en") else s + ".0"


def _write(text: str, doc: dict, table: str | None, values: dict, label: str) -> str:
    """Set ``values`` {key: (value, effect)} in ``table`` (None: the top level) of ``text``."""
    lines = text.splitlines(keepends=True)
    newline = "\r\n" if text.endswith("\r\n") else "\n"
    if lines and not lines[-1].endswith(("\n", "\r")):
        lines[-1] += newline
    start, end = _section(lines, table)
    added = []
    for key, (value, effect) in values.items():
        pat = re.compile(rf"^(\s*){re.escape(key)}\s*=")
        hit = next((i for i in range(start, end) if pat.match(lines[i])), None)
        if hit is None:
            added.append(f"{key} = {_toml_float(value)}{newline}")
            continue
        indent = pat.match(lines[hit]).group(1)
        old = lines[hit].split("=", 1)[1].split("#", 1)[0].strip()
        lines[hit] = f"{indent}{key} = {_toml_float(value)}  # {effect}: {label} (was {old}){newline}"
    if added:
        at = end
        while at > start and not lines[at - 1].strip():
            at -= 1
        effects = sorted({effect for _, effect in values.values()})
        block = [f"# {', '.join(effects)}: added by {label}{newline}"] + added
        lines[at:at] = block
    out = "".join(lines)
    _check_lossless(doc, _parse(out, "updated TOML"), table, {k: v for k, (v, _) in values.items()})
    return out


def _section(lines: list, table: str | None) -> tuple:
    """(first, end) line indices of the key/value lines of ``table`` (None: the top level)."""
    if table is None:
        end = next((i for i, ln in enumerate(lines) if _HEADER.match(ln)), len(lines))
        return 0, end
    head = re.compile(rf"^\s*\[\s*{re.escape(table)}\s*\]\s*(#.*)?$")
    first = next((i for i, ln in enumerate(lines) if head.match(ln.rstrip("\r\n"))), None)
    if first is None:
        raise ValueError(f"[{table}]: written inline or dotted; give the table as a [{table}] header")
    end = next((i for i in range(first + 1, len(lines)) if _HEADER.match(lines[i])), len(lines))
    return first + 1, end


def _check_lossless(before: dict, after: dict, table: str | None, written: dict) -> None:
    """``after`` equals ``before`` with ``written`` set in ``table``: nothing else changed."""
    expect = {k: (dict(v) if isinstance(v, dict) else v) for k, v in before.items()}
    target = expect.setdefault(table, {}) if table else expect
    target.update(written)
    if after != expect:
        raise ValueError("updated TOML does not hold exactly the old keys plus the written ones "
                         "(a key written in an unusual form?)")


__all__ = ["apply_to_tool", "apply_to_coefficients", "TOOL_EFFECTS", "COEFFICIENT_EFFECTS"]
