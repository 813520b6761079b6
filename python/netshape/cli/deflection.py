"""`netshape deflection`: tool deflection wall error of a steady cut (wall), along a program over a
stock (predict), and the compensated program (compensate)."""

from __future__ import annotations

import argparse
import math
import time

from netshape.cli import _args as a

_DESCRIPTION = """\
Tool deflection and the wall error it leaves (Cho & Suh 1993). The tool is a cantilever of length
stick-out; the wall at height z is cut when a flute's element at z passes the wall angle; the error
is the deflection there along the wall normal, + when material is left, - when overcut.
  wall        one steady straight cut (up: left wall, down: right wall, slot: both)
  predict     the wall error along a program's 2-D contour over a stock (Z-map swept move by move)
  compensate  rewrite the contour so the predicted wall error is within --tolerance
"""

_EPILOG = """\
examples:
  netshape deflection wall --diameter 25 --flutes 4 --helix 60 --stick-out 250 --youngs-modulus 210000 \\
      --rpm 600 --feed-per-tooth 0.0127 --ap 2.5 --ae 2 --mode down --coefficients cho_suh_example --json w.json
  netshape deflection predict part.nc --tool tool.toml --stock stock.toml --coefficients KT=1000,KR=0.4 \\
      --rpm 600 --json pred.json --plot plots/
  netshape deflection compensate part.nc --tool tool.toml --stock stock.toml --coefficients cho_suh_example \\
      --rpm 600 --scheme accelerated --level middle -o part_comp.nc
--coefficients: a named set (cho_suh_example, leekunhwee_flat_slot), Ktc=...,Krc=...,Kac=...,Kte=...,
Kre=...,Kae=... (linear edge, N/mm^2 and N/mm) or KT=...,KR=... (Kline-DeVor).
"""


def register(sub) -> None:
    p = sub.add_parser("deflection", help="tool deflection wall error and its path compensation",
                       description=_DESCRIPTION, epilog=_EPILOG,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    dsub = p.add_subparsers(dest="action", metavar="ACTION")
    dsub.required = True

    w = dsub.add_parser("wall", help="wall error of one steady straight cut",
                        formatter_class=argparse.RawDescriptionHelpFormatter, epilog=_EPILOG)
    w.add_argument("--tool", metavar="TOOL.toml", help="cutter TOML (diameter, flutes, helix, stick-out, E)")
    w.add_argument("--diameter", type=a.positive("--diameter", "mm"), metavar="MM", help="tool diameter [mm]")
    w.add_argument("--flutes", type=a.flutes(), metavar="N", help="number of flutes, 1..64")
    w.add_argument("--helix", type=a.real("--helix", "deg", ge=0, lt=85), metavar="DEG",
                   help="helix angle [deg] in [0, 85)")
    w.add_argument("--stick-out", type=a.positive("--stick-out", "mm"), metavar="MM", help="holder face to tip [mm]")
    w.add_argument("--youngs-modulus", type=a.positive("--youngs-modulus", "MPa"), metavar="MPA",
                   help="E of the tool [MPa]")
    _common(w)
    w.add_argument("--feed-per-tooth", type=a.positive("--feed-per-tooth", "mm"), required=True, metavar="MM",
                   help="feed per tooth c [mm]")
    w.add_argument("--ap", type=a.positive("--ap", "mm"), required=True, metavar="MM",
                   help="axial depth of cut [mm]")
    w.add_argument("--ae", type=a.positive("--ae", "mm"), metavar="MM", help="radial depth of cut [mm] (up/down)")
    w.add_argument("--mode", choices=("up", "down", "slot"), default="down", help="milling mode (default down)")
    w.add_argument("--levels", type=a.integer("--levels", ge=3, le=10001), default=21, metavar="N",
                   help="profile levels, bottom to top, 3..10001 (default 21)")
    w.add_argument("--json", metavar="OUT.json", help="write the result as JSON")
    w.set_defaults(func=run_wall)

    for name, helptext in (("predict", "wall error along a program over a stock"),
                           ("compensate", "write the deflection-compensated program")):
        q = dsub.add_parser(name, help=helptext, formatter_class=argparse.RawDescriptionHelpFormatter,
                            epilog=_EPILOG)
        q.add_argument("program", metavar="PROGRAM", help="G-code program with one 2-D contour")
        q.add_argument("--tool", required=True, metavar="TOOL.toml", help="cutter TOML (flat end mill)")
        q.add_argument("--stock", required=True, metavar="STOCK.toml",
                       help="min_mm, max_mm, spacing_mm, optional [[pre_cut]] program/tool")
        _common(q)
        q.add_argument("--spacing", type=a.positive("--spacing", "mm"), default=0.5, metavar="MM",
                       help="path point spacing [mm] (default 0.5)")
        q.add_argument("--max-points", type=a.integer("--max-points", "points", ge=1), default=None, metavar="N",
                       help="refuse a program whose path points (its feed length / --spacing, counted before "
                            "the work) exceed N (2000000)")
        q.add_argument("--side", choices=("auto", "left", "right"), default="auto",
                       help="wall side: left of the feed (up milling) or right (down milling); default auto")
        if name == "predict":
            q.add_argument("--drawing", metavar="NOMINAL.ngc",
                           help="measure the wall against this program's contour (the drawing) instead of "
                                "PROGRAM's own: checks a compensated program")
            q.add_argument("--json", metavar="OUT.json", help="write max_wall_error_mm and the per-point table")
            q.add_argument("--plot", metavar="DIR", help="write PNG plots into DIR")
            q.set_defaults(func=run_predict)
        else:
            q.add_argument("--scheme", choices=("one-d", "integrated", "sectional", "accelerated"),
                           default="accelerated", help="compensation scheme (default accelerated)")
            q.add_argument("--level", choices=("bottom", "middle", "top"), default="middle",
                           help="reference level of the wall (default middle)")
            q.add_argument("--tolerance", type=a.positive("--tolerance", "mm"), default=5e-4, metavar="MM",
                           help="largest wall error accepted at the level [mm] (default 0.0005)")
            q.add_argument("--discount", type=a.real("--discount", gt=0, le=1), default=1.0, metavar="LAMBDA",
                           help="discount factor lambda in (0, 1] of the update (default 1)")
            q.add_argument("--max-iterations", type=a.integer("--max-iterations", ge=1, le=100000), default=50,
                           metavar="N", help="iteration limit, 1..100000 (default 50)")
            q.add_argument("--density", type=a.integer("--density", ge=1, le=16), default=4, metavar="K",
                           help="check the written program at K times the sample density, 1..16 (default 4)")
            q.add_argument("-o", "--output", required=True, metavar="OUT.nc", help="compensated program")
            q.add_argument("--json", metavar="OUT.json", help="also write the summary as JSON")
            q.set_defaults(func=run_compensate)


def _common(p) -> None:
    p.add_argument("--inertia", choices=("square", "equivalent"), default="square",
                   help="I from the inscribed square D^4/48 or an equivalent diameter 0.8 D (default square)")
    p.add_argument("--load", choices=("resultant", "distributed"), default="distributed",
                   help="resultant at L - A/2 (eq. 7) or distributed element loads (default)")
    p.add_argument("--rpm", type=a.positive("--rpm", "rev/min"), required=True, metavar="RPM",
                   help="spindle speed [rev/min]")
    p.add_argument("--coefficients", type=a.parsed("--coefficients", _coefficients), required=True,
                   metavar="NAME|K=V,...",
                   help="named set, Ktc=...,Krc=...,Kac=...,Kte=...,Kre=...,Kae=... or KT=...,KR=...")


def _coefficients(text: str):
    from netshape.deflection import parse_coefficients

    return parse_coefficients(text)


def _write_json(path, data, cause: str | None = None) -> None:
    from netshape._json import write_json

    write_json(path, data, indent=1, cause=cause)


def run_wall(args) -> int:
    from netshape import deflection as d
    from netshape.cli import CliError

    a.check_outputs(args, files=("--json",))

    # options checked against each other (single values were checked while parsing, a --tool file's
    # values by load_cutter)
    if args.tool:
        from netshape.cutter import load_cutter

        c = load_cutter(args.tool)
        diameter, flutes, helix = 2 * c.radius, c.flutes, math.degrees(c.helix)
        stick, e, holder = c.stick_out, c.youngs_modulus, c.holder_compliance
        for name in ("diameter", "flutes", "helix", "stick_out", "youngs_modulus"):
            if getattr(args, name) is not None:
                raise CliError(f"--{name.replace('_', '-')} = {getattr(args, name):g}: give either --tool "
                               "or the tool options, not both")
    else:
        missing = [o for o, v in (("--diameter", args.diameter), ("--flutes", args.flutes), ("--helix", args.helix),
                                  ("--stick-out", args.stick_out), ("--youngs-modulus", args.youngs_modulus))
                   if v is None]
        if missing:
            raise CliError(f"{missing[0]}: required without --tool")
        diameter, flutes, helix, stick, e = args.diameter, args.flutes, args.helix, args.stick_out, args.youngs_modulus
        holder = 0.0
    if stick < args.ap:
        raise CliError(f"--stick-out = {stick:g}: shorter than the axial depth --ap = {args.ap:g} [mm]")
    if args.mode != "slot" and args.ae is None:
        raise CliError(f"--mode = {args.mode}: needs --ae, the radial depth of cut [mm]")
    if args.ae is not None and args.ae > diameter:
        raise CliError(f"--ae = {args.ae:g}: must not exceed the diameter ({diameter:g}) [mm]")
    model = d.make_model(diameter=diameter, flutes=flutes, helix_deg=helix, stick_out=stick, youngs_modulus=e,
                         feed_per_tooth=args.feed_per_tooth, ap=args.ap, ae=args.ae, mode=args.mode,
                         coefficients=args.coefficients, inertia=args.inertia, load=args.load,
                         holder_compliance=holder)
    res = d.steady_wall(model, args.mode, levels=args.levels)
    res.update({"mode": args.mode, "load": args.load, "inertia": args.inertia, "rpm": args.rpm})
    # a cantilever's deflection grows with stick-out³ / (E · D⁴): the tool's numbers are the cause
    tool = (f"--tool {args.tool} (stick_out_mm = {stick:g}, diameter_mm = {diameter:g}, youngs_modulus_MPa = {e:g})"
            if args.tool else f"--stick-out = {stick:g} (with --diameter = {diameter:g}, --youngs-modulus = {e:g})")
    from netshape._json import check_finite

    check_finite(res, cause=tool)
    w = res["wall_error_mm"]
    print(f"wall error ({res['side']} wall, {args.load}): bottom {w['bottom'] * 1e3:.2f} um, "
          f"middle {w['middle'] * 1e3:.2f} um, top {w['top'] * 1e3:.2f} um; max force {res['max_force_N']:.1f} N")
    if args.json:
        _write_json(args.json, res, cause=tool)
    return 0


def _setup(args):
    from netshape import deflection as d
    from netshape.cutter import load_cutter
    from netshape.toolpath import read_gcode

    from netshape._text import read_toml

    _check_points(args)
    cutter = load_cutter(args.tool)
    read_toml(args.stock)  # not UTF-8 or nested too deep: refused here naming the file and line
    stock = d.load_stock(args.stock)
    program = read_gcode(args.program)
    return d.setup_path(program, cutter, stock, coefficients=args.coefficients, rpm=args.rpm, spacing=args.spacing,
                        inertia=args.inertia, load=args.load, side=args.side)


def _final_wall(setup, r):
    """Per point: the block's wall is part of the finished part (netshape.deflection.walls)."""
    import numpy as np

    from netshape.deflection import walls, wall_normals

    normals = np.asarray(wall_normals(setup.nominal, setup.side))
    remains = walls.wall_remains_points(setup.program, setup.owner, setup.nominal, normals, np.asarray(r.depth),
                                        setup.cutter.radius)
    return walls.final_wall_points(setup.owner, remains, walls.generates_wall(r, setup.side))


def _pieces(setup, final):
    from netshape.deflection import walls

    blocks = list(setup.program.blocks)
    return [{k: v for k, v in p.items() if k != "points"}
            for p in walls.contour_pieces(setup.owner, final, lambda b: blocks[b].line)]


def _um(levels: dict) -> str:
    return ", ".join(f"{k} {v * 1e3:.2f} um" for k, v in levels.items())


def _check_points(args) -> None:
    """Refuse, before any work, a --spacing that puts more than --max-points points on the program."""
    import warnings

    import numpy as np

    from netshape import _budget as B
    from netshape import toolpath

    with warnings.catch_warnings():  # the reader's warnings come once, from the real read below
        warnings.simplefilter("ignore")
        a = toolpath.read_gcode_arrays(args.program, arcs="keep")
    feed = np.asarray(a["kind"]) != 0
    length = float(np.sum(toolpath.block_lengths(a)[feed]))
    B.refuse_over(f"--spacing = {args.spacing:g}", length / args.spacing + np.count_nonzero(feed),
                  B.MAX_PATH_POINTS if args.max_points is None else args.max_points,
                  f"path points along {length:g} mm of feed moves", "raise --max-points or --spacing")


def run_predict(args) -> int:
    import numpy as np

    from netshape import deflection as d
    from netshape._atomic import all_or_nothing
    from netshape.cli import CliError
    from netshape.deflection import walls

    a.check_outputs(args, files=("--json",), folders=("--plot",))
    t0 = time.perf_counter()
    setup = _setup(args)
    r = d.predict_path(setup)
    final = own_final = _final_wall(setup, r)
    data = {"side": str(setup.side).split(".")[-1], "feed_per_tooth_mm": setup.model.force.feed_per_tooth}
    if args.drawing:
        from netshape.toolpath import read_gcode

        drawing = d.setup_path(read_gcode(args.drawing), setup.cutter, setup.stock, coefficients=args.coefficients,
                               rpm=args.rpm, spacing=args.spacing, inertia=args.inertia, load=args.load,
                               side=data["side"])
        from netshape.deflection.checked import dense_drawing

        d_pts, d_owner, _ = dense_drawing(drawing, 4)
        dr = d.path_wall_errors(drawing.model, drawing.cutter, drawing.stock, d_pts,
                                d.wall_normals(d_pts, drawing.side), np.zeros(len(d_pts)), drawing.options)
        d_final = _final_wall(replace_nominal(drawing, d_pts, d_owner), dr)
        chk = walls.check_against_drawing(setup.model, setup.cutter, setup.stock, setup.nominal, d_pts, d_final,
                                          setup.side, setup.options)
        if float(np.max(np.abs(chk.offsets))) > setup.cutter.radius:
            raise CliError(f"--drawing = {args.drawing}: {args.program} lies up to "
                           f"{float(np.max(np.abs(chk.offsets))):.3f} mm from its contour, more than the tool "
                           "radius: not the same contour")
        err, final, engaged, prof = chk.error, chk.final, chk.engaged, chk.profile
        data["drawing"] = args.drawing
        data["offset_mm"] = {"min": float(np.min(chk.offsets)), "max": float(np.max(chk.offsets))}
    else:
        err, engaged, prof = np.asarray(r.error), np.asarray(r.engaged, dtype=bool), np.asarray(r.profile)
    dt = time.perf_counter() - t0
    sel = final & engaged
    mx = dict(zip(("bottom", "middle", "top"),
                  map(float, np.abs(err[sel]).max(axis=0) if np.any(sel) else np.zeros(3))))
    pieces = _pieces(setup, own_final)
    print(f"{args.program}: {len(setup.nominal)} points, {int(np.sum(engaged))} cutting, {int(np.sum(sel))} on "
          f"the final wall, {data['side']} wall" + (f", against {args.drawing}" if args.drawing else ""))
    if not np.any(sel):
        print("no point leaves a wall of the finished part (every wall is cut away by a later pass)")
    print(f"largest wall error: {_um(mx)}   ({dt:.2f} s)")
    with all_or_nothing():
        if args.json:
            table = d.path_table(r, setup.nominal)
            for k, name in enumerate(("error_bottom_mm", "error_middle_mm", "error_top_mm")):
                table[name] = err[:, k].tolist()
            table["final_wall"] = final.astype(bool).tolist()
            data.update({"max_wall_error_mm": mx, "contours": pieces, "points": table,
                         "profile": {"levels": int(prof.shape[1]) if prof.ndim == 2 else 0,
                                     "error_mm": np.asarray(prof).tolist()}})
            _write_json(args.json, data)
        if args.plot:
            from netshape.deflection.plots import plot_prediction

            plot_prediction(setup, r, args.plot)
    return 0


def replace_nominal(setup, nominal, owner):
    from dataclasses import replace

    return replace(setup, nominal=nominal, owner=owner)


def run_compensate(args) -> int:
    import numpy as np

    from netshape.cli import CliError
    from netshape._atomic import all_or_nothing
    from netshape.deflection.checked import compensate_checked
    from netshape.toolpath import gcode_encoding, write_gcode

    a.check_outputs(args, files=("--output", "--json"))
    t0 = time.perf_counter()
    setup = _setup(args)
    chk = compensate_checked(setup, scheme=args.scheme, level=args.level, tolerance=args.tolerance,
                             discount=args.discount, max_iterations=args.max_iterations, density=args.density)
    res = chk.result
    dt = time.perf_counter() - t0
    before, after = chk.before_mm, chk.after_mm
    n_final = int(chk.final.sum())
    print(f"scheme {args.scheme}, level {args.level}: {res.iterations} iterations, {res.path_evaluations} path "
          f"evaluations, {chk.rounds} round(s), {dt:.2f} s")
    print(f"written program checked at {args.density}x the sample density ({len(chk.check.s)} samples, "
          f"{n_final} drawing samples on the final wall)")
    print(f"  before: {_um(before)}")
    print(f"  after:  {_um(after)}")
    others = [k for k in ("bottom", "middle", "top") if k != args.level and after[k] > args.tolerance]
    if others:
        print(f"  taper: a 2-D offset moves the whole tool, so the {' and '.join(others)} of the wall keep "
              f"{', '.join(f'{after[k] * 1e3:.2f}' for k in others)} um")
    if chk.worse_points:
        print(f"  warning: {chk.worse_points} samples are worse than the uncompensated program")
    if not res.converged:
        raise CliError(f"{args.output} not written: {res.message}")
    status = "ok" if chk.converged and not chk.worse_points else "tolerance_missed"
    if status != "ok":
        lv = ("bottom", "middle", "top").index(args.level)
        miss = chk.check.final & (np.abs(chk.check.error[:, lv]) > args.tolerance)
        where = ", ".join(f"({p[0]:.3f}, {p[1]:.3f})" for p in chk.check.points[miss][:5])
        print(f"  warning: the written program leaves {after[args.level] * 1e3:.3f} um > --tolerance "
              f"{args.tolerance * 1e3:.3f} um at the {args.level} level between its samples, at "
              f"{int(miss.sum())} of {len(miss)} checked samples ({where}{' ...' if miss.sum() > 5 else ''}): "
              "where the required offset steps (engagement entries and exits) a polyline can only approach it")
    program = setup.program.with_blocks(chk.blocks, chk.origin)
    with all_or_nothing():
        write_gcode(program, args.output, encoding=gcode_encoding(args.program),
                    header_comment=f"netshape deflection compensate: {args.scheme}, {args.level}, max wall error "
                    f"{before[args.level] * 1e3:.1f} -> {after[args.level] * 1e3:.2f} um "
                    f"(bottom {after['bottom'] * 1e3:.1f}, top {after['top'] * 1e3:.1f} um)")
        if args.json:
            _write_json(args.json, {"scheme": args.scheme, "level": args.level, "converged": True,
                                    "status": status, "iterations": res.iterations,
                                    "path_evaluations": res.path_evaluations, "rounds": chk.rounds,
                                    "density": args.density, "samples_checked": int(len(chk.check.s)),
                                    "max_wall_error_before_mm": before[args.level],
                                    "max_wall_error_after_mm": after[args.level],
                                    "before_mm": before, "after_mm": after, "worse_points": chk.worse_points,
                                    "time_s": dt, "message": res.message})
    return 0
