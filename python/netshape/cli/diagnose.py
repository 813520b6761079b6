"""`netshape diagnose` — find where simulation and measurement disagree, name the missing effect,
add it and show the gap shrink (netshape.discrepancy, docs/discrepancy.md)."""

from __future__ import annotations

import argparse

_DESCRIPTION = """\
Read a measurement bundle (BUNDLE_DIR/manifest.toml + CSV files: kind cutting_force,
volumetric_error or wall_error), compare it with the bundle's model, fit every effect of the catalogue the model
may lack, add the one that held-out prediction error and BIC choose, and repeat until the residual
is consistent with the measurement noise. "effect": null means no catalogue effect was added:
"no missing effect found" when the residual is consistent with the noise, else "unexplained" says
where the rest is (component, covariate, trend/step/periodic). The noise comes from repeated points,
else the manifest's [noise] sigma_mm / sigma_N, else a smoother estimate ("noise_source").

  cutting_force     runout, edge_forces, size_effect, structural_mode
  volumetric_error  squareness, scale_error, thermal_drift, spindle_tilt, backlash
  wall_error        holder_compliance, runout
"""

_EPILOG = """\
examples:
  netshape diagnose slot_tests/ --json diagnosis.json
  netshape diagnose machine_check/ --json d.json --report report/    (PNG plots + index.html)
"""


def register(sub) -> None:
    p = sub.add_parser(
        "diagnose",
        help="name the effect a model misses from measurements",
        description=_DESCRIPTION,
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("bundle", metavar="BUNDLE_DIR", help="folder with manifest.toml and the CSV files")
    p.add_argument(
        "--json",
        required=True,
        metavar="OUT.json",
        help="write kind, effect, parameters, effects, rms_before, rms_after, noise_estimate, candidates, "
        "noise_source, noise_assumption, unexplained",
    )
    p.add_argument("--report", metavar="OUT_DIR", help="write residual plots (PNG) and index.html here")
    p.set_defaults(func=run)


def run(args) -> int:
    from netshape._atomic import all_or_nothing, atomic_write
    from netshape.cli._args import check_outputs
    from netshape.discrepancy import diagnose, load_bundle

    check_outputs(args, files=("--json",), folders=("--report",))
    bundle = load_bundle(args.bundle)
    d = diagnose(bundle)
    from netshape._json import dumps_json

    text = dumps_json(d.to_dict(), indent=2, cause=str(args.bundle))
    with all_or_nothing():
        with atomic_write(args.json) as fh:
            fh.write(text + "\n")
        if args.report:
            from netshape.discrepancy.report import write_report

            write_report(d, args.report)
    print(d.summary())
    for e in d.experiments:
        if "flute1_angle_at_t0_deg" in e:
            print(
                f"  {e['file']}: flute 1 at t = 0 at {e['flute1_angle_at_t0_deg']:.1f} deg, "
                f"spindle {e['spindle_rpm_estimated']:.1f} rpm"
            )
    return 0
