"""netshape.motion — look-ahead feedrate planning and 2-step interpolation (Lee & Lee; docs/motion.md).

Batch use::

    import netshape.motion as nm
    traj = nm.plan(blocks_or_points, nm.AxisLimits.uniform(250, 3000), rule="blend", tolerance=0.01)
    traj.t, traj.position, traj.velocity, traj.feed, traj.stats

Streaming use (controllers) is the C++ ``netshape::motion::Planner``; it is bound as
:class:`Planner` for experiments. Units: mm, s; feeds mm/s.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._core import motion as _m
from .._core import toolpath as _tp

AxisLimits = _m.AxisLimits
PlanOptions = _m.PlanOptions
CornerRule = _m.CornerRule
JunctionAccel = _m.JunctionAccel
Planner = _m.Planner
Sample = _m.Sample
Status = _m.Status
rule_name = _m.rule_name
parse_rule = _m.parse_rule
junction_accel_name = _m.junction_accel_name
parse_junction_accel = _m.parse_junction_accel
turn_angle = _m.turn_angle
paper_corner_speed = _m.paper_corner_speed
vector_corner_speed = _m.vector_corner_speed
per_axis_corner_speed = _m.per_axis_corner_speed
junction_deviation_speed = _m.junction_deviation_speed
klipper_junction_deviation = _m.klipper_junction_deviation
junction_acceleration = _m.junction_acceleration
junction_deviation_corner_speed = _m.junction_deviation_corner_speed
reach_speed = _m.reach_speed

RULES = ("paper", "vector", "per-axis", "junction-deviation", "blend")
#: rules of :func:`plan`: the planner's corner rules plus "smooth" (tolerance-band smoothing, then blend)
PLAN_RULES = RULES + ("smooth",)
JUNCTION_ACCELS = ("min-moving-axis", "along-change")

__all__ = [
    "AxisLimits", "PlanOptions", "CornerRule", "JunctionAccel", "Planner", "Sample", "Status", "Trajectory",
    "plan", "smooth_path", "smooth_path_streamed", "PLAN_RULES",
    "make_options", "path_points", "blocks_to_arrays", "polyline_arrays", "rule_name", "parse_rule", "turn_angle",
    "paper_corner_speed", "vector_corner_speed", "per_axis_corner_speed", "junction_deviation_speed",
    "klipper_junction_deviation", "junction_acceleration", "junction_deviation_corner_speed",
    "junction_accel_name", "parse_junction_accel", "reach_speed", "RULES", "JUNCTION_ACCELS",
]


@dataclass
class Trajectory:
    """Fine samples of a planned program.

    t : (n,) float64 [s]; position, velocity : (n, 3) float64 [mm], [mm/s]; feed : (n,) path speed
    [mm/s]; block : (n,) int index of the program block; stats : dict of figures (cycle_time_s,
    max_axis_velocity_mm_s, max_axis_accel_mm_s2, max_axis_jerk_mm_s3, max_path_deviation_mm, ...).
    """

    t: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    feed: np.ndarray
    block: np.ndarray
    stats: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        return dict(self.stats)


def make_options(rule: str | CornerRule = "vector", *, ts1: float = 1e-3, ts2: float = 1e-4,
                 lookahead: int = 64, tolerance: float = 0.01, corner_tolerance: float = 0.0,
                 allowable_speed_difference: float = 100.0 / 60.0,
                 junction_deviation: float = 0.0, square_corner_velocity: float = 5.0,
                 junction_accel: str | JunctionAccel = "min-moving-axis",
                 centripetal_fraction: float = 0.8) -> PlanOptions:
    """PlanOptions from keywords (periods [s], tolerance [mm], speeds [mm/s]); validated.

    junction-deviation rule: `junction_deviation` δ [mm] (grbl's $11) is used when
    `square_corner_velocity` is 0, else δ comes from Klipper's square corner velocity [mm/s];
    `junction_accel` is "min-moving-axis" (smallest limit of the moving axes) or "along-change"
    (grbl: the axis-limited acceleration along the velocity change). Blend rule: `corner_tolerance`
    [mm] > 0 is the tolerance at vertices where neither block is a cubic block (else `tolerance`).
    """
    o = PlanOptions()
    o.rule = rule if isinstance(rule, CornerRule) else parse_rule(str(rule))
    o.ts1, o.ts2, o.lookahead = float(ts1), float(ts2), int(lookahead)
    o.tolerance = float(tolerance)
    o.corner_tolerance = float(corner_tolerance)
    o.allowable_speed_difference = float(allowable_speed_difference)
    o.junction_deviation = float(junction_deviation)
    o.square_corner_velocity = float(square_corner_velocity)
    o.junction_accel = (junction_accel if isinstance(junction_accel, JunctionAccel)
                        else parse_junction_accel(str(junction_accel)))
    o.centripetal_fraction = float(centripetal_fraction)
    o.validate()
    return o


def polyline_arrays(points, feed) -> dict:
    """Block arrays for a polyline through (n, 3) points [mm] at feed [mm/s] (scalar or (n-1,))."""
    p = np.ascontiguousarray(points, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 3 or len(p) < 2:
        raise ValueError(f"points.shape = {p.shape}: must be (n, 3) with n >= 2")
    m = len(p) - 1
    f = np.broadcast_to(np.asarray(feed, dtype=np.float64), (m,)).copy()
    return dict(kind=np.ones(m, np.int32), start=p[:-1].copy(), end=p[1:].copy(), center=np.zeros((m, 3)),
                clockwise=np.zeros(m, np.int32), plane=np.zeros(m, np.int32), turns=np.ones(m, np.int32), feed=f)


def _enum_int(v) -> int:
    return int(getattr(v, "value", v))


def blocks_to_arrays(blocks) -> dict:
    """Block arrays from a toolpath (anything with `.blocks`) or a sequence of blocks with the
    attributes of netshape.toolpath.Block (kind, start, end, center, clockwise, plane, turns, feed)."""
    blocks = list(getattr(blocks, "blocks", blocks))
    n = len(blocks)
    if n == 0:
        raise ValueError("blocks = []: the program has no motion blocks")
    if all(type(b) is _tp.Block for b in blocks):  # the toolpath's own blocks: columns built in C++
        cols = _tp.BlockArrays.from_blocks(blocks).to_dict()
        return dict(kind=cols["kind"].astype(np.int32), start=cols["start"].copy(), end=cols["end"].copy(),
                    center=cols["center"].copy(), clockwise=cols["clockwise"].astype(np.int32),
                    plane=cols["plane"].astype(np.int32), turns=cols["turns"].astype(np.int32),
                    feed=cols["feed"].copy())
    out = dict(kind=np.empty(n, np.int32), start=np.empty((n, 3)), end=np.empty((n, 3)), center=np.empty((n, 3)),
               clockwise=np.empty(n, np.int32), plane=np.empty(n, np.int32), turns=np.empty(n, np.int32),
               feed=np.empty(n))
    for i, b in enumerate(blocks):
        out["kind"][i] = _enum_int(b.kind)
        out["start"][i] = b.start
        out["end"][i] = b.end
        out["center"][i] = getattr(b, "center", (0.0, 0.0, 0.0))
        out["clockwise"][i] = int(bool(getattr(b, "clockwise", False)))
        out["plane"][i] = _enum_int(getattr(b, "plane", 0))
        out["turns"][i] = int(getattr(b, "turns", 1))
        out["feed"][i] = float(b.feed)
    return out


def _program_object(program) -> bool:
    """A Toolpath or toolpath BlockArrays: the bindings take it as it is (no columns through Python)."""
    return isinstance(program, (_tp.Toolpath, _tp.BlockArrays))


def _block_arrays(program):
    """A Toolpath's BlockArrays (its columns built in C++); BlockArrays as they are."""
    return _tp.BlockArrays.from_blocks(program.blocks) if isinstance(program, _tp.Toolpath) else program


def _arrays(program, feed):
    if isinstance(program, _tp.BlockArrays):
        return program.to_dict()
    if isinstance(program, dict):
        return program
    if isinstance(program, np.ndarray) or (isinstance(program, (list, tuple)) and program
                                           and not hasattr(program[0], "kind")):
        if feed is None:
            raise ValueError("feed = None: a polyline needs a feed [mm/s]")
        return polyline_arrays(program, feed)
    return blocks_to_arrays(program)


def _program_args(arr):
    """The eight block arrays as the bindings that read a program take them (kinds 0, 1, 2)."""
    return (np.ascontiguousarray(arr["kind"], np.int32), np.ascontiguousarray(arr["start"], np.float64),
            np.ascontiguousarray(arr["end"], np.float64), np.ascontiguousarray(arr["center"], np.float64),
            np.ascontiguousarray(arr["clockwise"], np.int32), np.ascontiguousarray(arr["plane"], np.int32),
            np.ascontiguousarray(arr["turns"], np.int32), np.ascontiguousarray(arr["feed"], np.float64))


def _call_args(arr):
    """The block arrays as the planning bindings take them: :func:`_program_args` and ``ctrl``, the
    inner control points P1, P2 of the cubic blocks (kind 3) as (n, 6) (zeros when the key is absent;
    read only on kind 3 rows)."""
    args = _program_args(arr)
    n = len(args[0])
    ctrl = arr.get("ctrl") if isinstance(arr, dict) else None
    if ctrl is None:
        c = np.zeros((n, 6))
    else:
        c = np.asarray(ctrl, dtype=np.float64)
        if c.shape != (n, 2, 3):
            raise ValueError(f"ctrl.shape = {c.shape}: must be ({n}, 2, 3), P1 and P2 of each block [mm]")
        c = np.ascontiguousarray(c.reshape(n, 6))
    return (*args, c)


def path_points(program, limits: AxisLimits, options: PlanOptions, ds: float, *, feed=None):
    """The path the planner runs (blend rule: with its corner blends), sampled every `ds` [mm] of arc
    length: (m, 3) points [mm], (m,) arc lengths [mm], and the planned cycle time [s]."""
    pts, s, t = _m._path_points(*_call_args(_arrays(program, feed)), limits, options, float(ds))
    return np.asarray(pts), np.asarray(s), float(t)


def _dwells(program, n: int):
    """Dwell time [s] before each block and after the last, (n + 1,), or None when the program does
    not say (polylines, plain block lists). From the ``dwell`` array of
    netshape.toolpath.read_gcode_arrays or of BlockArrays, or the G4 commands of a Toolpath."""
    if isinstance(program, _tp.BlockArrays):
        program = program.to_dict()
    if isinstance(program, dict):
        if program.get("dwell") is None:
            return None
        d = np.zeros(n + 1)
        for key, at in (("dwell", slice(0, n)), ("dwell_after", slice(1, n + 1))):
            if program.get(key) is None:
                continue
            v = np.asarray(program[key], dtype=np.float64)
            if v.shape != (n,) or not np.all(np.isfinite(v)) or np.any(v < 0):
                raise ValueError(f"{key}: shape {v.shape}, must be ({n},) non-negative times [s]")
            d[at] += v
        return d
    commands = getattr(program, "commands", None)
    if commands is None:
        return None
    d = np.zeros(n + 1)
    for c in commands:
        if int(getattr(c.kind, "value", c.kind)) == 2:  # netshape.toolpath.CommandKind.dwell
            d[min(int(c.before), n)] += float(c.value)
    return d


def smooth_path(program, tolerance: float = 0.01, *, feed=None, fit_share: float = 0.98,
                max_segment: float = 4.0, max_turn: float = 0.5236, min_blocks: int = 3, window: int = 4096,
                smoothing_length: float = 1.5, lead_length: float = 2.0, max_fit_turn: float = 1.6057,
                space_flatness: float = 0.5):
    """Tolerance-band smoothing of micro-segment runs (C++ ``netshape::motion::smooth``).

    Runs of line blocks each at most `max_segment` [mm] long, turning at most `max_turn` [rad] at every
    vertex, with one feed, are replaced by curvature-continuous cubic pieces (block kind 3) that
    follow a smoothing spline (penalty ``smoothing_length⁴·∫|s''|²``, `smoothing_length` [mm]) pulled back
    into the tube, and stay within ``fit_share·tolerance`` [mm] of the polyline both ways (checked). A
    run in one coordinate plane is fitted as one curve; a run in space (3-D moves) in pieces each within
    ``space_flatness·fit_share·tolerance`` of a plane of its own, joined with one tangent
    (`space_flatness` in [0, 1); 0 leaves runs in space as programmed). A
    run borrows up to `lead_length` [mm] of an adjoining long line so that it joins it tangentially.
    Vertices turning more are corners, kept: the run ends there, and a vertex between two program lines
    becomes an arc within ``fit_share·tolerance`` (a corner made of several vertices around blocks
    shorter than max(0.02 mm, 2·tolerance) gets one arc). A corner turning at most `max_fit_turn` [rad]
    that a curve meets (it is not straight on both sides: a crease of a free-form surface, a curve
    running into a wall) stays inside the run and the curve passes it within the fit tolerance
    (``max_fit_turn=0`` keeps every corner). A straight run next to a corner stays as programmed. Returns ``(arrays, first, last, stats)``: the new blocks as block arrays,
    per new block the first and last program block it replaces, and ``runs_smoothed``, ``runs_kept``,
    ``corners_kept``, ``corners_rounded``, ``max_fit_deviation_mm``.
    """
    args = (float(tolerance), float(fit_share), float(max_segment), float(max_turn), int(min_blocks), int(window),
            float(smoothing_length), float(lead_length), float(max_fit_turn), float(space_flatness))
    if _program_object(program):
        arr, first, last, stats = _m._smooth_program(program, *args)
        return {k: np.asarray(v) for k, v in arr.items()}, np.asarray(first), np.asarray(last), dict(stats)
    return _run_smoother(_m._smooth_arrays, program, feed, *args[:8], max_fit_turn=args[8], space_flatness=args[9])


def smooth_path_streamed(program, tolerance: float = 0.01, *, chunk: int = 1, feed=None, fit_share: float = 0.98,
                         max_segment: float = 4.0, max_turn: float = 0.5236, min_blocks: int = 3,
                         window: int = 4096, smoothing_length: float = 1.5, lead_length: float = 2.0,
                         max_fit_turn: float = 1.6057, min_chunk: int = 64, space_flatness: float = 0.5):
    """:func:`smooth_path` through the streaming C++ ``netshape::motion::Smoother``.

    The program is pushed `chunk` blocks at a time into a smoother that holds at most ``2·window + 2``
    blocks, and its output is drained after every push. The smoother smooths a chunk as soon as a block
    that no smoothing reaches across (a rapid, an arc, a line longer than `max_segment`) arrives with
    at least `min_chunk` blocks before it. Returns what :func:`smooth_path` returns, with ``chunks``
    (smooth() calls), ``forced_cuts`` (cuts inside a stretch of micro-segments longer than the buffer)
    and ``first_output_after_blocks`` (blocks pushed before the first block came out) added to the
    stats; with no forced cut the blocks equal :func:`smooth_path`'s bit for bit.
    """
    return _run_smoother(_m._smooth_stream_arrays, program, feed, tolerance, fit_share, max_segment, max_turn,
                         min_blocks, window, smoothing_length, lead_length, int(chunk),
                         max_fit_turn=float(max_fit_turn), min_chunk=int(min_chunk),
                         space_flatness=float(space_flatness))


def _run_smoother(binding, program, feed, tolerance, fit_share, max_segment, max_turn, min_blocks, window,
                  smoothing_length, lead_length, *extra, **keywords):
    """One smoothing binding on a program: (new block arrays, first, last, stats) as NumPy / dict."""
    arr, first, last, stats = binding(*_program_args(_arrays(program, feed)), float(tolerance), float(fit_share),
                                      float(max_segment), float(max_turn), int(min_blocks), int(window),
                                      float(smoothing_length), float(lead_length), *extra, **keywords)
    return {k: np.asarray(v) for k, v in arr.items()}, np.asarray(first), np.asarray(last), dict(stats)


def _plan_smooth(program, limits, feed, with_deviation, kw, max_samples=0):
    """rule="smooth": smooth_path, then the blend rule with the rest of the tolerance on the new blocks;
    the deviation is measured against the original program."""
    tol = float(kw.pop("tolerance", 0.01))
    if not (tol > 0 and np.isfinite(tol)):
        raise ValueError(f"tolerance = {tol}: must be positive [mm]")
    skw = {k: kw.pop(k) for k in ("fit_share", "max_segment", "max_turn", "min_blocks", "window",
                                  "smoothing_length", "lead_length", "max_fit_turn", "space_flatness") if k in kw}
    arr = _block_arrays(program) if _program_object(program) else _arrays(program, feed)
    n = len(arr) if isinstance(arr, _tp.BlockArrays) else len(arr["kind"])
    dw = _dwells(program, n)
    if dw is not None and np.any(dw[1:-1] > 0):
        raise ValueError("rule = 'smooth': programs with dwells between moves are not supported yet")
    new, first, last, sstats = smooth_path(arr, tol, **skw)
    arr = _arrays(arr, feed)
    fit_share = float(skw.get("fit_share", 0.98))
    # blends next to cubic blocks get the rest of ε; between programmed pieces the whole ε, as `blend`
    options = make_options("blend", tolerance=tol * (1.0 - fit_share), corner_tolerance=tol, **kw)
    t, pos, vel, fd, blk, stats = _m._plan_arrays(*_call_args(new), limits, options, False, int(max_samples))
    stats = dict(stats)
    blk = np.asarray(blk)
    pos = np.asarray(pos)
    src = np.where(blk >= 0, np.asarray(first)[np.clip(blk, 0, None)], -1)
    if with_deviation:
        lo = np.asarray(first)[np.clip(blk, 0, None)]
        hi = np.asarray(last)[np.clip(np.minimum(blk + 1, len(last) - 1), 0, None)]
        stats["max_path_deviation_mm"] = float(_m._deviation_to_program(*_program_args(arr), pos, lo.tolist(),
                                                                           hi.tolist()))
    else:
        stats["max_path_deviation_mm"] = 0.0
    stats.update(sstats)
    stats["blocks"] = int(np.count_nonzero(np.linalg.norm(np.asarray(arr["end"]) - np.asarray(arr["start"]), axis=1)
                                           > 1e-9))
    stats["smoothed_blocks"] = int(len(first))
    stats["dwell_time_s"] = 0.0
    stats["rule"] = "smooth"
    stats["tolerance_mm"] = tol
    stats["ts1_s"], stats["ts2_s"], stats["lookahead"] = options.ts1, options.ts2, options.lookahead
    return Trajectory(np.asarray(t), pos, np.asarray(vel), np.asarray(fd), src, stats)


def plan(program, limits: AxisLimits, options: PlanOptions | None = None, *, feed=None,
         with_deviation: bool = True, max_samples: int = 0, **option_keywords) -> Trajectory:
    """Plan and interpolate a program.

    program : a Toolpath or toolpath.BlockArrays (taken by the core as they are), a sequence of
        blocks, a dict of block arrays, or (n, 3) points of a polyline (then `feed` [mm/s] is required). In block arrays, kind 3 rows are cubic Bézier blocks: start
        = P0, end = P3, and P1, P2 in row k of the optional key ``ctrl`` (n, 2, 3) [mm].
    limits : AxisLimits. options : PlanOptions, or keywords of :func:`make_options`.
    Returns a :class:`Trajectory` whose samples are at options.ts2 and end at the program end point.

    G4 dwells (a Toolpath's dwell commands, or the ``dwell`` / ``dwell_after`` arrays of
    netshape.toolpath.read_gcode_arrays): the tool comes to rest at the end of the block before a
    dwell, waits, and starts from rest; the program is planned as independent pieces between dwells and
    the dwell appears as a gap in ``t`` (same position before and after). ``stats["dwell_time_s"]`` is
    the total dwell and ``stats["cycle_time_s"]`` includes it; maxima are over all pieces.

    ``rule="smooth"`` (with ``tolerance`` ε [mm] and optionally the keywords of :func:`smooth_path`):
    micro-segment runs are first replaced by :func:`smooth_path` within ``fit_share·ε``, then planned
    with the blend rule at ``(1 − fit_share)·ε`` next to the fitted curves and the whole ε between
    programmed pieces (a program nothing is smoothed in is planned as ``rule="blend"`` plans it); ``max_path_deviation_mm`` is measured against the
    original program and ``block`` is the first program block of the smoothed block being run; stats
    add ``runs_smoothed``, ``runs_kept``, ``corners_kept``, ``corners_rounded``, ``max_fit_deviation_mm``,
    ``smoothed_blocks``.

    ``max_samples`` > 0 bounds the fine samples (about 70 B each while planned): the planner stops with a
    ValueError ``max_samples = N: the plan needs more fine samples …`` instead of filling the memory.
    """
    if options is None and str(option_keywords.get("rule", "")) == "smooth":
        option_keywords.pop("rule")
        return _plan_smooth(program, limits, feed, with_deviation, option_keywords, max_samples)
    if options is None:
        options = make_options(**option_keywords)
    elif option_keywords:
        raise ValueError(f"options given twice: {sorted(option_keywords)}")
    if _program_object(program):
        n = len(program) if isinstance(program, _tp.BlockArrays) else len(program.blocks)
    else:
        args = _call_args(_arrays(program, feed))
        n = len(args[0])
    dw = _dwells(program, n)
    cuts = [] if dw is None else [i for i in range(1, n) if dw[i] > 0.0]
    if _program_object(program) and cuts:  # planned in pieces: the program's columns (built in C++)
        args = _call_args(_arrays(_block_arrays(program), feed))
    if not cuts:
        if _program_object(program):
            t, pos, vel, fd, blk, stats = _m._plan_program(program, limits, options, with_deviation,
                                                           int(max_samples))
        else:
            t, pos, vel, fd, blk, stats = _m._plan_arrays(*args, limits, options, with_deviation, int(max_samples))
        stats = dict(stats)
        t = np.asarray(t)
        if dw is not None and dw.sum() > 0.0:  # dwells only before the first or after the last move
            t = t + dw[0]
            stats["cycle_time_s"] += float(dw.sum())
    else:
        t, pos, vel, fd, blk, stats = _plan_pieces(args, dw, [0, *cuts, n], limits, options, with_deviation,
                                                   int(max_samples))
    stats["dwell_time_s"] = 0.0 if dw is None else float(dw.sum())
    stats["rule"] = rule_name(options.rule)
    stats["ts1_s"], stats["ts2_s"], stats["lookahead"] = options.ts1, options.ts2, options.lookahead
    return Trajectory(np.asarray(t), np.asarray(pos), np.asarray(vel), np.asarray(fd), np.asarray(blk), stats)


def _plan_pieces(args, dw, bounds, limits, options, with_deviation, max_samples=0):
    """Plan blocks [bounds[j], bounds[j+1]) independently (each from rest to rest) and join them with
    the dwells between them; ``max_samples`` (> 0) bounds the samples of all pieces together."""
    ts, ps, vs, fs, bs = [], [], [], [], []
    stats: dict = {}
    t0 = float(dw[0])
    for a, b in zip(bounds[:-1], bounds[1:]):
        left = 0 if max_samples <= 0 else max(1, max_samples - sum(len(x) for x in ts))
        try:
            t, pos, vel, fd, blk, st = _m._plan_arrays(*(x[a:b] for x in args), limits, options, with_deviation,
                                                       left)
        except ValueError as exc:  # name the bound the caller gave, not this piece's share
            if str(exc).startswith("max_samples = "):
                raise ValueError(f"max_samples = {max_samples}: " + str(exc).split(": ", 1)[1]) from None
            raise
        st = dict(st)
        ts.append(np.asarray(t) + t0)
        ps.append(np.asarray(pos)), vs.append(np.asarray(vel)), fs.append(np.asarray(fd))
        bs.append(np.asarray(blk) + a)
        t0 += float(st["cycle_time_s"]) + float(dw[b])
        for k, v in st.items():
            if k not in stats:
                stats[k] = v
            elif k in ("blocks", "samples"):
                stats[k] += v
            elif k == "cycle_time_s" or k == "end_error_mm":
                stats[k] = v  # set below / the last piece ends the program
            elif isinstance(v, (list, tuple)):
                stats[k] = [max(x, y) for x, y in zip(stats[k], v)]
            else:
                stats[k] = max(stats[k], v)
    stats["cycle_time_s"] = t0
    return (np.concatenate(ts), np.concatenate(ps), np.concatenate(vs), np.concatenate(fs), np.concatenate(bs),
            stats)
