"""netshape.geometry — see DESIGN §4 and the C++ namespace netshape::geometry."""

from __future__ import annotations

from ._core import geometry as _geometry  # noqa: F401

__all__: list[str] = []
