"""
netshape C++ core (use the `netshape` package, not this module directly)
"""
from __future__ import annotations
from . import toolpath
from . import cutter
from . import stock
from . import force
from . import deflection
from . import geometry
from . import machine
from . import compensation
from . import motion
from . import posture
__all__: list[str] = ['compensation', 'cutter', 'deflection', 'force', 'geometry', 'machine', 'motion', 'posture', 'stock', 'toolpath']
