"""netshape.motion — see DESIGN §4 and the C++ namespace netshape::motion."""

from __future__ import annotations

from ._core import motion as _motion  # noqa: F401

__all__: list[str] = []
