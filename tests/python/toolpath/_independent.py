"""A small, independent pure-Python G-code interpreter used only to cross-check netshape's reader in
tests. It shares no code with the C++ reader: regex tokenising, a textual substitution of the
`#<name> = value` parameters and `[...]` arithmetic used by the shared programs, arcs from I/J/K or R,
and arc lengths / bounding boxes by dense sampling with NumPy."""

from __future__ import annotations

import math
import re

import numpy as np

_WORD = re.compile(r"([A-Za-z])\s*([-+]?\s*[0-9.]+)")
_PARAM_DEF = re.compile(r"^\s*#<(\w+)>\s*=\s*([-+0-9.]+)\s*$")


def _strip(line: str) -> str:
    line = re.sub(r"\([^)]*\)", "", line)
    return line.split(";", 1)[0]


def _substitute(line: str, params: dict) -> str:
    line = re.sub(r"#<(\w+)>", lambda m: repr(params[m.group(1).lower()]), line)
    # [a*b] products with plain numbers only (what the shared programs use)
    return re.sub(r"\[([^\[\]]*)\]", lambda m: repr(float(eval(m.group(1), {"__builtins__": {}}))), line)


def interpret(text: str) -> dict:
    """Blocks of a program as dicts: kind ('rapid'|'line'|'arc'), start, end, center, cw, plane, feed."""
    params: dict[str, float] = {}
    pos = np.zeros(3)
    motion, plane, scale, incremental, feed = None, 0, 1.0, False, 0.0
    blocks = []
    for raw in text.splitlines():
        line = _strip(raw).strip()
        if not line or line == "%":
            continue
        m = _PARAM_DEF.match(line)
        if m:
            params[m.group(1).lower()] = float(m.group(2))
            continue
        line = _substitute(line, params)
        words = [(k.upper(), float(v.replace(" ", ""))) for k, v in _WORD.findall(line)]
        gs = [v for k, v in words if k == "G"]
        ms = [v for k, v in words if k == "M"]
        w = {k: v for k, v in words if k not in "GM"}
        for g in gs:
            if g in (0, 1, 2, 3):
                motion = int(g)
            elif g in (17, 18, 19):
                plane = int(g) - 17
            elif g == 20:
                scale = 25.4
            elif g == 21:
                scale = 1.0
            elif g == 90:
                incremental = False
            elif g == 91:
                incremental = True
        if "F" in w:
            feed = w["F"] * scale / 60.0
        end = pos.copy()
        moved = False
        for i, k in enumerate("XYZ"):
            if k in w:
                end[i] = (pos[i] if incremental else 0.0) + w[k] * scale
                moved = True
        if moved:
            b = {"kind": {0: "rapid", 1: "line"}.get(motion, "arc"), "start": pos.copy(), "end": end, "feed": feed}
            if motion in (2, 3):
                a, bb = {0: (0, 1), 1: (2, 0), 2: (1, 2)}[plane]
                c = pos.copy()
                if "R" in w:
                    r = w["R"] * scale
                    d = end - pos
                    chord = math.hypot(d[a], d[bb])
                    h = math.sqrt(max(r * r - chord * chord / 4.0, 0.0))
                    left = np.array([-d[bb], d[a]]) / chord
                    side = (1.0 if motion == 3 else -1.0) * (1.0 if r > 0 else -1.0)
                    c[a] = (pos[a] + end[a]) / 2 + side * h * left[0]
                    c[bb] = (pos[bb] + end[bb]) / 2 + side * h * left[1]
                else:
                    for axis, letter in ((0, "I"), (1, "J"), (2, "K")):
                        if axis in (a, bb):
                            c[axis] = pos[axis] + w.get(letter, 0.0) * scale
                b.update(center=c, cw=motion == 2, plane=plane, turns=int(w.get("P", 1)))
            blocks.append(b)
            pos = end
        if any(m in (2, 30) for m in ms):
            break
    return {"blocks": blocks}


def sample_arc(b: dict, n: int = 20001) -> np.ndarray:
    """Points along an arc block (radius and normal coordinate vary linearly with the angle)."""
    a, bb = {0: (0, 1), 1: (2, 0), 2: (1, 2)}[b["plane"]]
    nrm = 3 - a - bb
    s, e, c = b["start"], b["end"], b["center"]
    t0 = math.atan2(s[bb] - c[bb], s[a] - c[a])
    t1 = math.atan2(e[bb] - c[bb], e[a] - c[a])
    r0 = math.hypot(s[a] - c[a], s[bb] - c[bb])
    r1 = math.hypot(e[a] - c[a], e[bb] - c[bb])
    closed = math.hypot(e[a] - s[a], e[bb] - s[bb]) < 1e-12
    if b["cw"]:
        sweep = -(2 * math.pi) if closed else -((t0 - t1) % (2 * math.pi) or 2 * math.pi)
        sweep -= 2 * math.pi * (b["turns"] - 1)
    else:
        sweep = 2 * math.pi if closed else ((t1 - t0) % (2 * math.pi) or 2 * math.pi)
        sweep += 2 * math.pi * (b["turns"] - 1)
    u = np.linspace(0.0, 1.0, n)
    ang = t0 + u * sweep
    r = r0 + u * (r1 - r0)
    p = np.empty((n, 3))
    p[:, a] = c[a] + r * np.cos(ang)
    p[:, bb] = c[bb] + r * np.sin(ang)
    p[:, nrm] = s[nrm] + u * (e[nrm] - s[nrm])
    return p


def figures(text: str) -> dict:
    """Counts, lengths [mm], bounding box [mm] and feed time [s] of a program, computed independently."""
    blocks = interpret(text)["blocks"]
    out = {"rapids": 0, "lines": 0, "arcs": 0, "rapid_length_mm": 0.0, "feed_length_mm": 0.0, "feed_time_s": 0.0}
    lo = np.full(3, np.inf)
    hi = np.full(3, -np.inf)
    for b in blocks:
        if b["kind"] == "arc":
            p = sample_arc(b)
            # arc length: planar arc length (exact for the linear-radius spiral to O(1/n²)) combined with the axial rise
            seg = np.linalg.norm(np.diff(p, axis=0), axis=1).sum()
            length = seg
        else:
            p = np.vstack([b["start"], b["end"]])
            length = float(np.linalg.norm(b["end"] - b["start"]))
        lo = np.minimum(lo, p.min(axis=0))
        hi = np.maximum(hi, p.max(axis=0))
        out[{"rapid": "rapids", "line": "lines", "arc": "arcs"}[b["kind"]]] += 1
        if b["kind"] == "rapid":
            out["rapid_length_mm"] += length
        else:
            out["feed_length_mm"] += length
            out["feed_time_s"] += length / b["feed"]
    out["bbox_min_mm"] = lo.tolist()
    out["bbox_max_mm"] = hi.tolist()
    out["blocks"] = blocks
    return out
