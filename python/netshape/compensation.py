"""netshape.compensation — see DESIGN §4 and the C++ namespace netshape::compensation."""

from __future__ import annotations

from ._core import compensation as _compensation  # noqa: F401

__all__: list[str] = []
