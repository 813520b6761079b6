"""The stock before a program, in one format: the job's ``[stock]`` table and every command's
``--stock STOCK.toml`` read the same keys (docs/stock.md)::

    min_mm = [-20.0, -20.0, -10.0]     # the stock box [x, y, z] in the program's G54 frame
    max_mm = [20.0, 20.0, 0.0]
    spacing_mm = 0.1                   # Z-map node spacing (or `heights` below, or both)
    heights = "casting.npy"            # optional: (ny, nx) heights [mm] over the box, .npy or .csv
    [[pre_cut]]                        # optional, in order: programs swept through the stock first
    program = "rough.ngc"
    tool = "rough_tool.toml"           # a cutter TOML path, or a table of its keys (and `file`)

In a job the table is ``[stock]`` (or ``stock = "STOCK.toml"``, whose keys the table's override) and
pre-cuts are ``[[stock.pre_cut]]``. Relative paths are taken from the file that names them.
:func:`stock_from_dict` checks a table without loading anything large; :func:`build_stock` makes the
Z-map; :func:`load_stock` does both for a file.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any, Callable

from .. import _config as cfg
from .._budget import MAX_ZMAP_NODES

#: The stock's keys (``file`` only in a job's table: the STOCK.toml it reads first).
STOCK_KEYS = frozenset({"file", "min_mm", "max_mm", "spacing_mm", "heights", "pre_cut"})
PRE_CUT_KEYS = frozenset({"program", "tool"})


@dataclass
class PreCut:
    """A program swept through the stock before the main program (paths resolved; ``tool`` holds the
    cutter TOML keys, netshape.cutter)."""

    program: Path
    tool: dict


def stock_from_dict(v: Any, *, source: str, base: Path, prefix: str = "", error: type = ValueError,
                    read_tool: Callable[..., dict] | None = None) -> dict:
    """The checked stock table ``v`` (or a STOCK.toml path string) as a dict: ``min_mm``, ``max_mm``,
    ``spacing_mm`` (if given), ``heights`` (Path or None), ``nodes`` (Z-map node count), ``pre_cut``
    (list of PreCut). Errors name ``source`` and the key as ``prefix + key``
    (e.g. ``job.toml: stock.spacing_mm = -1: must be positive``), raised as ``error``. ``read_tool``
    (source, base, where, value) reads a pre-cut's tool (default netshape.cutter.tool_table)."""
    if read_tool is None:
        from netshape.cutter import tool_table

        read_tool = partial(tool_table, error=error)
    if isinstance(v, (str, os.PathLike)):
        v = {"file": os.fspath(v)}
    t = cfg.check_keys(source, prefix.rstrip("."), v, STOCK_KEYS, error)
    sbase = base
    if "file" in t:
        p = cfg.file_path(source, base, f"{prefix}file", t["file"], error=error)
        inner = cfg.load_toml(p, str(p))
        cfg.check_keys(str(p), "", inner, STOCK_KEYS - {"file"}, error)
        t = {**inner, **{k: x for k, x in t.items() if k != "file"}}
        source, sbase = str(p), p.parent
    out: dict = {"pre_cut": [], "heights": None}
    for key in ("min_mm", "max_mm"):
        if key not in t:
            raise cfg.field_error(source, prefix + key, cfg.MISSING, "missing (the stock box [x, y, z] in mm)", error)
        out[key] = cfg.vec3(source, prefix + key, t[key], error)
    lo, hi = out["min_mm"], out["max_mm"]
    for i, ax in enumerate("xyz"):
        if not hi[i] > lo[i]:
            raise cfg.field_error(source, f"{prefix}max_mm[{i}]", hi[i],
                                  f"must exceed {prefix}min_mm[{i}] = {lo[i]} ({ax}) [mm]", error)
    if "spacing_mm" not in t and "heights" not in t:
        raise cfg.field_error(source, f"{prefix}spacing_mm", cfg.MISSING, "missing (Z-map node spacing in mm)", error)
    if "spacing_mm" in t:
        out["spacing_mm"] = cfg.number(source, f"{prefix}spacing_mm", t["spacing_mm"], positive=True, error=error)
        cells = (hi[0] - lo[0]) / out["spacing_mm"] * (hi[1] - lo[1]) / out["spacing_mm"]
        if cells > MAX_ZMAP_NODES:
            raise cfg.field_error(source, f"{prefix}spacing_mm", t["spacing_mm"],
                                  f"gives {cells:.3g} Z-map nodes (> 4e7); use a coarser spacing", error)
        out["nodes"] = cells
    if "heights" in t:
        hp = cfg.file_path(source, sbase, f"{prefix}heights", t["heights"], error=error)
        if hp.suffix.lower() not in (".npy", ".csv"):
            raise cfg.field_error(source, f"{prefix}heights", t["heights"],
                                  "must be a .npy or .csv file of (ny, nx) heights [mm]", error)
        ny, nx, about = heights_shape(hp)
        if ny * nx > MAX_ZMAP_NODES:
            raise cfg.field_error(source, f"{prefix}heights", t["heights"],
                                  f"holds {'at least ' if about else ''}{ny:.0f} x {nx} = {ny * nx:.3g} Z-map "
                                  "nodes, over the limit of 4e7 (not loaded)", error)
        out["heights"] = hp
        out["nodes"] = ny * nx
    pre = t.get("pre_cut", [])
    if not isinstance(pre, list):
        raise cfg.field_error(source, f"{prefix}pre_cut", pre,
                              f"must be an array of tables [[{prefix}pre_cut]]", error)
    for i, pc in enumerate(pre):
        w = f"{prefix}pre_cut[{i}]"
        cfg.check_keys(source, w, pc, PRE_CUT_KEYS, error)
        for k in ("program", "tool"):
            if k not in pc:
                raise cfg.field_error(source, f"{w}.{k}", cfg.MISSING, "missing", error)
        out["pre_cut"].append(PreCut(program=cfg.file_path(source, sbase, f"{w}.program", pc["program"], error=error),
                                     tool=read_tool(source, sbase, f"{w}.tool", pc["tool"])))
    return out


def heights_shape(path: Path, max_nodes: int = MAX_ZMAP_NODES) -> tuple[float, int, bool]:
    """(ny, nx, at_least) of a heights file without loading it: a .npy header, or a CSV's first row (nx)
    and its lines with data (ny), counted in 1 MB chunks. Counting stops once ny · nx exceeds
    ``max_nodes``; then ny is a lower bound and ``at_least`` is True."""
    if path.suffix.lower() == ".npy":
        import numpy as np

        try:
            with open(path, "rb") as fh:
                major, _ = np.lib.format.read_magic(fh)
                read = np.lib.format.read_array_header_1_0 if major == 1 else np.lib.format.read_array_header_2_0
                shape = read(fh)[0]
        except (ValueError, OSError):
            return 0.0, 0, False  # unreadable: the stock stage says so when it loads it
        if len(shape) != 2:
            return 0.0, 0, False
        return float(shape[0]), int(shape[1]), False
    with open(path, "rb") as fh:
        first = fh.readline(1 << 20)
        if not first.strip():
            return 0.0, 0, False
        nx = first.count(b",") + 1
        ny, last = 1, b"\n"
        while chunk := fh.read(1 << 20):
            ny += chunk.count(b"\n")
            last = chunk[-1:]
            if ny * nx > max_nodes:
                return float(ny), nx, True
    if last != b"\n":  # a last row without its newline
        ny += 1
    return float(ny), nx, False


def build_stock(spec: dict):
    """The Z-map of a checked stock (:func:`stock_from_dict`): the box at ``spacing_mm``, or the heights
    file over the box, then every pre-cut swept in order."""
    import numpy as np

    from netshape.cutter import cutter_from_dict
    from netshape.toolpath import GcodeWarning, read_gcode

    from . import ZMap, from_heights, sweep

    lo, hi = spec["min_mm"], spec["max_mm"]
    if spec["heights"] is not None:
        path = spec["heights"]
        if path.suffix.lower() == ".npy":
            h = np.load(path, allow_pickle=False)
        else:
            import io

            from netshape._text import read_text

            h = np.loadtxt(io.StringIO(read_text(path)), delimiter=",", ndmin=2)
        h = np.asarray(h, dtype=float)
        if h.ndim != 2 or min(h.shape) < 2:
            raise ValueError(f"stock.heights = {str(path)!r}: shape {h.shape}, must be (ny, nx) with ny, nx ≥ 2")
        if not np.isfinite(h).all():
            raise ValueError(f"stock.heights = {str(path)!r}: heights must be finite [mm]")
        if h.min() < lo[2]:
            raise ValueError(f"stock.heights = {str(path)!r}: height {h.min():g} below stock.min_mm[2] = {lo[2]:g}")
        z = from_heights(h, lo[0], hi[0], lo[1], hi[1], lo[2])
    else:
        z = ZMap(lo[0], hi[0], lo[1], hi[1], spec["spacing_mm"], hi[2], lo[2])
    import warnings

    for pc in spec["pre_cut"]:
        with warnings.catch_warnings():  # a pre-cut is read in its own coordinates, like the stock
            warnings.simplefilter("ignore", GcodeWarning)
            prog = read_gcode(pc.program, arcs="keep")
        sweep(z, cutter_from_dict(pc.tool, source="tool"), prog)
    return z


def load_stock(path: str | os.PathLike):
    """The Z-map of a STOCK.toml (the module docstring's keys): checked, built, pre-cuts swept.
    ValueError naming the file and the key for a bad one."""
    p = Path(os.fspath(path))
    if not p.is_file():
        raise ValueError(f"{p}: no such stock file")
    return build_stock(stock_from_dict(cfg.load_toml(p, str(p)), source=str(p), base=p.parent))
