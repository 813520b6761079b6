"""The scheduled program: its pieces as blocks (planned by netshape.motion), and as the program's own text
with only F words and block splits added (docs/feeds.md, "Lossless").

Every line stays as written except that each feed move's line gets an F word (its own F replaced, or one
added before its comments) and, where its block is split, the pieces before its last are written on lines
of their own just before it: ``G1 X… Y… Z… F…`` to the piece's end, in the program's units. A block is
split only where that leaves the line itself valid as written: a straight G1 move, absolute (G90), one
move on the line, no words on it but N, G0–G3, X, Y, Z, F and comments, and no cutter radius
compensation (G41/G42) in the program. Any other block keeps one piece, at the smallest feed of its pieces.
Feeds are written rounded down (0.1 mm/min, 0.01 in/min), so no written feed exceeds its schedule.
"""

from __future__ import annotations

import re

import numpy as np

from netshape.motion.gcode_splice import _Modal, _number, _words

_SPLIT_WORDS = set("NGXYZF")
_F_WORD = re.compile(r"[Ff]\s*(\[[^\]]*\]|#<[^>]*>|#\d+|[-+]?(\d+\.?\d*|\.\d+))")


def splittable_blocks(text: str, program) -> np.ndarray:
    """(n) bool per block of ``program`` (read from ``text``): the block may be split (module docstring)."""
    lines = text.splitlines()
    n = len(program.blocks)
    ok = np.zeros(n, dtype=bool)
    if re.search(r"(?i)G\s*4[12](?!\d)", "\n".join(_code(ln) for ln in lines)):
        return ok
    per_line: dict[int, int] = {}
    for b in program.blocks:
        per_line[int(b.line)] = per_line.get(int(b.line), 0) + 1
    modal = _Modal()
    by_line = {}
    for ln, raw in enumerate(lines, start=1):
        words, _ = _words(raw)
        modal.read(words)
        plain = all(a in _SPLIT_WORDS for a, _ in words) and all(
            _number(v) in (0.0, 1.0, 2.0, 3.0) for a, v in words if a == "G")
        by_line[ln] = plain and not modal.incremental and per_line.get(ln, 0) == 1
    for i, b in enumerate(program.blocks):
        ok[i] = int(b.kind) == 1 and by_line.get(int(b.line), False)
    return ok


def _code(line: str) -> str:
    """The line without its comments."""
    return re.sub(r"\([^)]*\)|;.*$", "", line)


def merge_unsplittable(pieces: dict, splittable: np.ndarray) -> dict:
    """Pieces with every block that may not be split (``splittable`` False) as one piece at the smallest
    feed of its pieces (its binding and sample from that piece)."""
    blk = np.asarray(pieces["block"])
    out = {k: [] for k in pieces}
    i, n = 0, len(blk)
    while i < n:
        j = i
        while j < n and blk[j] == blk[i]:
            j += 1
        if splittable[blk[i]] or j - i == 1:
            for k in pieces:
                out[k].extend(np.asarray(pieces[k])[i:j].tolist())
        else:
            m = i + int(np.argmin(np.asarray(pieces["feed"])[i:j]))
            for k in pieces:
                out[k].append(np.asarray(pieces[k])[m].item())
            out["start"][-1], out["end"][-1] = 0.0, 1.0
        i = j
    return {k: np.asarray(v) for k, v in out.items()}


def round_feeds(feed_mm_s: np.ndarray, inch: bool = False) -> np.ndarray:
    """Feeds [mm/s] rounded down to what the G-code F word says (0.1 mm/min or 0.01 in/min)."""
    f = np.asarray(feed_mm_s, dtype=float) * 60.0
    if inch:
        return np.floor(f / 25.4 * 100.0 + 1e-9) / 100.0 * 25.4 / 60.0
    return np.floor(f * 10.0 + 1e-9) / 10.0 / 60.0


def copy_block(b):
    """A copy of a toolpath Block (every field)."""
    from netshape import toolpath as tpm

    nb = tpm.Block()
    for a in ("kind", "start", "end", "center", "clockwise", "plane", "turns", "feed", "spindle_rpm", "tool",
              "line"):
        setattr(nb, a, getattr(b, a))
    return nb


def pieces_toolpath(program, pieces: dict):
    """The program with each block cut into its pieces (rapids and blocks without pieces as they are),
    feeds from ``pieces["feed"]`` [mm/s]; ``origin`` per new block its program block. Returns
    (Toolpath, piece index per new block, −1 for blocks without a piece)."""
    by_block: dict[int, list[int]] = {}
    for k, b in enumerate(np.asarray(pieces["block"])):
        by_block.setdefault(int(b), []).append(k)
    blocks, origin, which = [], [], []
    for i, b in enumerate(program.blocks):
        ks = by_block.get(i)
        if not ks:
            blocks.append(b)
            origin.append(i)
            which.append(-1)
            continue
        for k in ks:
            s0, s1 = float(pieces["start"][k]), float(pieces["end"][k])
            nb = copy_block(b)
            if len(ks) > 1:
                nb.start = np.asarray(b.point_at(s0), dtype=float)
                nb.end = np.asarray(b.point_at(s1), dtype=float)
            nb.feed = float(pieces["feed"][k])
            blocks.append(nb)
            origin.append(i)
            which.append(k)
    return program.with_blocks(blocks, origin), np.asarray(which)


def cap_to_plan(pieces: dict, which: np.ndarray, trajectory) -> dict:
    """Each piece's feed lowered to the largest feed the plan reaches in it (the planner decides: the
    machine never runs a piece faster than that, so the plan is the same and no feed is asked for that
    the plan cannot reach within its piece). Returns the pieces with ``reached`` [mm/s] added."""
    blk = np.asarray(trajectory.block, dtype=np.int64)
    fd = np.asarray(trajectory.feed, dtype=float)
    top = np.zeros(len(which))
    ok = (blk >= 0) & (blk < len(which))
    np.maximum.at(top, blk[ok], fd[ok])
    reached = np.full(len(pieces["feed"]), np.inf)
    for nb, k in enumerate(which):
        if k >= 0:
            reached[k] = top[nb]
    out = dict(pieces)
    feed = np.asarray(pieces["feed"], dtype=float)
    out["reached"] = reached
    out["capped"] = (reached > 0) & (reached < feed * (1 - 1e-3))
    out["feed"] = np.where(out["capped"], reached, feed)
    return out


def merge_equal(pieces: dict) -> dict:
    """Adjacent pieces of one block with the same feed as one piece (the first one's binding)."""
    n = len(pieces["feed"])
    keep = np.ones(n, dtype=bool)
    end = np.asarray(pieces["end"], dtype=float).copy()
    last = 0
    for k in range(1, n):
        if pieces["block"][k] == pieces["block"][last] and pieces["feed"][k] == pieces["feed"][last]:
            keep[k] = False
            end[last] = end[k]
        else:
            last = k
    out = {key: np.asarray(v)[keep] for key, v in pieces.items()}
    out["end"] = end[keep]
    return out


def _fmt(v: float, digits: int) -> str:
    s = f"{v:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _with_feed(raw: str, f_text: str) -> str:
    """The line with its F word's value replaced by ``f_text``, or F added before its comments."""
    parts = re.split(r"(\([^)]*\)|;.*$)", raw)
    for i in range(0, len(parts), 2):  # code parts are the even ones
        if _F_WORD.search(parts[i]):
            parts[i] = _F_WORD.sub(lambda _: "F" + f_text, parts[i], count=1)
            return "".join(parts)
    code = parts[0].rstrip()
    gap = "" if not code else " "
    return code + gap + "F" + f_text + (" " + "".join(parts[1:]).lstrip() if len(parts) > 1 and
                                         "".join(parts[1:]).strip() else "")


def scheduled_gcode_lines(text: str, program, pieces: dict, header: str) -> tuple[list[str], list[int]]:
    """The program ``text`` (read into ``program``, program coordinates) with its feed lines' F words set
    from ``pieces`` (after :func:`merge_unsplittable`: a line's block split only when splittable) and the
    splits written before their lines (module docstring). ``header`` is one comment line. Returns the
    lines and, per line, the program line it comes from (0 for the header)."""
    by_block: dict[int, list[int]] = {}
    for k, b in enumerate(np.asarray(pieces["block"])):
        by_block.setdefault(int(b), []).append(k)
    blocks_of: dict[int, list[int]] = {}
    for i, b in enumerate(program.blocks):
        blocks_of.setdefault(int(b.line), []).append(i)
    lines = text.splitlines()
    out: list[str] = []
    start = 1 if lines and lines[0].strip() == "%" else 0
    out.extend(lines[:start])
    out.append(header)
    src = list(range(1, start + 1)) + [0]
    modal = _Modal()
    for ln, raw in enumerate(lines[start:], start=start + 1):
        words, _ = _words(raw)
        modal.read(words)
        ks = [k for i in blocks_of.get(ln, []) for k in by_block.get(i, [])]
        if not ks:
            out.append(raw)
            src.append(ln)
            continue
        unit, digits = (25.4, 5) if modal.inch else (1.0, 4)
        if len(blocks_of[ln]) > 1:  # several moves on one line: one F word, the smallest feed, no split
            ks = [min(ks, key=lambda k: pieces["feed"][k])]
        feeds = round_feeds(np.asarray(pieces["feed"])[ks], modal.inch) * 60.0 / unit
        fdig = 2 if modal.inch else 1
        for k, f in zip(ks[:-1], feeds[:-1]):
            b = program.blocks[int(pieces["block"][k])]
            p = np.asarray(b.point_at(float(pieces["end"][k])), dtype=float) / unit
            xyz = " ".join(f"{a}{_fmt(v, digits)}" for a, v in zip("XYZ", p))
            out.append(f"G1 {xyz} F{_fmt(f, fdig)}")
            src.append(ln)
        out.append(_with_feed(raw, _fmt(feeds[-1], fdig)))
        src.append(ln)
    return out, src


def header_comment(limits_stated: dict) -> str:
    """One comment line naming what was optimised against which limits."""
    text = ", ".join(f"{k} {v:g}" for k, v in limits_stated.items())
    return f"(netshape feeds: F words set and blocks split where the engagement changes; limits: {text})"


__all__ = ["cap_to_plan", "copy_block", "header_comment", "merge_equal", "merge_unsplittable",
           "pieces_toolpath", "round_feeds", "scheduled_gcode_lines", "splittable_blocks"]
