"""The smoothed program written into the program's own text (``netshape plan --smoothed-gcode``).

Every line of the program stays in place, word for word — comments, parameter assignments, T M6,
coolant, spindle, work offsets, G64, the end word as written (M2 or M30) — except the lines whose moves
smoothing changed. Such a line keeps its other words (N, M, S, T, F, …) on a line of its own, and the
new blocks whose first program block it holds are written after it in the form of
:func:`netshape.motion.smooth_gcode.smoothed_gcode_lines` (G1 / G2 / G3, G5 for cubics in the XY
plane, G1 chords within the chord tolerance for other cubics), in the program's own frame (the work
offset and tool length of the block's program block taken off again) and units (G20: inch). A line
whose block came out unchanged (same kind, same end; a line may start later, where the curve before
it ended) is kept as written. No move is added that the program does not make.

O-words stay where they are: a program number, and a subroutine's definition (`oN sub` … `oN endsub`),
whose moves belong to the line that calls it. A call whose moves came out unchanged is kept as written;
otherwise the moves it makes are written in place of the call line (its comments kept), and the
definition stays, unused there.

A changed line's N label goes on its first written move (a changed line whose moves a curve took in
is left out when it holds nothing else). Before the next line kept as written, the program's modal
state there is restored on one line — its motion mode, plane, G91 when the program is incremental
there (the written moves are G90), and its last F word as written — so the lines after read as they did.
"""

from __future__ import annotations

import numpy as np

from netshape.motion.smooth_gcode import _check_format, _Writer, write_blocks

_MOTION_LETTERS = set("XYZIJKRPQL")  # the words of a move (P, Q, L: arcs' turns, G5, G5.2)
_MODES = {0.0: "G0", 1.0: "G1", 2.0: "G2", 3.0: "G3"}


def _words(line: str) -> tuple[list[tuple[str, str]], str]:
    """(letter, value text) words of a line, its comments (as text); values may be numbers,
    #parameters or [expressions]. A parameter assignment line has no words."""
    words, comments, i, n = [], [], 0, len(line)
    head = line.lstrip()
    if head.startswith("#"):
        return [], ""
    if head[:1] in "oO" and head[1:2].strip()[:1] in tuple("0123456789<"):  # o-word line: one word
        code = head.split("(")[0].split(";")[0].strip()
        j = head.find(code) + len(code)
        return [("O", code[1:])], _words(head[j:])[1]
    while i < n:
        c = line[i]
        if c == "(":
            j = line.find(")", i)
            j = n - 1 if j < 0 else j
            comments.append(line[i:j + 1])
            i = j + 1
        elif c == ";":
            comments.append(line[i:])
            break
        elif c.isalpha():
            j = i + 1
            while j < n and line[j] == " ":
                j += 1
            k = j
            if k < n and line[k] == "[":
                depth = 0
                while k < n:
                    depth += {"[": 1, "]": -1}.get(line[k], 0)
                    k += 1
                    if depth == 0:
                        break
            elif k < n and line[k] == "#":
                k += 1
                if k < n and line[k] == "<":
                    k = line.find(">", k) + 1 or n
                else:
                    while k < n and line[k].isdigit():
                        k += 1
            else:
                while k < n and (line[k] in "+-. " or line[k].isdigit()):
                    k += 1
            words.append((c.upper(), line[j:k].replace(" ", "")))
            i = k
        else:
            i += 1
    return words, " ".join(comments)


def _number(v: str) -> float | None:
    try:
        return float(v)
    except ValueError:
        return None


class _Modal:
    """The modal state a program line leaves: motion mode, plane, units, distance mode, last F."""

    def __init__(self):
        self.mode, self.plane, self.inch, self.incremental, self.f = "G1", "G17", False, False, None

    def read(self, words) -> None:
        for letter, v in words:
            if letter == "F":
                self.f = "F" + v
            if letter != "G" or _number(v) is None:
                continue
            g = float(v)
            if g in _MODES:
                self.mode = _MODES[g]
            elif g in (17.0, 18.0, 19.0):
                self.plane = f"G{int(g)}"
            elif g in (20.0, 21.0):
                self.inch = g == 20.0
            elif g in (90.0, 91.0):
                self.incremental = g == 91.0

    def restore(self) -> str:
        return " ".join([self.mode, self.plane] + (["G91"] if self.incremental else []) +
                        ([self.f] if self.f else []))


def _unchanged(new: dict, k: int, prog: dict, b: int, fmt: str) -> bool:
    kind = int(new["kind"][k])
    if kind != int(prog["kind"][b]) or (kind == 2 and fmt != "arcs") or kind == 3:
        return False
    same = lambda key: np.array_equal(np.asarray(new[key][k]), np.asarray(prog[key][b]))  # noqa: E731
    return same("end") and (kind != 2 or same("start"))


def spliced_gcode_lines(text: str, program: dict, frame_shift, new: dict, first, fmt: str = "arcs", *,
                        chord_tolerance: float = 0.001, feed_scale: float = 1.0) -> list[str]:
    """The program `text` with the smoothed blocks `new` (block arrays of smooth_path, ``first``: per
    new block its first program block) in place of the moves they replace (module docstring).

    program : the block arrays the program was read into (with its ``line`` per block) and smoothed
        from [mm]; frame_shift : (n, 3) per program block, its machine point less its point in the
        program's frame [mm] (work offset and tool length; zeros when none were applied);
        feed_scale : the factor the feeds in `new` carry over the program's (written back without it).
    """
    _check_format(fmt)
    first = np.asarray(first)
    line_of = np.asarray(program["line"])
    shift = np.asarray(frame_shift, dtype=float)
    blocks_of: dict[int, list[int]] = {}
    for b, ln in enumerate(line_of):
        blocks_of.setdefault(int(ln), []).append(b)
    news_of: dict[int, list[int]] = {}
    for k, b in enumerate(first):
        news_of.setdefault(int(b), []).append(k)
    modal = _Modal()
    chorded = "cubics outside the XY plane" + (" and every arc" if fmt == "g1" else "")
    out = [f"(netshape smooth: micro-segment runs replaced within the contour tolerance, form {fmt}; "
           f"{chorded} as G1 chords within {chord_tolerance:g} mm)"]
    pending = False  # written moves since the last line kept as written: restore the modal state first
    for ln, raw in enumerate(text.splitlines(), start=1):
        words, comments = _words(raw)
        own = blocks_of.get(ln, [])
        news = [k for b in own for k in news_of.get(b, [])]
        as_written = len(news) == len(own) and all(
            len(news_of.get(b, [])) == 1 and _unchanged(new, news_of[b][0], program, b, fmt) for b in own)
        if not own or as_written:
            if pending and words:
                out.append(modal.restore())
                pending = False
            out.append(raw)
            modal.read(words)
            continue
        modal.read(words)
        label = " ".join(f"{a}{v}" for a, v in words if a == "N")
        rest = " ".join(f"{a}{v}" for a, v in words if a not in _MOTION_LETTERS and a not in "NO" and not (
            a == "G" and _number(v) in (0.0, 1.0, 2.0, 3.0, 5.0, 17.0, 18.0, 19.0, 90.0, 91.0)))
        if rest or comments:  # the line's other words (and its label) stay, on a line of their own
            out.append(" ".join(x for x in (label, rest, comments) if x))
            label = ""
        if news:
            if not pending:  # a fresh writer: F (and G90) on its first move
                w = _Writer(["G90"] if modal.incremental else [])
            n0 = len(w.out)
            _chunk(w, new, news, first, shift, modal, fmt, chord_tolerance, feed_scale)
            if label and len(w.out) > n0:  # the label goes on the first move written for the line
                w.out[n0] = f"{label} {w.out[n0]}"
            out.extend(w.out)
            w.out.clear()
            pending = True
    return out


def _chunk(w, new, ks, first, shift, modal, fmt, tol, feed_scale) -> None:
    """The new blocks ks into writer w, in the program's frame and units."""
    unit = 25.4 if modal.inch else 1.0
    idx = np.asarray(ks)
    d = shift[first[idx]]
    sub = {key: np.asarray(new[key])[idx] for key in ("kind", "clockwise", "plane", "turns") if key in new}
    for key in ("start", "end", "center"):
        sub[key] = (np.asarray(new[key], dtype=float)[idx] - d) / unit
    if "ctrl" in new:
        sub["ctrl"] = (np.asarray(new["ctrl"], dtype=float)[idx] - d[:, None, :]) / unit
    sub["feed"] = np.asarray(new["feed"], dtype=float)[idx] / (feed_scale * unit)
    write_blocks(w, sub, fmt, tol / unit)


def frame_shift(machine: dict, program: dict) -> np.ndarray:
    """Per block, its end read with work offsets and tool lengths less its end read without [mm]."""
    a, b = np.asarray(machine["end"], dtype=float), np.asarray(program["end"], dtype=float)
    if a.shape != b.shape:
        raise ValueError(f"blocks = {len(a)} with offsets, {len(b)} without: must be the same program")
    return a - b

