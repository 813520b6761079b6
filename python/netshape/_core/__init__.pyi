"""
netshape C++ core (use the `netshape` package, not this module directly)
"""
from __future__ import annotations
import typing
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
__all__: list[str] = ['compensation', 'cutter', 'deflection', 'force', 'geometry', 'kernel_isa', 'machine', 'motion', 'posture', 'set_progress', 'stock', 'toolpath']
def kernel_isa() -> str:
    """
    Instruction set of the SIMD kernels in this process: 'baseline', 'avx2' or 'avx512' (the best the CPU runs unless NETSHAPE_ISA names a lower one).
    """
def set_progress(callback: typing.Any) -> None:
    """
    Sets the callable `callback(what: str, done: int, total: int)` that long C++ computations call from the importing thread, at most 20 times a second (None removes it). An exception it raises stops the computation and propagates; Ctrl-C does the same without a callback.
    """
