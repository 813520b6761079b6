"""netshape.force — see DESIGN §4 and the C++ namespace netshape::force."""

from __future__ import annotations

from ._core import force as _force  # noqa: F401

__all__: list[str] = []
