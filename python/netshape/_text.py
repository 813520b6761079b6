"""Reading text input files (TOML, CSV, JSON): one place that decodes them and turns what the parsers
raise into one ValueError naming the file and, where known, the line.

- Input files are UTF-8 (a UTF-8 byte-order mark is allowed); any other byte is refused naming the file,
  line and column (G-code programs are the exception: netshape.toolpath reads them as Latin-1 when
  they are not UTF-8).
- Nesting deeper than :data:`MAX_DEPTH` (arrays or tables in arrays or tables) is refused before the
  parser recurses into it.
"""

from __future__ import annotations

import json
import os
import re
import sys

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

#: Deepest nesting of arrays / tables / objects accepted in an input file.
MAX_DEPTH = 64


class InputError(ValueError):
    """An input file that cannot be read as the text it should be (names the file)."""


def _name(path, src) -> str:
    return src if src is not None else os.fspath(path)


def decode(data: bytes, src: str) -> str:
    """``data`` as UTF-8 text; a non-UTF-8 byte → InputError ``src:LINE: not UTF-8 text (byte 0xE4 at
    column C)``."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        col = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
        raise InputError(f"{src}:{line}: not UTF-8 text (byte 0x{data[exc.start]:02X} at column {col}); "
                         "save the file as UTF-8") from None
    return text[1:] if text.startswith("\ufeff") else text


def read_bytes(path, src: str | None = None) -> bytes:
    with open(path, "rb") as fh:
        return fh.read()


def read_text(path, src: str | None = None) -> str:
    """The UTF-8 text of ``path`` (``src`` names it in errors; default the path)."""
    return decode(read_bytes(path), _name(path, src))


def read_controller_text(path) -> str:
    """The text of a file a controller or a measuring program wrote (a tool table, a ``.var`` parameter
    file, a DynoWare export): UTF-8 when it is, else Latin-1 (ISO 8859-1, one character per byte), as
    such software writes its comments and labels in the machine's local code page. Their numbers and
    keywords are ASCII, so no byte is replaced: a non-ASCII byte inside a number is refused by the
    reader's own check, naming the line."""
    data = read_bytes(path)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        text = data.decode("latin-1")
    return text[1:] if text.startswith("\ufeff") else text


#: What is not structure: strings (and TOML comments), dropped before brackets are counted.
_TOML_SKIP = re.compile(r'"""[\s\S]*?"""|\'\'\'[\s\S]*?\'\'\'|"(?:\\.|[^"\\\n])*"|\'[^\'\n]*\'|#[^\n]*')
_JSON_SKIP = re.compile(r'"(?:\\.|[^"\\])*"')


def _depth_check(text: str, src: str, skip: re.Pattern) -> None:
    """Refuse nesting deeper than MAX_DEPTH, counted over the brackets outside strings and comments (an
    upper bound of the nesting of TOML inline tables and arrays, exact for JSON)."""
    if text.count("[") + text.count("{") <= MAX_DEPTH:
        return
    bare = skip.sub(lambda m: "\n" * m.group().count("\n"), text)  # keeps the line numbers
    depth = 0
    for m in re.finditer(r"[\[\]{}]", bare):
        if m.group() in "[{":
            depth += 1
            if depth > MAX_DEPTH:
                line = bare.count("\n", 0, m.start()) + 1
                raise InputError(f"{src}:{line}: nested more than {MAX_DEPTH} levels deep")
        else:
            depth = max(0, depth - 1)


def loads_toml(text: str, src: str) -> dict:
    _depth_check(text, src, _TOML_SKIP)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{src}: not valid TOML: {exc}") from None
    except RecursionError:
        raise InputError(f"{src}: nested more than {MAX_DEPTH} levels deep") from None


def read_toml(path, src: str | None = None) -> dict:
    """The TOML document of ``path`` as a dict; InputError naming the file (and line) if it is not UTF-8,
    not TOML, or nested too deeply."""
    return loads_toml(read_text(path, src), _name(path, src))


def loads_json(text: str, src: str):
    _depth_check(text, src, _JSON_SKIP)

    def constant(name):
        raise InputError(f"{src}: not valid JSON: {name} is not a number JSON allows")

    try:
        return json.loads(text, parse_constant=constant)
    except json.JSONDecodeError as exc:
        raise InputError(f"{src}:{exc.lineno}: not valid JSON: {exc.msg} (column {exc.colno})") from None
    except RecursionError:
        raise InputError(f"{src}: nested more than {MAX_DEPTH} levels deep") from None


def read_json(path, src: str | None = None):
    """The JSON value of ``path``; InputError naming the file (and line) if it is not UTF-8 or not JSON
    (NaN and Infinity included), or nested too deeply."""
    return loads_json(read_text(path, src), _name(path, src))
