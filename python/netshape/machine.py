"""netshape.machine — see DESIGN §4 and the C++ namespace netshape::machine."""

from __future__ import annotations

from ._core import machine as _machine  # noqa: F401

__all__: list[str] = []
