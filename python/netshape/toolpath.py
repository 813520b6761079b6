"""netshape.toolpath — see DESIGN §4 and the C++ namespace netshape::toolpath."""

from __future__ import annotations

from ._core import toolpath as _toolpath  # noqa: F401

__all__: list[str] = []
