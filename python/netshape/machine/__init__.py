"""netshape.machine — a 3-axis machine's geometric errors (ISO 230-1) and their synthesis into the
tool-tip error relative to the workpiece (Yang & Kweon §2, §4; C++ netshape::machine).

    import netshape as ns
    m = ns.machine.load_machine("examples/machines/hmc_yang_kweon.toml")
    e = ns.machine.tip_error(m, points)              # (n, 3) mm, exact product of transforms
    emap = ns.machine.grid_error_map(m, (9, 9, 5))    # Yang & Kweon eq. 16 over the workspace
    fig = ns.machine.plot_error_map(emap)             # Yang & Kweon Fig. 6

Yang & Kweon symbols → ISO 230-1 names (docs/machine.md): δ_ij → E{I}{J} (δ_xx → EXX, δ_yx → EYX …),
ε_ij → E{A,B,C for i = x,y,z}{J} (ε_xx → EAX, ε_yx → EBX, ε_zx → ECX …), S_xy → EC0Y,
S_yz → EA0Z, S_zx → −EB0Z, ε_xs/ε_ys → spindle_tilt_a/b, L → tool_length, T → spindle_nose.
"""

from __future__ import annotations

from .._core import machine as _m
from .provenance import machine_terms
from .description import AXES, iso_names, load_machine, machine_from_dict, read_error_table
from .volumetric_map import (
    ErrorMap,
    actual_points,
    compare_orders,
    error_map,
    grid_error_map,
    grid_points,
    plot_error_map,
    plot_surface_error,
    program_error_map,
    program_points,
    tip_error,
    volumetric_error,
)

Machine = _m.Machine
Axis = _m.Axis
ErrorFunction = _m.ErrorFunction
OutOfRange = _m.OutOfRange
Component = _m.Component
Side = _m.Side
Order = _m.Order
ideal_machine = _m.ideal_machine
component_name = _m.component_name
rotation_zyx = _m.rotation_zyx
CyclicTerm = _m.CyclicTerm
ThermalDrift = _m.ThermalDrift
approach_directions = _m.approach_directions


def state_error(machine, directions, times):
    """Backlash + thermal drift of the tip s(d, t) [mm] (C++ machine/state_error.hpp): directions
    (n, 3) (each axis' last direction of motion, ±1), times (n,) program time [s] → (n, 3)."""
    import numpy as np

    d = np.ascontiguousarray(directions, dtype=float).reshape(-1, 3)
    t = np.ascontiguousarray(times, dtype=float).reshape(-1)
    return _m.state_error(machine, d, t)


def actual_path(machine, commanded, times=None, initial=(1.0, 1.0, 1.0)):
    """Where the tip lands when the machine runs through the commanded points (n, 3) [mm] in order
    at program times (n,) [s] (default 0): p + e(p) + s(d, t), d each axis' approach direction
    (:func:`approach_directions` from ``initial``). (n, 3) [mm]."""
    import numpy as np

    p = np.ascontiguousarray(commanded, dtype=float).reshape(-1, 3)
    t = np.zeros(len(p)) if times is None else np.asarray(times, dtype=float)
    return p + _m.tip_error(machine, p) + state_error(machine, _m.approach_directions(p, initial), t)

#: Yang & Kweon symbol → (ISO 230-1 name, sign) for the paper's HMC. Its Z axis is on the workpiece
#: side, where the paper writes the table's own motion and netshape the tool's motion relative to the
#: workpiece (ISO 230-1 sense): δ_iz(z_table) = −E·Z(q) and ε_iz = −E·Z to first order, with the
#: table position z_table = −q (docs/machine.md).
SEEDS003_SYMBOLS = {
    **{f"δ_{d}{a}": (f"E{d.upper()}{a.upper()}", -1 if a == "z" else +1) for a in "xyz" for d in "xyz"},
    **{f"ε_{d}{a}": (f"E{'ABC'['xyz'.index(d)]}{a.upper()}", -1 if a == "z" else +1)
       for a in "xyz" for d in "xyz"},
    "S_xy": ("EC0Y", +1),
    "S_yz": ("EA0Z", +1),
    "S_zx": ("EB0Z", -1),
    "ε_xs": ("spindle_tilt_a", +1),
    "ε_ys": ("spindle_tilt_b", +1),
}

__all__ = [
    "AXES", "Axis", "Component", "CyclicTerm", "ThermalDrift", "actual_path", "approach_directions",
    "state_error", "ErrorFunction", "ErrorMap", "Machine", "Order", "OutOfRange",
    "SEEDS003_SYMBOLS", "Side", "actual_points", "compare_orders", "component_name", "error_map",
    "grid_error_map", "grid_points", "ideal_machine", "iso_names", "load_machine", "machine_terms", "machine_from_dict",
    "plot_error_map", "plot_surface_error", "program_error_map", "program_points", "read_error_table",
    "rotation_zyx", "tip_error", "volumetric_error",
]
