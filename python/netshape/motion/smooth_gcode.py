"""The smoothed program (block arrays of :func:`netshape.motion.smooth_path`) back out as G-code."""

from __future__ import annotations

import numpy as np

from netshape._atomic import atomic_write

_PLANE = ("G17", "G18", "G19")
_IJK = ((0, "I"), (1, "J"), (2, "K"))


def smoothed_gcode_lines(arrays) -> list[str]:
    """G-code lines (G21 G90, absolute mm, feeds in mm/min) for block arrays: G0 rapids, G1 lines,
    G2/G3 arcs with I/J/K centre offsets in their plane (G17/G18/G19)."""
    kind = np.asarray(arrays["kind"])
    start, end, center = (np.asarray(arrays[k], dtype=float) for k in ("start", "end", "center"))
    cw, plane, feed = np.asarray(arrays["clockwise"]), np.asarray(arrays["plane"]), np.asarray(arrays["feed"], float)
    out = ["(netshape smooth: smoothed program)", "G21 G90"]
    if len(kind):
        out.append(f"G0 X{start[0, 0]:.6f} Y{start[0, 1]:.6f} Z{start[0, 2]:.6f}")
    last_f, last_plane = None, None
    for i in range(len(kind)):
        x, y, z = end[i]
        words = f"X{x:.6f} Y{y:.6f} Z{z:.6f}"
        if kind[i] == 0:
            out.append(f"G0 {words}")
            continue
        f = ""
        if last_f is None or feed[i] != last_f:
            f = f" F{feed[i] * 60.0:.4f}"
            last_f = feed[i]
        if kind[i] == 1:
            out.append(f"G1 {words}{f}")
            continue
        pl = int(plane[i])
        pre = ""
        if pl != last_plane:
            pre = _PLANE[pl] + " "
            last_plane = pl
        off = center[i] - start[i]
        axes = ((0, 1), (2, 0), (1, 2))[pl]
        ijk = " ".join(f"{_IJK[a][1]}{off[a]:.6f}" for a in sorted(axes))
        out.append(f"{pre}{'G2' if cw[i] else 'G3'} {words} {ijk}{f}")
    out.append("M2")
    return out


def write_smoothed_gcode(arrays, path) -> None:
    """Write :func:`smoothed_gcode_lines` to `path` atomically."""
    with atomic_write(path, "w") as fh:
        fh.write("\n".join(smoothed_gcode_lines(arrays)) + "\n")
