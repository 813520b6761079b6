"""netshape: predict the shape errors of a CNC program and rewrite it so the part comes out right.

Areas are submodules, mirroring the C++ namespaces ``netshape::<area>``::

    import netshape as ns
    tp = ns.toolpath.read_gcode("part.ngc")

Units everywhere: mm, s, N, MPa, rad (feeds in mm/s; mm/min only in G-code and keys that say so).
"""

from __future__ import annotations

from importlib import import_module as _import_module
from pathlib import Path as _Path

from .errors import Error, ParseError

__version__ = "0.1.0"

_AREAS = (
    "toolpath",
    "cutter",
    "stock",
    "force",
    "deflection",
    "geometry",
    "machine",
    "compensation",
    "motion",
    "posture",
)


def __getattr__(name: str):
    # Areas load on first use, so `import netshape` stays fast for the CLI.
    if name in _AREAS:
        module = _import_module(f".{name}", __name__)
        globals()[name] = module
        return module
    raise AttributeError(f"module 'netshape' has no attribute {name!r}")


def kernel_isa() -> str:
    """Instruction set of the C++ SIMD kernels in this process: ``"baseline"``, ``"avx2"`` or ``"avx512"``.

    The best one the CPU runs is chosen once per process; the environment variable ``NETSHAPE_ISA``
    (set before netshape is imported) forces a lower one. Every choice gives the same results.
    """
    from . import _core

    return _core.kernel_isa()


def cmake_dir() -> str:
    """Folder holding ``netshapeConfig.cmake`` of the C++ library installed with this package.

    Pass it as ``-Dnetshape_DIR=...`` (or on ``CMAKE_PREFIX_PATH``) to build a C++ program against
    netshape: ``find_package(netshape CONFIG REQUIRED)`` then link ``netshape::netshape``.
    """
    here = _Path(__file__).resolve().parent
    for libdir in ("lib", "lib64"):
        candidate = here / libdir / "cmake" / "netshape"
        if (candidate / "netshapeConfig.cmake").is_file():
            return str(candidate)
    raise FileNotFoundError(
        "the C++ library is not installed with this netshape (a development build?); "
        "install the package with pip to get it"
    )


__all__ = ["Error", "ParseError", "cmake_dir", "kernel_isa", "__version__", *_AREAS]
