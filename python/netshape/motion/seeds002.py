"""Deprecated alias of :mod:`netshape.motion.lookahead_lee` (Lee & Lee's test paths); removed in the next release."""

from __future__ import annotations

import warnings

from .lookahead_lee import *  # noqa: F401,F403

warnings.warn("netshape.motion.seeds002 is deprecated; import netshape.motion.lookahead_lee instead",
              DeprecationWarning, stacklevel=2)
