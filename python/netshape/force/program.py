"""Force along a program on a Z-map stock (docs/force.md "per path position")."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from netshape._core import force as _f


@dataclass
class ProgramForceResult:
    """Per force sample along the program (m samples): positions (m, 3) [mm], block (m,) index,
    feed_direction (m, 3), mean and peak (m, 3) [N] per revolution (forces on the cutter in the
    local cutting frame: X along the feed), peak_resultant and mean_resultant (m,) [N],
    engaged_fraction (m,), removed_volume [mm³]."""

    positions: np.ndarray
    block: np.ndarray
    feed_direction: np.ndarray
    mean: np.ndarray
    peak: np.ndarray
    peak_resultant: np.ndarray
    mean_resultant: np.ndarray
    engaged_fraction: np.ndarray
    removed_volume: float

    def to_dict(self) -> dict:
        return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in self.__dict__.items()}


def simulate_program(stock, cutter, program, coefficients, *, step: float = 0.5, samples_per_revolution: int = 72,
                     bins: int = 360, disk_height: float = 0.1, element_angle_deg: float = 2.0,
                     feed_per_tooth: float = 0.0, spindle_rpm: float = 0.0, copy_stock: bool = True,
                     chip=None) -> ProgramForceResult:
    """Cut ``program`` (netshape.toolpath Toolpath, feeds in mm/s) through ``stock``
    (netshape.stock.ZMap) with ``cutter`` and return the per-revolution forces at sample positions
    every ``step`` mm. ``coefficients``: LinearEdgeCoefficients or
    netshape.deflection.SizeEffectCoefficients (flat) or BallEndCoefficients (ball).
    A flat cutter's chip carries the cutter's runout (``cutter.runout_rho``, ``runout_lambda``) and
    the coefficients' chip-size effect, or ``chip`` (a RunoutSizeEffect) when given
    (netshape.deflection.chip.chip_of); a ball cutter's carries the same runout (along the element
    normal, docs/force.md) and refuses a chip exponent ≠ 1 (its size effect is Feng–Menq's m_T, m_R).
    The stock is updated as the cutter moves; with ``copy_stock`` (default) a copy is cut and the
    argument is left as it was. ``feed_per_tooth`` / ``spindle_rpm`` > 0 override the program's."""
    import math

    from netshape.deflection.chip import SizeEffectCoefficients, chip_of

    if isinstance(coefficients, (_f.LinearEdgeCoefficients, SizeEffectCoefficients)):
        coefficients, ext = chip_of(coefficients, chip, cutter)
        key = "linear_edge"
    elif isinstance(coefficients, _f.BallEndCoefficients):
        _, ext = chip_of(coefficients, chip, cutter)  # the cutter's runout unless ``chip`` is given
        key = "ball_end"
    else:
        raise ValueError(f"coefficients = {coefficients!r}: must be LinearEdgeCoefficients, "
                         "SizeEffectCoefficients or BallEndCoefficients")
    z = stock.copy() if copy_stock else stock
    opts = _f.ProgramForceOptions(step=step, samples_per_revolution=samples_per_revolution, bins=bins,
                                  disk_height=disk_height, element_angle=math.radians(element_angle_deg),
                                  feed_per_tooth=feed_per_tooth, spindle_rpm=spindle_rpm)
    r = _f.simulate_program_core(z, cutter, program, options=opts, chip=ext, **{key: coefficients})
    return ProgramForceResult(**r)
