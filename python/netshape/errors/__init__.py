"""netshape's exception types.

- :class:`Error` (a ``RuntimeError``): a failure that is not the caller's input, e.g. an iteration
  that did not converge.
- ``ValueError``: bad input; the message names the field and the value.
- :class:`ParseError` (a ``ValueError``): bad input text at a known position (file, line, column).
"""

from __future__ import annotations


class Error(RuntimeError):
    """A netshape failure that is not bad input (non-convergence, internal limits)."""


class ParseError(ValueError):
    """Bad input text. ``source``, ``line`` and ``column`` (1-based, 0 = unknown) locate it."""

    def __init__(self, message: str, source: str = "", line: int = 0, column: int = 0, reason: str = ""):
        super().__init__(message)
        self.source = source
        self.line = line
        self.column = column
        self.reason = reason or message

    def __reduce__(self):
        return (type(self), (str(self), self.source, self.line, self.column, self.reason))
