"""`netshape forces`: cutting forces on the cutter over one or more revolutions
(frame and signs: docs/conventions.md)."""

from __future__ import annotations

import argparse
import math

from netshape.cli import _args as a

_DESCRIPTION = """\
Simulate the cutting forces ON THE CUTTER of a flat or ball end mill over whole revolutions and
write them as CSV (angle_deg,fx_N,fy_N,fz_N). Frame (docs/conventions.md §2): X along the feed, Z along
the tool axis from the tip into the spindle, Y = Z x X; the cutter turns clockwise seen from the spindle; the
angle is the immersion of flute 1 at the tool tip, clockwise from +Y.
"""

_EPILOG = """\
examples:
  netshape forces --tool flat --diameter 10 --flutes 2 --helix 30 --rpm 6000 --feed-per-tooth 0.1 \\
      --ap 3 --ae 10 --mode slot \\
      --coefficients Ktc=958.8,Krc=251.1,Kac=146.4,Kte=15.8,Kre=19.4,Kae=18.2 --csv slot.csv --plot slot.png
  netshape forces --tool ball --diameter 12 --flutes 2 --helix 30 --rpm 600 --feed-per-tooth 0.05 \\
      --ap 3 --ae 12 --mode slot --coefficient-set kim_zas_ball12 --csv ball.csv
named coefficient sets: flat: leekunhwee_flat_slot; ball: kim_zas_ball12 (Kim et al.).
"""


def _linear_coefficients(text: str):
    from netshape.force import parse_coefficients

    return parse_coefficients(text)


def register(sub) -> None:
    p = sub.add_parser("forces", help="cutting forces of a flat or ball end mill over a revolution",
                       description=_DESCRIPTION, epilog=_EPILOG,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--tool", choices=("flat", "ball"), default="flat", help="end mill kind (default flat)")
    p.add_argument("--diameter", type=a.positive("--diameter", "mm"), required=True, metavar="MM",
                   help="tool diameter [mm]")
    p.add_argument("--flutes", type=a.flutes(), required=True, metavar="N", help="number of flutes, 1..64")
    p.add_argument("--helix", type=a.real("--helix", "deg", ge=0, lt=85), default=30.0, metavar="DEG",
                   help="helix angle [deg] in [0, 85) (default 30)")
    p.add_argument("--rpm", type=a.positive("--rpm", "rev/min"), required=True, metavar="RPM",
                   help="spindle speed [rev/min] (sets the time axis of the plot)")
    p.add_argument("--feed-per-tooth", type=a.positive("--feed-per-tooth", "mm"), required=True, metavar="MM",
                   help="feed per tooth c [mm]")
    p.add_argument("--ap", type=a.positive("--ap", "mm"), required=True, metavar="MM", help="axial depth of cut [mm]")
    p.add_argument("--ae", type=a.positive("--ae", "mm"), metavar="MM",
                   help="radial depth of cut [mm] (up/down milling), from the wall to the tool's largest radius; "
                        "ball elements of smaller radius meet the wall at their own angle")
    p.add_argument("--mode", choices=("up", "down", "slot"), default="slot", help="milling mode (default slot)")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--coefficients", type=a.parsed("--coefficients", _linear_coefficients), metavar="K=V,...",
                   help="linear edge coefficients Ktc,Krc,Kac [N/mm^2], Kte,Kre,Kae [N/mm] (flat tool)")
    g.add_argument("--coefficient-set", metavar="NAME", help="a named coefficient set (see below)")
    p.add_argument("--inclination", type=a.real("--inclination", "deg", gt=-80, lt=80), default=0.0,
                   metavar="DEG", help="ball end mill: ramp angle xi of the feed [deg] in (-80, 80), > 0 climbing "
                   "(default 0)")
    p.add_argument("--runout-rho", type=a.real("--runout-rho", "mm", ge=0, lt=1), default=0.0, metavar="MM",
                   help="cutter runout: offset of the tool axis [mm] (default 0)")
    p.add_argument("--runout-lambda", type=a.real("--runout-lambda", "deg"), default=0.0, metavar="DEG",
                   help="runout angle [deg]: flute j cuts at R + rho cos(lambda - j 360/N) (default 0)")
    p.add_argument("--chip-exponent", type=a.real("--chip-exponent", gt=0, le=2), default=1.0, metavar="P",
                   help="chip-size effect: cutting terms grow as h_ref (h/h_ref)^P (flat tool; default 1, none)")
    p.add_argument("--reference-chip", type=a.real("--reference-chip", "mm", ge=0), default=0.0, metavar="MM",
                   help="h_ref of the size effect [mm] (default: the feed per tooth)")
    p.add_argument("--revolutions", type=a.real("--revolutions", ge=1), default=1.0,
                   help="revolutions (>= 1, default 1)")
    p.add_argument("--samples", type=a.integer("--samples", ge=8, le=1_000_000), default=360, metavar="N",
                   help="samples per revolution, 8..1000000 (default 360)")
    p.add_argument("--csv", required=True, metavar="OUT.csv", help="output CSV: angle_deg,fx_N,fy_N,fz_N")
    p.add_argument("--plot", metavar="OUT.png", help="also write a PNG of Fx, Fy, Fz against the angle")
    p.set_defaults(func=run)


def run(args) -> int:
    import numpy as np

    from netshape._atomic import all_or_nothing, atomic_write
    from netshape.cli import CliError
    from netshape.cli._args import check_outputs
    from netshape.force import cutter_forces

    check_outputs(args, files=("--csv", "--plot"))

    # options checked against each other (single values were checked while parsing)
    if args.mode != "slot" and args.ae is None:
        raise CliError(f"--mode = {args.mode}: needs --ae, the radial depth of cut [mm]")
    if args.ae is not None and args.ae > args.diameter:
        raise CliError(f"--ae = {args.ae:g}: must not exceed --diameter ({args.diameter:g}) [mm]")
    if args.mode == "slot" and args.ae is not None and abs(args.ae - args.diameter) > 1e-9 * args.diameter:
        raise CliError(f"--ae = {args.ae:g}: a slot is cut by the whole tool; give --ae {args.diameter:g} "
                       f"(the diameter) or leave it out")
    if args.coefficients is not None:
        if args.tool == "ball":
            raise CliError("--coefficients: a ball end mill (--tool ball) takes --coefficient-set "
                           "(e.g. kim_zas_ball12)")
    else:
        from netshape.force import ball_end_coefficient_set_names, linear_edge_coefficient_set_names

        names = linear_edge_coefficient_set_names() if args.tool == "flat" else ball_end_coefficient_set_names()
        if args.coefficient_set not in names:
            raise CliError(f"--coefficient-set = {args.coefficient_set}: unknown for a {args.tool} tool "
                           f"(known: {', '.join(names)})")
    if args.tool == "flat" and args.inclination != 0:
        raise CliError(f"--inclination = {args.inclination:g}: ramp cuts are modelled for --tool ball only")
    from netshape.force import RunoutSizeEffect

    ext = RunoutSizeEffect(runout_rho=args.runout_rho, runout_lambda=math.radians(args.runout_lambda),
                           chip_exponent=args.chip_exponent, reference_chip=args.reference_chip)
    if args.tool == "ball" and ext.chip_exponent != 1.0:
        raise CliError(f"--chip-exponent = {args.chip_exponent:g}: modelled for --tool flat only (a ball end "
                       "mill's size effect is its Feng–Menq exponents)")
    angles, forces = cutter_forces(
        tool=args.tool, diameter=args.diameter, flutes=args.flutes, helix_deg=args.helix,
        feed_per_tooth=args.feed_per_tooth, ap=args.ap, ae=args.ae, mode=args.mode,
        coefficients=args.coefficients, coefficient_set=args.coefficient_set, inclination_deg=args.inclination,
        samples_per_revolution=args.samples, revolutions=args.revolutions, extension=ext)
    deg = np.degrees(angles)
    table = np.column_stack([deg, forces])
    with all_or_nothing():
        with atomic_write(args.csv, "w") as fh:
            fh.write("angle_deg,fx_N,fy_N,fz_N\n")
            np.savetxt(fh, table, delimiter=",", fmt="%.10g")
        if args.plot:
            from netshape._atomic import atomic_save_figure
            from netshape.force.plots import plot_forces

            title = (f"{args.tool} D{args.diameter:g} N{args.flutes} β{args.helix:g}° {args.mode} "
                     f"ap {args.ap:g} c {args.feed_per_tooth:g} mm, {args.rpm:g} rpm")
            fig = plot_forces(angles, forces, title=title, rpm=args.rpm)
            atomic_save_figure(fig, args.plot, dpi=110)
    return 0
