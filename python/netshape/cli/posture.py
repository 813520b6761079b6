"""`netshape posture` — 5-axis tool posture planning (C-space, MC-space, MB-spline, repair, machine angles)."""

from __future__ import annotations

import argparse

from netshape._budget import MAX_POSTURE_POINTS
from netshape.cli import _args as a

_DESCRIPTION = """\
Choose a collision-free, smoothly changing tool posture at every cutter-contact (CC) point of a 5-axis
ball-end path (Park, Jung, Hwang, Jung, "A theoretical consideration for continuity control of cutter
posture", KSPE): the normal posture (raw), its C-space and the MC-space move to the middle between the two
C-obstacles (mc), MB-spline smoothing of the posture-vector end points, and repair of any smoothed posture
that entered an obstacle (final). See docs/posture.md.

  plan   plan the postures along the middle iso-curve of a surface (or the passage of an impeller)
"""

_EPILOG = """\
examples:
  netshape posture plan --impeller --out run/                       default impeller and tool
  netshape posture plan --impeller imp.toml --tool tool.toml --out run/ --clearance 0.5 --plot
  netshape posture plan --surface floor.json --obstacles walls.stl --tool tool.toml --out run/ \\
                        --machine table_ac.toml
"""


def register(sub) -> None:
    p = sub.add_parser("posture", help="5-axis tool posture planning", description=_DESCRIPTION, epilog=_EPILOG,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    ps = p.add_subparsers(dest="posture_command", metavar="ACTION")
    ps.required = True
    q = ps.add_parser("plan", help="plan postures along a path", description=_DESCRIPTION, epilog=_EPILOG,
                      formatter_class=argparse.RawDescriptionHelpFormatter)
    src = q.add_mutually_exclusive_group(required=True)
    src.add_argument("--impeller", nargs="?", const="", metavar="IMPELLER.toml",
                     help="machine the passage floor of a generated impeller (no file: the default impeller)")
    src.add_argument("--surface", metavar="SURF.json",
                     help="NURBS surface to machine (JSON or TOML; normals towards the tool); needs --obstacles")
    q.add_argument("--obstacles", metavar="OBST.stl", help="surfaces the assembly must clear (STL)")
    q.add_argument("--tool", metavar="TOOL.toml",
                   help="ball-end cutter TOML with shank_diameter_mm, shank_length_mm, holder_diameter_mm, "
                   "holder_length_mm (default with --impeller: Ø6 ball, Ø20 holder)")
    q.add_argument("--out", required=True, metavar="DIR", help="output folder (created if missing)")
    q.add_argument("--clearance", type=a.non_negative("--clearance", "mm"), default=0.5, metavar="MM",
                   help="safety clearance [mm] (default 0.5)")
    q.add_argument("--machine", metavar="KIN.toml",
                   help="machine kinematics (table_ac or head_bc): also write program.ngc with A/C or B/C words")
    q.add_argument("--points", type=a.integer("--points", ge=4, le=MAX_POSTURE_POINTS), default=40, metavar="N",
                   help=f"CC points along the path, 4..{MAX_POSTURE_POINTS} (default 40)")
    q.add_argument("--passes", type=a.integer("--passes", ge=0), default=3, metavar="K",
                   help="MB-spline smoothing passes (default 3)")
    q.add_argument("--tilt-max", type=a.real("--tilt-max", "deg", gt=0, lt=90), default=60.0, metavar="DEG",
                   help="largest tilt searched [deg] in (0, 90) (default 60)")
    q.add_argument("--feed", type=a.positive("--feed", "mm/min"), default=1000.0, metavar="MM_PER_MIN",
                   help="feed of program.ngc and of the rotary-axis figures [mm/min] (default 1000)")
    q.add_argument("--approach-mm", type=a.non_negative("--approach-mm", "mm"), default=10.0, metavar="MM",
                   help="approach and retract along the tool axis [mm] (default 10; 0: none)")
    q.add_argument("--chord-mm", type=a.positive("--chord-mm", "mm"), default=0.01, metavar="MM",
                   help="subdivide rotary moves where the tip would leave the chord by more [mm] (default 0.01)")
    q.add_argument("--plot", action="store_true", help="write cspace.png and angles.png")
    q.add_argument("--plot-point", type=a.integer("--plot-point", ge=0), metavar="I", help="CC point of cspace.png (default: first collision)")
    q.set_defaults(func=run)


def run(args) -> int:
    import math

    from netshape import posture as npost
    from netshape._atomic import all_or_nothing
    from netshape.cli import CliError
    from netshape.cli._args import check_outputs

    check_outputs(args, folders=("--out",))

    # options checked against each other (single values were checked while parsing; --plot-point against
    # the number of points by PostureRun.write)
    if args.impeller is not None and args.obstacles:
        raise CliError(f"--obstacles = {args.obstacles}: not used with --impeller (the impeller's blades are "
                       "the obstacles)")
    if args.surface is not None:
        for name in ("obstacles", "tool"):
            if not getattr(args, name):
                raise CliError(f"--{name}: required with --surface")
    kin = npost.load_kinematics(args.machine) if args.machine else None
    if args.impeller is not None:
        imp = npost.load_impeller(args.impeller or None)
        cc, normals = imp.cc_path(args.points)
        verts, faces = imp.obstacles()
        assembly = npost.load_tool(args.tool) if args.tool else npost.default_assembly()
    else:
        from netshape import geometry as ng

        surf = (ng.load_toml if str(args.surface).endswith(".toml") else ng.load_json)(args.surface)
        if not isinstance(surf, ng.NurbsSurface):
            raise CliError(f"--surface {args.surface}: holds a curve, not a NURBS surface")
        cc, normals = npost.surface_cc_path(surf, args.points)
        try:
            verts, faces, _ = ng.read_stl(args.obstacles)
        except ValueError as exc:
            raise CliError(f"--obstacles {args.obstacles}: {exc}") from None
        if len(faces) == 0:
            raise CliError(f"--obstacles {args.obstacles}: empty mesh (no triangles)")
        assembly = npost.load_tool(args.tool)
    opts = npost.PlanOptions()
    opts.passes = args.passes
    opts.cspace.theta_max = math.radians(args.tilt_max)
    run_ = npost.plan_postures(cc, normals, verts, faces, assembly, clearance=args.clearance, options=opts,
                               kinematics=kin, approach_mm=args.approach_mm, chord_mm=args.chord_mm,
                               feed_mm_per_min=args.feed)
    from netshape._atomic import make_output_folder

    out = make_output_folder(args.out, "--out")
    with all_or_nothing():
        run_.write(out, plot=args.plot, plot_point=args.plot_point, kinematics=kin, feed_mm_per_min=args.feed)
    s = run_.summary()
    print(f"{s['points']} CC points: collisions raw {s['collisions']['raw']}, mc {s['collisions']['mc']}, "
          f"final {s['collisions']['final']}; repaired {s['repaired']}; max posture change "
          f"{s['max_posture_change_deg_per_mm']['mc']:.3g} (mc) -> {s['max_posture_change_deg_per_mm']['final']:.3g} "
          f"(final) deg/mm; moves colliding {s['moves']['colliding_before_repair']} -> {s['moves']['colliding']} "
          f"({s['moves']['inserted']} CL points inserted); written to {out}")
    if s["status"] != "ok":
        print(f"  warning: status {s['status']}: {s['collisions']['final']} final postures and "
              f"{s['moves']['colliding']} moves of program.ngc still come within --clearance of the obstacles; "
              "check them before running the program")
    rot = s["rotary"]
    for stage in ("raw", "mc", "final", "program"):
        print(f"  rotary {stage:7s} at {rot['feed_mm_per_min']:g} mm/min: " + "; ".join(
            f"{ax} peak/rms {r['peak_velocity_deg_s']:.3g}/{r['rms_velocity_deg_s']:.3g} deg/s, "
            f"{r['peak_acceleration_deg_s2']:.3g}/{r['rms_acceleration_deg_s2']:.3g} deg/s²"
            for ax, r in rot[stage].items()))
    return 0
