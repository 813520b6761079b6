"""netshape.posture — see DESIGN §4 and the C++ namespace netshape::posture."""

from __future__ import annotations

from ._core import posture as _posture  # noqa: F401

__all__: list[str] = []
