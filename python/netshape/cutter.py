"""netshape.cutter — see DESIGN §4 and the C++ namespace netshape::cutter."""

from __future__ import annotations

from ._core import cutter as _cutter  # noqa: F401

__all__: list[str] = []
