"""netshape.deflection — see DESIGN §4 and the C++ namespace netshape::deflection."""

from __future__ import annotations

from ._core import deflection as _deflection  # noqa: F401

__all__: list[str] = []
