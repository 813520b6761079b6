"""netshape.stock — see DESIGN §4 and the C++ namespace netshape::stock."""

from __future__ import annotations

from ._core import stock as _stock  # noqa: F401

__all__: list[str] = []
