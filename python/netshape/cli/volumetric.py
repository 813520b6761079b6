"""`netshape volumetric` — machine volumetric error maps and compensated programs (Yang & Kweon)."""

from __future__ import annotations

import argparse

from netshape.cli import _args as a

_DESCRIPTION = """\
Volumetric error of a 3-axis machine from its ISO 230-1 geometric errors (machine TOML, see
docs/machine.md), and post-processor compensation of G-code so the actual tool tip lands on the
nominal path.

  map         error of the tool tip relative to the workpiece over a grid of the axes' travel
  compensate  rewrite a program: every point compensated to 1e-9 mm, lines and arcs followed
              within --chord-tolerance; points the compensation pushes outside travel are refused
"""

_EPILOG = """\
examples:
  netshape volumetric map machine.toml --grid 9,9,5 --plot map.png --json map.json
  netshape volumetric map machine.toml --program part.ngc --plot along_part.png
  netshape volumetric compensate part.ngc --machine machine.toml -o part_comp.ngc --chord-tolerance 0.001
"""


def register(sub) -> None:
    p = sub.add_parser("volumetric", help="machine volumetric error map and program compensation",
                       description=_DESCRIPTION, epilog=_EPILOG,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    vs = p.add_subparsers(dest="volumetric_command", metavar="ACTION")
    vs.required = True
    m = vs.add_parser("map", help="volumetric error over a grid of the workspace",
                      description="Tool-tip error relative to the workpiece over a regular grid of the "
                      "axes' travel (exact product of transforms; Yang & Kweon eq. 16 for |error|).")
    m.add_argument("machine", metavar="MACHINE.toml", help="machine description")
    m.add_argument("--grid", type=a.counts("--grid", 3, ge=1, example="9,9,5"), default=(9, 9, 5),
                   metavar="NX,NY,NZ",
                   help="grid points per axis over the travel (default 9,9,5)")
    m.add_argument("--program", metavar="PROGRAM",
                   help="map along this G-code program (block end points, arcs split at 0.01 mm) "
                   "instead of the grid")
    m.add_argument("--plot", metavar="OUT.png", help="write the error map plot (Yang & Kweon Fig. 6)")
    m.add_argument("--json", metavar="OUT.json", help="write summary and per-point errors [mm] as JSON")
    m.add_argument("--max-points", type=a.integer("--max-points", "points", ge=1), default=None, metavar="N",
                   help="refuse a map of more than N points, counted before the work (2000000)")
    m.set_defaults(func=run)
    c = vs.add_parser("compensate", help="compensate a G-code program",
                      description="Rewrite PROGRAM so the actual tool tip lands on the nominal path of "
                      "MACHINE. Every comment and non-motion word (M, S, T, G4, G43, G54-G59.3, G64 ...) is "
                      "kept in order at its place; M30 stays M30.")
    c.add_argument("program", metavar="PROGRAM", help="G-code program (RS274/NGC)")
    c.add_argument("--machine", required=True, metavar="MACHINE.toml", help="machine description")
    c.add_argument("-o", "--output", required=True, metavar="OUT.nc", help="compensated program")
    c.add_argument("--chord-tolerance", type=a.positive("--chord-tolerance", "mm"), default=0.002,
                   metavar="MM",
                   help="largest deviation of the actual path from the nominal lines and arcs [mm] "
                   "(default 0.002)")
    c.add_argument("--json", metavar="OUT.json", help="write the report as JSON")
    c.add_argument("--max-chords", type=a.integer("--max-chords", "moves", ge=1), default=None, metavar="N",
                   help="refuse a program whose compensated moves (estimated before the work from the "
                   "error model and --chord-tolerance) exceed N (20000000)")
    from netshape.cli._offsets import add_offset_options

    add_offset_options(c)
    c.set_defaults(func=run)


def run(args) -> int:
    import numpy as np

    from netshape.cli import CliError

    action = args.volumetric_command
    from netshape import machine as nm
    from netshape._atomic import all_or_nothing, atomic_save_figure, atomic_write
    from netshape.cli._args import check_outputs

    from netshape import _budget as B
    from netshape._json import check_finite, write_json

    check_outputs(args, files=("--plot", "--json") if action == "map" else ("--output", "--json"))
    machine = nm.load_machine(args.machine)
    if action == "map":
        limit = B.MAX_MAP_POINTS if args.max_points is None else args.max_points
        if args.program:
            B.refuse_over(f"--program = {args.program}", _program_points(args.program), limit, "map points",
                          "raise --max-points")
            emap = nm.program_error_map(machine, args.program)
            if len(emap.points) == 0:
                raise CliError(f"{args.program}: no motion blocks")
        else:
            points = float(np.prod(args.grid, dtype=float))
            B.refuse_over(f"--grid = {','.join(map(str, args.grid))}", points, limit, "map points", "raise --max-points")
            emap = nm.grid_error_map(machine, args.grid)
        _check_map(emap, args.machine, machine)
        s = emap.summary()
        print(f"{machine.name}: {s['points']} points, volumetric error {s['min_um']:.3f} – {s['max_um']:.3f} µm "
              f"(mean {s['mean_um']:.3f}); exact − first order ≤ {s['max_exact_minus_first_order_um']:.3g} µm")
        with all_or_nothing():
            if args.plot:
                atomic_save_figure(nm.plot_error_map(emap), args.plot, dpi=120)
            if args.json:
                write_json(args.json, {"machine": machine.name, **emap.to_dict(points=True)}, indent=1,
                           cause=args.machine)
        return 0
    if action == "compensate":
        from netshape import compensation as nc
        from netshape import toolpath

        from netshape.cli._offsets import offset_kwargs, reader_warnings

        with all_or_nothing():
            with reader_warnings("volumetric"):  # one context: each warning once for both reads
                arrays = toolpath.read_gcode_arrays(args.program, arcs="keep", **offset_kwargs(args))
                B.refuse_over(f"--chord-tolerance = {args.chord_tolerance:g}",
                              nc.estimate_chords(machine, arrays, args.chord_tolerance),
                              B.MAX_COMPENSATE_CHORDS if args.max_chords is None else args.max_chords,
                              f"compensated moves for {args.program} (estimated)",
                              "raise --max-chords or the tolerance")
                rep = nc.compensate_gcode(machine, args.program, args.output,
                                          chord_tolerance=args.chord_tolerance, **offset_kwargs(args))
            d = rep.to_dict()
            check_finite(d, cause=args.machine)
            if args.json:
                write_json(args.json, d, indent=1, cause=args.machine)
        print(f"{args.output}: {d['blocks_in']} blocks in, {d['blocks_out']} out; largest correction "
              f"{d['max_correction_mm'] * 1e3:.3f} µm, residual ≤ {d['max_residual_mm']:.2g} mm, "
              f"path within {d['max_path_deviation_mm'] * 1e3:.3f} µm; arcs kept {d['arcs_kept']}, "
              f"split {d['arcs_split']}; {d['commands']} comments and non-motion words kept")
        return 0
    raise CliError(f"unknown action {action!r}")


def _program_points(program) -> float:
    """Points of a map along ``program`` (block ends, arcs in chords within 0.01 mm), before reading it
    into points."""
    import numpy as np

    from netshape import toolpath

    a = toolpath.read_gcode_arrays(program, arcs="keep")
    arc = np.asarray(a["kind"]) == 2
    if not arc.any():
        return float(len(a["kind"]) + 1)
    r = np.linalg.norm((np.asarray(a["start"]) - np.asarray(a["center"]))[arc], axis=1)
    sweep = toolpath.block_lengths(a)[arc] / np.maximum(r, 1e-300)
    with np.errstate(divide="ignore", invalid="ignore"):
        theta = np.where(0.01 >= r, 0.5 * np.pi, 2.0 * np.arccos(1.0 - 0.01 / r))
        chords = np.ceil(sweep / theta)
    return float(len(a["kind"]) + 1 + np.sum(chords))


def _check_map(emap, path, machine) -> None:
    """A map with a non-finite error is refused, naming the machine file, the point and the tool length."""
    import numpy as np

    bad = ~(np.isfinite(emap.errors).all(axis=1) & np.isfinite(emap.volumetric)
            & np.isfinite(emap.first_order_difference))
    if bad.any():
        k = int(np.argmax(bad))
        x, y, z = emap.points[k]
        raise ValueError(f"{path}: its error model gives a non-finite tip error at X{x:g} Y{y:g} Z{z:g} "
                         f"(check the polynomial coefficients, tables and tool.length_mm = {machine.tool_length:g}); "
                         "nothing written")
