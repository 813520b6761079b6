"""Write a diagnosis into the model file it was found against (``Diagnosis.apply``,
``netshape diagnose BUNDLE --update MODEL_FILE --model-out NEW_FILE``).

By the bundle's kind:

* ``volumetric_error``: MODEL_FILE is a machine TOML (:mod:`update_machine`);
* ``wall_error``: the tool TOML (``netshape.discrepancy.update_tool.apply_to_tool``);
* ``cutting_force``: a cutter TOML (a file with ``diameter_mm``: ``apply_to_tool``) or a
  coefficients TOML (``apply_to_coefficients``).

A diagnosis that found no effect returns the text unchanged (``--model-out`` is then a copy, so a
loop that always writes the next model keeps working). A model file of the wrong kind, or a kind
whose updater is not installed, is a ValueError naming the file and the bundle kind.
"""

from __future__ import annotations

import importlib
import os
from pathlib import Path

#: what MODEL_FILE must be, per bundle kind (messages)
MODEL_FILE_KIND = {"volumetric_error": "a machine TOML", "wall_error": "a tool TOML",
                   "cutting_force": "a cutter or coefficients TOML"}


def _read(model) -> tuple[str, str, str]:
    """(text, source name, base folder) of ``model``: a path or the text itself."""
    if isinstance(model, os.PathLike) or (isinstance(model, str) and "\n" not in model and "=" not in model):
        from netshape._text import read_text

        p = Path(model)
        return read_text(p), str(p), str(p.parent)
    if not isinstance(model, str):
        raise ValueError(f"model: {type(model).__name__} is neither a model file's text nor its path")
    return model, "<model>", "."


def _tool_updater(kind: str):
    try:
        return importlib.import_module("netshape.discrepancy.update_tool")
    except ModuleNotFoundError as exc:
        if exc.name != "netshape.discrepancy.update_tool":
            raise
        raise ValueError(f"--update: writing a {kind} diagnosis into {MODEL_FILE_KIND[kind]} is not available "
                         f"(netshape.discrepancy.update_tool is not installed)") from None


def check_model(kind: str, model) -> tuple[str, str, str, dict]:
    """(text, source, base folder, parsed document) of ``model`` after checking it can take a ``kind``
    diagnosis: the right kind of file, and its updater installed. ValueError naming both otherwise."""
    text, source, base_dir = _read(model)
    if kind not in MODEL_FILE_KIND:
        raise ValueError(f"kind = {kind!r}: no model file to update for it")
    from netshape._text import loads_toml

    doc = loads_toml(text, source)
    is_machine = "tool_chain" in doc or "workpiece_chain" in doc
    if (kind == "volumetric_error") != is_machine:
        raise ValueError(f"{source}: is not {MODEL_FILE_KIND[kind]}, the model of a {kind} bundle"
                         + (" (it is a machine TOML)" if is_machine else " (no tool_chain / workpiece_chain)"))
    if kind != "volumetric_error":
        _tool_updater(kind)
    return text, source, base_dir, doc


def apply(diagnosis, model, *, stamp: str | None = None) -> str:
    """The text of ``model`` (a model file's text or path) with ``diagnosis``'s effects added."""
    kind = diagnosis.kind
    text, source, base_dir, doc = check_model(kind, model)
    if not diagnosis.effects:
        return text
    if kind == "volumetric_error":
        from .update_machine import apply_to_machine

        return apply_to_machine(diagnosis, text, source, stamp=stamp, base_dir=base_dir)
    mod = _tool_updater(kind)
    if kind == "wall_error" or "diameter_mm" in doc:
        return mod.apply_to_tool(diagnosis, text)
    return mod.apply_to_coefficients(diagnosis, text)


def write_updated_model(diagnosis, model_file, out_file) -> str:
    """Apply ``diagnosis`` to ``model_file`` and write the result to ``out_file`` atomically (whole or
    not at all); returns the text written."""
    from netshape._atomic import atomic_write

    text = apply(diagnosis, Path(model_file))
    with atomic_write(out_file) as fh:
        fh.write(text)
    return text
