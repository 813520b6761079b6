"""netshape.discrepancy — where simulation and measurement disagree, which physical effect the model
lacks, and how much of the gap adding it closes (the workflow of docs/discrepancy.md).

    import netshape.discrepancy as nd
    b = nd.load_bundle("bundle/")        # manifest.toml + CSV files
    d = nd.diagnose(b)                   # Diagnosis: d.effect, d.effects, d.rms_before, d.rms_after …
    print(d.summary()); d.to_dict()

The catalogue (``nd.catalogue(kind)``) is an open registry: subclass :class:`Effect` and call
:func:`register_effect` to add your own. Python orchestration only: the models are evaluated by the
C++ kernels of netshape.force, netshape.machine and netshape.deflection; the fits are SciPy ``least_squares``.
"""

from __future__ import annotations

from .bundle import (
    Bundle,
    ForceExperiment,
    VolumetricExperiment,
    WallContourExperiment,
    WallExperiment,
    load_bundle,
)
from .catalogue import Effect, EffectFit, catalogue, register_effect, unregister_effect
from . import force_effects as _force_effects  # noqa: F401  (registers the cutting-force catalogue)
from . import volumetric_effects as _volumetric_effects  # noqa: F401  (registers the volumetric catalogue)
from . import wall_effects as _wall_effects  # noqa: F401  (registers the wall-error catalogue)
from .force_effects import ForceProblem, ForceSpec
from .volumetric_effects import VolumetricProblem, VolumetricSpec
from .wall_effects import WallProblem, WallSpec
from .workflow import Diagnosis, diagnose, make_problem

__all__ = [
    "Bundle",
    "Diagnosis",
    "Effect",
    "EffectFit",
    "ForceExperiment",
    "ForceProblem",
    "ForceSpec",
    "VolumetricExperiment",
    "VolumetricProblem",
    "VolumetricSpec",
    "WallContourExperiment",
    "WallExperiment",
    "WallProblem",
    "WallSpec",
    "catalogue",
    "diagnose",
    "load_bundle",
    "make_problem",
    "register_effect",
    "unregister_effect",
]
