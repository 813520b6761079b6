"""Edits of a TOML file's text that keep everything they do not touch (comments, order, spacing):
find a table's lines, replace or insert one key, append a block. Enough for the flat key = value
tables and [[array]] tables of netshape's model files; the caller checks the result parses."""

from __future__ import annotations

import re

_HEADER = re.compile(r"^\s*(\[\[?)\s*([^\[\]]+?)\s*\]\]?\s*(#.*)?$")


def _norm(name: str) -> str:
    return ".".join(p.strip().strip('"').strip("'") for p in name.split("."))


def _depth(text: str) -> int:
    """Net bracket depth of ``text`` outside strings and comments."""
    d, quote = 0, None
    for ch in text:
        if quote:
            if ch == quote:
                quote = None
        elif ch in "\"'":
            quote = ch
        elif ch == "#":
            break
        elif ch == "[":
            d += 1
        elif ch == "]":
            d -= 1
    return d


class TomlText:
    def __init__(self, text: str):
        self.lines = text.splitlines(keepends=True)
        if self.lines and not self.lines[-1].endswith("\n"):
            self.lines[-1] += "\n"

    def text(self) -> str:
        return "".join(self.lines)

    def _headers(self):
        out, depth = [], 0
        for i, line in enumerate(self.lines):
            if depth == 0:
                m = _HEADER.match(line)
                if m:
                    out.append((i, m.group(1), _norm(m.group(2))))
                    continue
            depth += _depth(line)
        return out

    def table_span(self, name: str, case_insensitive: bool = False):
        """(first line of the table's body, end) of ``[name]`` (the root table for ""), None if absent."""
        hs = self._headers()
        if name == "":
            return 0, hs[0][0] if hs else len(self.lines)
        same = (lambda a, b: a.lower() == b.lower()) if case_insensitive else (lambda a, b: a == b)
        for j, (i, kind, n) in enumerate(hs):
            if kind == "[" and same(n, name):
                return i + 1, hs[j + 1][0] if j + 1 < len(hs) else len(self.lines)
        return None

    def find_key(self, span, key: str):
        """(first, end) lines of ``key = …`` in the span (a multi-line array included), None if absent."""
        pat = re.compile(r"^\s*" + re.escape(key) + r"\s*=")
        i = span[0]
        while i < span[1]:
            if pat.match(self.lines[i]):
                j, depth = i, _depth(self.lines[i].split("=", 1)[1])
                while depth > 0 and j + 1 < len(self.lines):
                    j += 1
                    depth += _depth(self.lines[j])
                return i, j + 1
            i += 1
        return None

    def set_key(self, span, key: str, value: str, comment: str) -> None:
        """Replace ``key`` in the span by ``key = value`` under ``# comment``, or insert it after the
        span's last key line."""
        new = [f"# {comment}\n", f"{key} = {value}\n"]
        at = self.find_key(span, key)
        if at is not None:
            indent = re.match(r"^\s*", self.lines[at[0]]).group(0)
            self.lines[at[0]:at[1]] = [indent + s for s in new]
            return
        i = span[1]
        while i > span[0] and (not self.lines[i - 1].strip() or self.lines[i - 1].lstrip().startswith("#")):
            i -= 1
        self.lines[i:i] = new

    def append(self, block: str) -> None:
        if self.lines and self.lines[-1].strip():
            self.lines.append("\n")
        self.lines.extend(block.splitlines(keepends=True))
