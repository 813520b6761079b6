"""`netshape feeds`: feed scheduling from the physics (docs/feeds.md)."""

from __future__ import annotations

import argparse
import math

from netshape.cli import _args as a

_DESCRIPTION = """\
Rewrite the feed of every cutting block so the cut is as fast as the stated limits allow: the program is
cut through the stock (Z-map), the engagement is read once at every force sample, and each sample gets the
largest feed that keeps every limit (the force is linear in the feed per tooth for a flat end mill, so the
feed is found in closed form; ball end mills by bisection). Blocks are split where the engagement changes;
each piece takes the smallest feed of its samples; air cuts run at the air feed; each piece is then capped
at what the feed plan (--vmax/--amax or --limits) reaches in it. The written program keeps every other
word in place: only F words and splits are added, with a comment header naming the limits.
Limits: --max-force (resultant on the cutter), --max-chip/--min-chip (largest uncut chip), --max-deflection
(tool tip), --max-wall-error (on walls that remain at the end of the program), --max-power/--max-torque
(spindle, mean over a revolution; flat end mills), --min-feed/--max-feed, --air-feed.
"""

_EPILOG = """\
examples:
  netshape feeds part.ngc --tool tool.toml --stock stock.toml --coefficients leekunhwee_flat_slot \\
      --max-force 400 --max-chip 0.08 --max-feed 3000 --vmax 200 --amax 2000 -o part_feeds.ngc \\
      --json feeds.json --csv feeds.csv --plot feeds.png
stock TOML: min_mm = [x, y, z], max_mm = [...], spacing_mm = 0.25 (the job's [stock] keys, docs/job.md),
in G54 work coordinates: a block under G55…G59 is moved by its offset less G54's (--var).
Summary keys: cycle_time_s {original, optimized}, binding (pieces per limit),
max_force_N {original, optimized}, max_chip_mm, check (the written program re-simulated).
"""

#: option → key of the limits table (netshape.compensation.feeds.LIMIT_KEYS)
_LIMIT_OPTIONS = {
    "max_force": "max_force_N", "max_chip": "max_chip_mm", "min_chip": "min_chip_mm",
    "max_deflection": "max_deflection_mm", "max_wall_error": "max_wall_error_mm", "max_power": "max_power_W",
    "max_torque": "max_torque_Nm", "min_feed": "min_feed_mm_min", "max_feed": "max_feed_mm_min",
    "air_feed": "air_feed_mm_min", "split_tolerance": "split_tolerance", "min_piece": "min_piece_mm",
}


def register(sub) -> None:
    p = sub.add_parser("feeds", help="feed of every block from force, chip, deflection and spindle limits",
                       description=_DESCRIPTION, epilog=_EPILOG,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("program", help="G-code program (RS274/NGC)")
    p.add_argument("--tool", required=True, metavar="TOOL.toml", help="cutter TOML (flat or ball end mill)")
    p.add_argument("--stock", required=True, metavar="STOCK.toml", help="stock TOML (the job's [stock] keys)")
    p.add_argument("--coefficients", required=True, metavar="SPEC",
                   help="a named set (leekunhwee_flat_slot, kim_zas_ball12) or "
                        "Ktc=…,Krc=…,Kac=…,Kte=…,Kre=…,Kae=…")
    p.add_argument("-o", "--output", required=True, metavar="OUT.ngc", help="the scheduled program (atomic)")
    g = p.add_argument_group("limits (each optional but --max-feed)")
    g.add_argument("--max-force", type=a.positive("--max-force", "N"), metavar="N",
                   help="resultant force [N]")
    g.add_argument("--max-chip", type=a.positive("--max-chip", "mm"), metavar="MM",
                   help="largest uncut chip [mm]")
    g.add_argument("--min-chip", type=a.non_negative("--min-chip", "mm"), metavar="MM",
                   help="smallest largest chip, against rubbing [mm]")
    g.add_argument("--max-deflection", type=a.positive("--max-deflection", "mm"), metavar="MM",
                   help="tool tip deflection [mm]")
    g.add_argument("--max-wall-error", type=a.positive("--max-wall-error", "mm"), metavar="MM",
                   help="wall error on the walls that remain [mm]")
    g.add_argument("--max-power", type=a.positive("--max-power", "W"), metavar="W", help="spindle power [W]")
    g.add_argument("--max-torque", type=a.positive("--max-torque", "N*m"), metavar="NM",
                   help="spindle torque [N*m]")
    g.add_argument("--min-feed", type=a.non_negative("--min-feed", "mm/min"), metavar="MM_PER_MIN",
                   help="smallest feed [mm/min] (0)")
    g.add_argument("--max-feed", type=a.positive("--max-feed", "mm/min"), required=True, metavar="MM_PER_MIN",
                   help="largest feed [mm/min]")
    g.add_argument("--air-feed", type=a.positive("--air-feed", "mm/min"), metavar="MM_PER_MIN",
                   help="feed where the tool cuts nothing [mm/min] (--max-feed)")
    g.add_argument("--split-tolerance", type=a.real("--split-tolerance", ge=0, le=10), default=0.1,
                   metavar="R",
                   help="relative change of engaged depth or chip factor that starts a new piece (0.1)")
    g.add_argument("--min-piece", type=a.non_negative("--min-piece", "mm"), default=1.0, metavar="MM",
                   help="shortest piece [mm] (1)")
    m = p.add_argument_group("feed plan (either --limits or --vmax and --amax)")
    m.add_argument("--limits", metavar="MACHINE.toml",
                   help="per-axis limits in a TOML file (as netshape plan)")
    m.add_argument("--vmax", type=a.positive("--vmax", "mm/s"), metavar="MM_PER_S",
                   help="velocity limit [mm/s]")
    m.add_argument("--amax", type=a.positive("--amax", "mm/s^2"), metavar="MM_PER_S2",
                   help="acceleration limit [mm/s^2]")
    m.add_argument("--rule", choices=("paper", "vector", "per-axis", "junction-deviation", "blend"),
                   default="vector",
                   help="corner rule of the feed plan (vector)")
    s = p.add_argument_group("sampling")
    s.add_argument("--step", type=a.positive("--step", "mm"), default=0.5, metavar="MM",
                   help="force sample spacing along a block [mm] (0.5)")
    s.add_argument("--samples", type=a.integer("--samples", ge=8, le=3600), default=72, metavar="N",
                   help="angles per revolution, 8..3600 (72)")
    s.add_argument("--disk-height", type=a.positive("--disk-height", "mm"), default=0.1, metavar="MM",
                   help="disk height of the force model [mm] (0.1)")
    s.add_argument("--rpm", type=a.positive("--rpm", "rev/min"), metavar="RPM",
                   help="spindle speed [rev/min] (default: the program's S words)")
    p.add_argument("--var", metavar="FILE.var",
                   help="LinuxCNC parameter file: the work offsets G54-G59 the program selects; the stock "
                        "is in G54 work coordinates (without it all offsets are zero)")
    p.add_argument("--json", metavar="OUT.json", help="summary")
    p.add_argument("--csv", metavar="OUT.csv", help="per program line: binding limit, feeds, force, chip")
    p.add_argument("--plot", metavar="OUT.png", help="feed and force along the path, before and after")
    p.set_defaults(func=run)


def _inputs(args, cutter):
    """Stock and coefficients from their files, errors naming the option."""
    from types import SimpleNamespace

    from netshape.cli import CliError
    from netshape.job.spec import _coefficients
    from netshape.job.stages import coefficients_for
    from netshape.stock.config import load_stock

    stock = load_stock(args.stock)
    try:
        spec = _coefficients("--coefficients", args.coefficients)
        coeffs = coefficients_for(SimpleNamespace(coefficients=spec), cutter)
    except ValueError as exc:
        raise CliError(f"--coefficients = {args.coefficients}: {str(exc).split(': ', 1)[-1]}") from None
    return stock, coeffs


def _tool(path):
    """(cutter, spindle limits) from one reading of the tool TOML: the cutter's keys and its optional
    ``max_power_W`` / ``max_torque_Nm`` (netshape.cutter.SPINDLE_KEYS)."""
    from netshape._config import load_toml
    from netshape.cli import CliError
    from netshape.cutter import cutter_from_dict, spindle_limits

    try:
        data = load_toml(path)
        return cutter_from_dict(data, source=str(path)), spindle_limits(data)
    except (OSError, ValueError) as exc:
        msg = str(exc)
        raise CliError(msg if msg.startswith(str(path)) else f"--tool = {path}: {msg}") from None


def _work_offsets(args):
    """(9, 3) work offsets G54…G59.3 [mm] from --var, or None."""
    from netshape.cli import CliError
    from netshape.toolpath import read_var_file

    if args.var is None:
        return None
    try:
        return read_var_file(args.var)
    except (OSError, ValueError) as exc:
        raise CliError(f"--var = {args.var}: {exc}") from None


def _axis_limits(args):
    from netshape.cli import CliError
    from netshape.motion import AxisLimits
    from netshape.motion.limits_file import read_limits

    if args.limits:
        if args.vmax is not None or args.amax is not None:
            raise CliError(f"--limits = {args.limits}: give either --limits or --vmax/--amax, not both")
        return read_limits(args.limits)
    for name in ("vmax", "amax"):
        if getattr(args, name) is None:
            raise CliError(f"--{name}: required without --limits (the feed plan's limits)")
    return AxisLimits.uniform(args.vmax, args.amax, math.inf)


def run(args) -> int:
    import json

    from netshape._atomic import all_or_nothing, atomic_save_figure, atomic_write
    from netshape._text import read_text
    from netshape.cli import CliError
    from netshape.cli._args import check_outputs
    from netshape.compensation.feeds import feed_limits_from_dict
    from netshape.compensation.feeds_report import CSV_COLUMNS, plot_feeds
    from netshape.compensation.feeds_run import optimize_program
    from netshape.motion import make_options

    check_outputs(args, files=("--output", "--json", "--csv", "--plot"))
    table = {key: getattr(args, opt) for opt, key in _LIMIT_OPTIONS.items() if getattr(args, opt) is not None}
    cutter, spindle = _tool(args.tool)
    table = spindle | table  # the options win over the tool file's spindle limits
    try:
        limits, split = feed_limits_from_dict(table, source="")
    except ValueError as exc:  # "<key> = v: rule" → the option
        msg = str(exc).lstrip(".")
        key = msg.split(" ", 1)[0]
        opt = next((o for o, k in _LIMIT_OPTIONS.items() if k == key), key)
        raise CliError("--" + opt.replace("_", "-") + msg[len(key):]) from None
    axis = _axis_limits(args)
    work_offsets = _work_offsets(args)
    stock, coeffs = _inputs(args, cutter)
    sampling = {"step": args.step, "samples_per_revolution": args.samples, "disk_height": args.disk_height,
                "spindle_rpm": args.rpm or 0.0}
    text = read_text(args.program)
    res = optimize_program(text, args.program, stock, cutter, coeffs, limits, axis_limits=axis,
                           plan_options=make_options(args.rule, ts1=2e-3, ts2=1e-3), split=split,
                           sampling=sampling, work_offsets=work_offsets)
    if not res.rows:
        raise CliError(f"{args.program}: no feed moves to schedule")
    res.summary["output"] = args.output
    with all_or_nothing():
        with atomic_write(args.output, "w") as fh:
            fh.write(res.text)
        if args.json:
            with atomic_write(args.json, "w") as fh:
                json.dump(res.summary, fh, indent=2)
                fh.write("\n")
        if args.csv:
            with atomic_write(args.csv, "w") as fh:
                fh.write(",".join(CSV_COLUMNS) + "\n")
                for r in res.rows:
                    cells = (f"{r[c]:.6g}" if isinstance(r[c], float) else str(r[c]) for c in CSV_COLUMNS)
                    fh.write(",".join(cells) + "\n")
        if args.plot:
            fig = plot_feeds(res.schedule.samples, res.pieces, res.after.positions, res.after.peak_resultant,
                             res.program, title=f"{args.program}: feeds scheduled")
            atomic_save_figure(fig, args.plot, dpi=110)
    c = res.summary["cycle_time_s"]
    print(f"cycle time {c['original']:.3f} s -> {c['optimized']:.3f} s; {res.summary['pieces']} pieces; "
          f"written {args.output}")
    return 0
