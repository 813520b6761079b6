"""Trouble met while running a job, reported in summary.json ``warnings`` as {``kind``, ``line``,
``message``}: the program is valid, but something in it will not come out as the job predicts."""

from __future__ import annotations

import numpy as np

#: At most this many warnings of one kind are listed; the last one says how many more there were.
MAX_PER_KIND = 20


def tool_shorter_than_cut(job, blocks, warnings: list) -> None:
    """Cuts deeper below the stock top than the tool sticks out (a feed move without a feed is refused
    by the reader already)."""
    top = job.stock["max_mm"][2] if job.stock.get("max_mm") is not None else None
    stick = job.tool.get("stick_out_mm")
    if top is not None and stick:
        deep = [b for b in blocks if int(b.kind) != 0 and top - min(b.start[2], b.end[2]) > float(stick)]
        if deep:
            b = deep[0]
            warnings.append({"kind": "tool_shorter_than_cut", "line": int(b.line),
                             "message": f"line {b.line} cuts {top - min(b.start[2], b.end[2]):g} mm below the stock "
                                        f"top, more than the tool's stick-out {float(stick):g} mm (the holder would "
                                        "hit the stock)"})


def outside_travel(machine, tp_machine) -> list[dict]:
    """Moves of the program (machine frame, so axis positions) that leave an axis' travel
    (``travel_mm`` of the machine TOML), one warning per move, the whole move counted (arcs by their
    bounding box). The machine's error there is extrapolated, and volumetric compensation refuses
    such a program."""
    from netshape import toolpath as tpm

    axes = list(machine.axes)[:3]
    lo = np.array([a.travel_min for a in axes])
    hi = np.array([a.travel_max for a in axes])
    out: list[dict] = []
    count = 0
    for b in tp_machine.blocks:
        bmin, bmax = (np.asarray(v).ravel() for v in tpm.block_bounds(b))
        below, above = bmin < lo, bmax > hi
        if not (below.any() or above.any()):
            continue
        count += 1
        if len(out) >= MAX_PER_KIND:
            continue
        k = int(np.flatnonzero(below | above)[0])
        reach = bmin[k] if below[k] else bmax[k]
        out.append({"kind": "move_outside_travel", "line": int(b.line),
                    "message": f"line {b.line}: axis {'XYZ'[k]} reaches {reach:.4f} mm, outside its travel "
                               f"[{lo[k]:g}, {hi[k]:g}] mm (machine frame)"})
    if count > len(out):
        out[-1]["message"] += f"; {count - len(out)} more moves leave the travel"
    return out
