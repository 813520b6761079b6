"""The stages of the main job that work in the stock's frame (stock, cut, forces), the feed plan and the
error figures, one function each. They take and return plain objects (no file writes); the program
and its frames are in :mod:`netshape.job.program`, the machine stages in
:mod:`netshape.job.stage_volumetric`, the deflection stage in :mod:`netshape.job.stage_deflection`.
:mod:`netshape.job.run` calls them in order, times them and writes the outputs.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from .program import Program, _sub_toolpath, stock_frame_toolpath
from .spec import Job

if TYPE_CHECKING:
    from .stage_deflection import DeflectionResult
    from .stage_volumetric import VolumetricResult

# ---------------------------------------------------------------------------------------------- stock


def make_cutter(tool: dict):
    from netshape.cutter import cutter_from_dict

    return cutter_from_dict(tool, source="tool")


def stage_stock(job: Job):
    """The stock before the program: a box or a heights file, then every ``[[stock.pre_cut]]`` swept in
    order (netshape.stock.config.build_stock). Returns a netshape.stock.ZMap."""
    from netshape.stock.config import build_stock

    return build_stock(job.stock)


def stage_cut(job: Job, stock0, prog: Program, warnings: list | None = None):
    """The stock after the program (Z-map material removal). Returns (ZMap, removed volume [mm³]).
    Rapid moves that remove material are appended to ``warnings`` as ``rapid_through_material`` with
    their program line (each rapid is swept on its own, in order, to tell which)."""
    from netshape import stock as ns

    z = stock0.copy()
    tp = stock_frame_toolpath(prog)
    cutter = make_cutter(job.tool)
    blocks = list(tp.blocks)
    rapid = [i for i, b in enumerate(blocks) if int(b.kind) == 0]
    removed, done = 0.0, 0
    for i in rapid + [len(blocks)]:
        if i > done:
            removed += float(ns.sweep(z, cutter, _sub_toolpath(tp, blocks[done:i])).removed_volume)
        if i < len(blocks):
            st = ns.sweep(z, cutter, _sub_toolpath(tp, blocks[i:i + 1]))
            removed += float(st.removed_volume)
            if st.removed_volume > 1e-9 and warnings is not None:
                b = blocks[i]
                warnings.append({"kind": "rapid_through_material", "line": int(b.line),
                                 "message": f"the rapid (G0) move on line {b.line} to X{b.end[0]:g} Y{b.end[1]:g} "
                                            f"Z{b.end[2]:g} removes {st.removed_volume:.3g} mm^3 of stock"})
        done = i + 1
    if warnings is not None:
        from .warnings import tool_shorter_than_cut

        tool_shorter_than_cut(job, blocks, warnings)
    return z, removed


# ---------------------------------------------------------------------------------------------- forces


def coefficients_for(job: Job, cutter):
    """Force coefficients of the job for its cutter (linear edge for flat/bull, the ball model for ball;
    with a ``chip_exponent`` ≠ 1 in the table: netshape.deflection.chip.SizeEffectCoefficients)."""
    from netshape import force as nf
    from netshape.cutter import CutterKind

    c = job.coefficients
    is_ball = cutter.kind == CutterKind.ball
    if isinstance(c, dict):
        from netshape.deflection.chip import SIZE_EFFECT_KEYS, SizeEffectCoefficients

        vals = {k.split("_")[0].lower(): v for k, v in c.items() if k not in SIZE_EFFECT_KEYS}
        if is_ball:
            raise ValueError("coefficients: a ball end mill takes a named ball set (e.g. kim_zas_ball12)")
        k = nf.LinearEdgeCoefficients(**vals)
        if c.get("chip_exponent", 1.0) != 1.0:
            return SizeEffectCoefficients(k, c["chip_exponent"], c.get("reference_chip_mm", 0.0))
        return k
    if "=" in c:
        if is_ball:
            raise ValueError(f"coefficients = {c!r}: a ball end mill takes a named ball set (e.g. kim_zas_ball12)")
        return nf.parse_coefficients(c)
    if c in nf.ball_end_coefficient_set_names():
        if not is_ball:
            raise ValueError(f"coefficients = {c!r}: a ball-end set, but tool.kind is not ball")
        return nf.ball_end_coefficient_set(c).coefficients
    if is_ball:
        raise ValueError(f"coefficients = {c!r}: a flat-end set, but tool.kind = ball")
    return nf.linear_edge_coefficient_set(c).coefficients


#: Blocks per call of the force simulation: the stage reports progress between calls. The Z-map is
#: carried from call to call; each call starts its sampling at its first block.
FORCE_CHUNK_BLOCKS = 250


def stage_forces(job: Job, stock0, prog: Program, progress=None):
    """Per-revolution forces on the cutter along the program, cut through a copy of the stock
    (netshape.force.simulate_program, with the tool's runout and the coefficients' chip-size effect;
    :data:`FORCE_CHUNK_BLOCKS` blocks per call; ``progress(k)`` is called with the blocks done after
    each call). Returns a ProgramForceResult."""
    from netshape.force import ProgramForceResult, simulate_program

    cutter = make_cutter(job.tool)
    c = job.cutting
    coeffs = coefficients_for(job, cutter)  # a flat cutter's chip: its runout and the size effect
    tp = stock_frame_toolpath(prog)
    blocks = list(tp.blocks)
    z = stock0.copy()
    parts = []
    for i0 in range(0, len(blocks), FORCE_CHUNK_BLOCKS):
        chunk = _sub_toolpath(tp, blocks[i0:i0 + FORCE_CHUNK_BLOCKS])
        r = simulate_program(z, cutter, chunk, coeffs, step=c["step_mm"],
                             samples_per_revolution=c["samples_per_revolution"], disk_height=c["disk_height_mm"],
                             feed_per_tooth=c["feed_per_tooth_mm"] or 0.0, spindle_rpm=c["spindle_rpm"] or 0.0,
                             copy_stock=False)
        r.block = np.asarray(r.block) + i0
        parts.append(r)
        if progress is not None:
            progress(min(len(blocks), i0 + FORCE_CHUNK_BLOCKS))
    if len(parts) == 1:
        return parts[0]
    fields = ("positions", "block", "feed_direction", "mean", "peak", "peak_resultant", "mean_resultant",
              "engaged_fraction")
    merged = {f: np.concatenate([np.asarray(getattr(p, f)) for p in parts]) for f in fields}
    return ProgramForceResult(**merged, removed_volume=float(sum(p.removed_volume for p in parts)))


# ---------------------------------------------------------------------------------------------- motion


def stage_feed_plan(job: Job, tp):
    """Look-ahead feed plan and interpolation of ``tp`` under the job's limits. Returns a
    netshape.motion.Trajectory (``stats['cycle_time_s']``)."""
    from netshape import motion as nmo

    lim = job.limits
    jerk = lim.get("jmax_mm_s3", [math.inf] * 3)
    limits = nmo.AxisLimits(lim["vmax_mm_s"], lim["amax_mm_s2"], jerk)
    from netshape._budget import MAX_PLAN_SAMPLES

    # the options as keywords: "smooth" (smoothing, then blend) is a rule of plan, not of the planner
    try:
        return nmo.plan(tp, limits, with_deviation=False, max_samples=MAX_PLAN_SAMPLES, rule=lim["rule"],
                        ts1=lim["ts1_s"], ts2=lim["ts2_s"], lookahead=lim["lookahead"],
                        tolerance=lim["tolerance_mm"])
    except ValueError as exc:  # the planner's own bound, reached where the estimate before the run was low
        if str(exc).startswith("max_samples = "):
            raise ValueError(f"{job.source}: limits: the feed plan needs more than {MAX_PLAN_SAMPLES} fine samples "
                             f"(limits.ts2_s = {lim['ts2_s']!r}, jmax_mm_s3 = {lim.get('jmax_mm_s3')!r}); "
                             "use a larger ts2_s or limits the program can run under") from None
        raise


# ---------------------------------------------------------------------------------------------- errors


def error_stats(before, after) -> dict:
    """max and RMS [mm] of |error| before and after (None where there is no value)."""

    def mx(v):
        return None if v is None or len(v) == 0 else float(np.max(np.abs(v)))

    def rms(v):
        return None if v is None or len(v) == 0 else float(np.sqrt(np.mean(np.square(v))))

    return {"max_before_mm": mx(before), "max_after_mm": mx(after),
            "rms_before_mm": rms(before), "rms_after_mm": rms(after)}


def total_error(defl: DeflectionResult | None, vol: VolumetricResult | None, which: str, machine=None,
                to_machine=None):
    """Total error [mm] from the sources predicted, at the points where they act on the part.

    On the final walls (the deflection samples) the errors add along the wall normal n: before
    compensation the wall error minus the machine's tip error along n (``machine`` and ``to_machine``,
    stock-frame points → machine frame, give it; a tip moved towards the wall cuts more), after it the
    wall error plus the volumetric residual distance in the adverse direction (that residual has no
    direction), interpolated by path distance. Elsewhere on the path the volumetric error alone. One
    source alone is the total."""
    d_s = d_v = None
    if defl is not None and defl.available:
        if which == "before":
            d_s, d_v = defl.s_mm, defl.before_mm
        else:
            d_s = defl.s_after_mm if defl.s_after_mm is not None else defl.s_mm
            d_v = defl.after_mm
    v_s = v_v = None
    if vol is not None:
        v_s, v_v = (vol.s_before_mm, vol.before_mm) if which == "before" else (vol.s_after_mm, vol.after_mm)
    if d_v is None and v_v is None:
        return None
    if v_v is None or len(v_v) == 0:
        return d_v
    if d_v is None or len(d_v) == 0:
        return v_v
    if which == "before" and machine is not None and to_machine is not None and len(defl.points_mm) == len(d_v):
        from netshape import machine as nm

        e = np.asarray(nm.tip_error(machine, to_machine(defl.points_mm)), dtype=float)
        on_wall = d_v - np.einsum("ij,ij->i", e[:, :2], defl.normals)
    else:
        v_on_d = np.interp(d_s, v_s, v_v)
        on_wall = d_v + np.where(d_v >= 0, 1.0, -1.0) * v_on_d
    # volumetric samples off the final walls keep their own error
    inside = np.zeros(len(v_s), dtype=bool)
    for s0, s1 in defl.ranges:
        inside |= (v_s >= s0) & (v_s <= s1)
    return np.concatenate([on_wall, v_v[~inside]])
