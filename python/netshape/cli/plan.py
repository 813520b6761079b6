"""`netshape plan`: look-ahead feedrate planning and 2-step interpolation of a G-code program."""

from __future__ import annotations

import argparse
import contextlib
import math

from netshape.cli import _args as a

_DESCRIPTION = """\
Plan the feedrate of a G-code program under axis limits with a look-ahead buffer (Lee & Lee, see docs/references.md), then
interpolate it in two loops (rough period --ts1, fine period --ts2). The tool stops for every G4
dwell and waits its duration (counted in cycle_time_s and in dwell_time_s). Writes a JSON summary:
blocks, cycle_time_s, dwell_time_s, max_axis_velocity_mm_s, max_axis_accel_mm_s2, max_axis_jerk_mm_s3 (largest over all
axes and samples, by finite differences of the fine samples) and max_path_deviation_mm.

Corner rules:
  paper               Lee & Lee eq. 4, Acc*Ts1/(1-cos θ) floored by the allowable speed difference
  vector              velocity vector jump |Δv| <= Acc*Ts2 (feasible by construction)
  per-axis            each axis' jump |Δv_i| <= A_i*Ts2 (feasible by construction)
  junction-deviation  grbl/Klipper: v² = a·δ·cos(φ/2)/(1-cos(φ/2)) at a turn φ, δ from
                      --junction-deviation (grbl $11) or Klipper's --scv (default 5 mm/s);
                      a per --junction-accel
  blend               a G2 Bézier blend within --tolerance at each corner (feasible, no jump)
  smooth              runs of micro-segments (lines <= --max-segment mm turning <= --max-turn deg at
                      each vertex) are replaced by a smoothing spline pulled back within 0.98 of
                      --tolerance of the program (checked both ways), planned as its curvature-
                      continuous cubic Bézier pieces;
                      sharper vertices are corners, rounded by an arc where they lie between lines and
                      blended within the rest, except where a curve meets them (<= --max-fit-turn
                      deg, not straight on both sides): the curve passes those; then planned as
                      blend. Adds runs_smoothed, corners_kept, corners_rounded;
                      max_path_deviation_mm is measured against the
                      original program
"""

_EPILOG = """\
examples:
  netshape plan part.ngc --vmax 250 --amax 3000 --rule blend --tolerance 0.01 --json plan.json
  netshape plan part.ngc --limits machine.toml --rule per-axis --json plan.json --plot feed.png
  netshape plan part.ngc --vmax 250 --amax 3000 --rule smooth --tolerance 0.01 --json plan.json \\
      --smoothed-gcode smooth.ngc --smoothed-format g1 --chord-tolerance 0.001
limits TOML: [axes.x] vmax_mm_s = 250  amax_mm_s2 = 3000  jmax_mm_s3 = 1e6 (per axis, optional
jerk), or [limits] vmax_mm_s = ..., amax_mm_s2 = ... for all axes. Units: mm, s.
"""


def register(sub) -> None:
    p = sub.add_parser("plan", help="look-ahead feedrate planning and 2-step interpolation",
                       description=_DESCRIPTION, epilog=_EPILOG,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("program", help="G-code program (RS274/NGC)")
    g = p.add_argument_group("limits (either --limits or --vmax and --amax)")
    g.add_argument("--limits", metavar="MACHINE.toml", help="per-axis limits in a TOML file")
    g.add_argument("--vmax", type=a.positive("--vmax", "mm/s"), metavar="MM_PER_S", help="velocity limit of every axis [mm/s]")
    g.add_argument("--amax", type=a.positive("--amax", "mm/s^2"), metavar="MM_PER_S2", help="acceleration limit of every axis [mm/s^2]")
    g.add_argument("--jmax", type=a.positive("--jmax", "mm/s^3"), metavar="MM_PER_S3",
                   help="jerk limit of every axis [mm/s^3] (S-curve profiles)")
    p.add_argument("--rule", required=True, choices=("paper", "vector", "per-axis", "junction-deviation", "blend", "smooth"))
    p.add_argument("--tolerance", type=a.real("--tolerance", "mm", ge=1e-6), default=0.01, metavar="MM",
                   help="blend / smooth tolerance ε [mm], >= 1e-6 (0.01)")
    p.add_argument("--max-segment", type=a.positive("--max-segment", "mm"), default=4.0, metavar="MM",
                   help="smooth rule: longest line that is a micro-segment [mm] (4)")
    p.add_argument("--max-turn", type=a.real("--max-turn", "deg", gt=0, lt=180), default=30.0, metavar="DEG",
                   help="smooth rule: a vertex turning more is a corner that is kept [deg] in (0, 180) (30)")
    p.add_argument("--max-fit-turn", type=a.real("--max-fit-turn", "deg", ge=0, lt=180), default=92.0, metavar="DEG",
                   help="smooth rule: a corner turning at most this that a curve meets (not straight on "
                        "both sides) is passed by the run's curve within the tolerance; 0 keeps every "
                        "corner [deg] in [0, 180) (92)")
    p.add_argument("--space-flatness", type=a.real("--space-flatness", ge=0, lt=1), default=0.5, metavar="K",
                   help="smooth rule: a run in space (3-D moves) is fitted in pieces each within K·0.98·tolerance "
                        "of a plane of its own; 0 leaves runs in space as programmed, in [0, 1) (0.5)")
    p.add_argument("--smoothed-gcode", metavar="OUT.ngc",
                   help="smooth rule: write the program with its smoothed moves in place atomically (every other "
                        "line and word as written; new moves G1/G2/G3, G5 for cubics in XY, G1 chords within "
                        "--chord-tolerance for other cubics)")
    # the choices are netshape.motion.smooth_gcode.FORMATS, not imported here so that parsing needs no NumPy
    p.add_argument("--smoothed-format", choices=("arcs", "g1", "nurbs"), default=None,
                   help="form of --smoothed-gcode: arcs (G1/G2/G3, the default), g1 (every arc as G1 chords "
                        "within --chord-tolerance) or nurbs (XY arcs as LinuxCNC G5.2/G5.3 NURBS blocks; "
                        "G5.2 moves X and Y only, so arcs in G18/G19 and helical arcs stay G2/G3)")
    p.add_argument("--chord-tolerance", type=a.positive("--chord-tolerance", "mm"), default=None,
                   metavar="MM",
                   help="--smoothed-format g1: largest distance between a chord and its arc [mm] (0.001)")
    p.add_argument("--ts1", type=a.real("--ts1", "s", gt=0, le=1), default=1e-3, metavar="S",
                   help="rough loop period [s], a whole multiple of --ts2 (0.001)")
    p.add_argument("--ts2", type=a.real("--ts2", "s", gt=0, le=1), default=1e-4, metavar="S",
                   help="fine loop period [s] (0.0001)")
    p.add_argument("--lookahead", type=a.integer("--lookahead", "blocks", ge=2, le=1_000_000), default=64,
                   metavar="N", help="look-ahead depth in blocks, 2..1000000 (64)")
    p.add_argument("--max-samples", type=a.integer("--max-samples", "samples", ge=1), default=None, metavar="N",
                   help="refuse a program whose fine samples (cycle time / --ts2, estimated before planning) "
                        "exceed N (50000000, about 10 GB while planned)")
    p.add_argument("--allowable", type=a.non_negative("--allowable", "mm/min"), default=100.0,
                   metavar="MM_PER_MIN",
                   help="paper rule: allowable speed difference [mm/min] (100)")
    p.add_argument("--scv", type=a.positive("--scv", "mm/s"), default=None, metavar="MM_PER_S",
                   help="junction-deviation rule: Klipper square corner velocity [mm/s], "
                        "δ = scv²·(√2-1)/a (5 unless --junction-deviation is given)")
    p.add_argument("--junction-deviation", type=a.positive("--junction-deviation", "mm"), default=None, metavar="MM",
                   help="junction-deviation rule: δ [mm] as grbl's $11 (instead of --scv)")
    p.add_argument("--junction-accel", choices=("min-moving-axis", "along-change"), default="min-moving-axis",
                   help="junction-deviation rule: acceleration at a corner, the smallest limit of the moving "
                        "axes (default) or grbl's axis-limited value along the velocity change")
    p.add_argument("--feed-scale", type=a.positive("--feed-scale"), default=1.0, metavar="K",
                   help="multiply programmed feeds by K")
    p.add_argument("--json", required=True, metavar="OUT.json", help="summary (written atomically)")
    p.add_argument("--samples", metavar="OUT.csv", help="fine samples: t_s,x_mm,...,vx_mm_s,...,feed_mm_s,block")
    p.add_argument("--plot", metavar="OUT.png", help="feed and per-axis velocity plot")
    from netshape.cli._offsets import add_offset_options

    add_offset_options(p)
    p.set_defaults(func=run)


def _check(args) -> None:
    """The options checked against each other (single values were checked while parsing; the library's
    PlanOptions.validate stays the backstop)."""
    from netshape.cli import CliError

    if args.limits:
        for name in ("vmax", "amax", "jmax"):
            if getattr(args, name) is not None:
                raise CliError(f"--{name} = {getattr(args, name):g}: give either --limits or "
                               "--vmax/--amax/--jmax, not both")
    else:
        for name in ("vmax", "amax"):
            if getattr(args, name) is None:
                raise CliError(f"--{name}: required without --limits (give --limits MACHINE.toml or both --vmax "
                               "and --amax)")
    periods = args.ts1 / args.ts2
    if args.ts1 < args.ts2 or abs(periods - round(periods)) > 1e-6 * periods:
        raise CliError(f"--ts1 = {args.ts1:g}: must be a whole multiple of --ts2 = {args.ts2:g} [s]")
    if args.junction_deviation is not None and args.scv is not None:
        raise CliError(f"--scv = {args.scv:g}: give either --junction-deviation or --scv, not both")
    if args.smoothed_gcode and args.rule != "smooth":
        raise CliError(f"--smoothed-gcode = {args.smoothed_gcode}: needs --rule smooth, not --rule {args.rule}")
    if args.smoothed_format is not None and not args.smoothed_gcode:
        raise CliError(f"--smoothed-format = {args.smoothed_format}: needs --smoothed-gcode OUT.ngc")
    if args.chord_tolerance is not None and args.smoothed_format != "g1":
        raise CliError(f"--chord-tolerance = {args.chord_tolerance:g}: only used with --smoothed-format g1")


def _limits(args):
    from netshape.motion import AxisLimits
    from netshape.motion.limits_file import read_limits

    if args.limits:
        return read_limits(args.limits)
    return AxisLimits.uniform(args.vmax, args.amax, math.inf if args.jmax is None else args.jmax)


def _max_samples(args) -> int:
    from netshape._budget import MAX_PLAN_SAMPLES

    return MAX_PLAN_SAMPLES if args.max_samples is None else args.max_samples


@contextlib.contextmanager
def _samples_named():
    """The planner's own bound (reached when the estimate was low, e.g. corners under a tiny jerk
    limit) as the option's error."""
    try:
        yield
    except ValueError as exc:
        msg = str(exc)
        if msg.startswith("max_samples = "):
            raise ValueError("--" + msg.replace("max_samples", "max-samples", 1)) from None
        raise


def _check_work(args, arrays, limits) -> None:
    """Refuse, before planning, a program whose fine samples (at least its cycle time / ts2) exceed
    --max-samples, naming the input that makes the time long (docs/motion.md, Limits)."""
    from netshape._budget import refuse_over
    from netshape.motion.budget import min_motion_time

    limit = _max_samples(args)
    bound = min_motion_time(arrays, limits)
    samples = bound.time_s / args.ts2
    if samples <= limit:
        return
    k = bound.block
    where = ""
    if k >= 0 and bound.block_time_s >= 0.5 * bound.time_s:  # one move takes most of the time
        line = int(arrays["line"][k]) if "line" in arrays else k + 1
        where = f"{args.program}:{line}: a move of {bound.block_mm:g} mm"
    if bound.time_s / 1e-4 <= limit:  # would fit at the default period: the period asks for it
        cause = f"--ts2 = {args.ts2:g} [s]"
    elif bound.limit in ("vmax", "amax", "jmax"):
        unit = {"vmax": "mm/s", "amax": "mm/s^2", "jmax": "mm/s^3"}[bound.limit]
        value = getattr(args, bound.limit)
        cause = (f"--{bound.limit} = {value:g} [{unit}]" if value is not None
                 else f"--limits {args.limits} ({bound.limit})") + (f" ({where})" if where else "")
    elif where:
        feed = float(arrays["feed"][k]) * 60.0 / args.feed_scale
        cause = f"{where} at F{feed:g} mm/min" + (f" × --feed-scale {args.feed_scale:g}" if args.feed_scale != 1 else "")
    else:
        cause = f"{args.program}: {bound.path_mm:g} mm of moves at their feeds"
    refuse_over(cause, samples, limit,
                f"fine samples (at least {bound.time_s:.3g} s of motion, one sample every --ts2 = {args.ts2:g} s)",
                "raise --max-samples or --ts2")


def run(args) -> int:
    import numpy as np

    from netshape import toolpath
    from netshape._atomic import atomic_write
    from netshape.cli import CliError
    from netshape.motion import make_options, plan

    from netshape._atomic import all_or_nothing
    from netshape.cli._args import check_outputs

    _check(args)
    check_outputs(args, files=("--json", "--samples", "--plot", "--smoothed-gcode"))
    limits = _limits(args)
    if args.junction_deviation is not None:
        deviation, scv = args.junction_deviation, 0.0
    else:
        deviation, scv = 0.0, (5.0 if args.scv is None else args.scv)
    rule = "blend" if args.rule == "smooth" else args.rule
    options = make_options(rule, ts1=args.ts1, ts2=args.ts2, lookahead=args.lookahead, tolerance=args.tolerance,
                           allowable_speed_difference=args.allowable / 60.0, junction_deviation=deviation,
                           square_corner_velocity=scv, junction_accel=args.junction_accel)
    from netshape.cli._offsets import offset_kwargs, reader_warnings

    with reader_warnings("plan"):
        arrays = toolpath.read_gcode_arrays(args.program, **offset_kwargs(args))
    arrays = {k: np.asarray(v) for k, v in arrays.items()}
    arrays["feed"] = arrays["feed"] * args.feed_scale
    _check_work(args, arrays, limits)
    fmax = toolpath.max_feed_mm_per_min
    if args.smoothed_gcode and np.max(arrays["feed"], initial=0.0) > fmax / 60.0:  # the writer's bound
        k = int(np.argmax(arrays["feed"]))
        raise CliError(f"--feed-scale = {args.feed_scale:g}: gives F {arrays['feed'][k] * 60.0:.6g} mm/min on "
                       f"{args.program}:{int(arrays['line'][k])}, over the largest feed written, F {fmax:g} mm/min")
    with all_or_nothing():
        if args.rule == "smooth":
            skw = dict(max_segment=args.max_segment, max_turn=math.radians(args.max_turn),
                       max_fit_turn=math.radians(args.max_fit_turn), space_flatness=args.space_flatness)
            with _samples_named():
                traj = plan(arrays, limits, rule="smooth", tolerance=args.tolerance, ts1=args.ts1, ts2=args.ts2,
                            lookahead=args.lookahead, max_samples=_max_samples(args), **skw)
            if args.smoothed_gcode:
                kw = {} if args.chord_tolerance is None else {"chord_tolerance": args.chord_tolerance}
                try:
                    _write_spliced(args, arrays, skw, kw)
                except ValueError as exc:  # the core's chord count names its argument; name the option
                    msg = str(exc)
                    if msg.startswith("chord_tolerance "):
                        raise CliError("--chord-tolerance" + msg[len("chord_tolerance"):]) from None
                    raise
        else:
            with _samples_named():
                traj = plan(arrays, limits, options, max_samples=_max_samples(args))
        out = {
            "program": str(args.program),
            "rule": args.rule,
            "tolerance_mm": args.tolerance if args.rule in ("blend", "smooth") else None,
            "ts1_s": args.ts1,
            "ts2_s": args.ts2,
            "lookahead": args.lookahead,
            "junction_deviation_mm": ((deviation if deviation > 0 else None) if args.rule == "junction-deviation"
                                      else None),
            "scv_mm_s": (scv if scv > 0 else None) if args.rule == "junction-deviation" else None,
            "junction_accel": args.junction_accel if args.rule == "junction-deviation" else None,
            "limits": {
                "vmax_mm_s": list(limits.velocity),
                "amax_mm_s2": list(limits.acceleration),
                "jmax_mm_s3": [x if math.isfinite(x) else None for x in limits.jerk],
            },
        }
        out.update(traj.stats)
        out["note"] = ("max_axis_* are finite differences of the fine samples at ts2; rules that jump velocity at "
                       "a vertex (paper, junction-deviation) show it as large acceleration and jerk")
        from netshape._json import check_finite, write_json

        table = None
        if args.samples:  # checked before the JSON is written: both or neither
            table = np.column_stack([traj.t, traj.position, traj.velocity, traj.feed, traj.block])
            if not np.isfinite(table).all():
                check_finite({"samples": table.tolist()}, cause=args.program)
        write_json(args.json, out, cause=args.program)
        if table is not None:
            with atomic_write(args.samples, "w") as fh:
                fh.write("t_s,x_mm,y_mm,z_mm,vx_mm_s,vy_mm_s,vz_mm_s,feed_mm_s,block\n")
                np.savetxt(fh, table, delimiter=",", fmt=["%.6f"] + ["%.6f"] * 7 + ["%d"])
        if args.plot:
            from netshape._atomic import atomic_save_figure
            from netshape.motion.plots import plot_profiles

            fig = plot_profiles(traj, title=f"{args.program} — rule {args.rule}")
            atomic_save_figure(fig, args.plot)
    dwell = traj.stats.get("dwell_time_s", 0.0)
    print(f"{traj.stats['blocks']} blocks, cycle time {traj.stats['cycle_time_s']:.4f} s"
          + (f" (dwells {dwell:.4f} s)" if dwell else "") + ", "
          f"max axis velocity {traj.stats['max_axis_velocity_mm_s']:.2f} mm/s, "
          f"accel {traj.stats['max_axis_accel_mm_s2']:.1f} mm/s^2, "
          f"path deviation {traj.stats['max_path_deviation_mm']:.4f} mm")
    return 0


def _write_spliced(args, arrays, skw, kw) -> None:
    """--smoothed-gcode: the program's text with the smoothed moves in place (netshape.motion.gcode_splice)."""
    import warnings
    from pathlib import Path

    import numpy as np

    from netshape import toolpath
    from netshape._atomic import atomic_write
    from netshape.motion import smooth_path
    from netshape.motion.gcode_splice import frame_shift, spliced_gcode_lines

    new, first, _, _ = smooth_path(arrays, args.tolerance, **skw)
    if args.var or args.tool_table:  # the program's own frame: the same program read without them
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", toolpath.GcodeWarning)
            own = toolpath.read_gcode_arrays(args.program)
        shift = frame_shift(arrays, own)
    else:
        shift = np.zeros((len(arrays["kind"]), 3))
    text = Path(args.program).read_text(encoding="utf-8", errors="replace")
    lines = spliced_gcode_lines(text, arrays, shift, new, first, args.smoothed_format or "arcs",
                                feed_scale=args.feed_scale, **kw)
    with atomic_write(args.smoothed_gcode, "w") as fh:
        fh.write("\n".join(lines) + "\n")
