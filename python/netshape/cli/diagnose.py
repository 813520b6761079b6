"""`netshape diagnose` — find where simulation and measurement disagree, name the missing effect,
add it and show the gap shrink (netshape.discrepancy, docs/discrepancy.md)."""

from __future__ import annotations

import argparse
from pathlib import Path

_DESCRIPTION = """\
Read a measurement bundle (BUNDLE_DIR/manifest.toml + CSV files: kind cutting_force,
volumetric_error or wall_error), compare it with the bundle's model, fit every effect of the catalogue the model
may lack, add the one that held-out prediction error and BIC choose, and repeat until the residual
is consistent with the measurement noise. "effect": null means no catalogue effect was added:
"no missing effect found" when the residual is consistent with the noise, else "unexplained" says
where the rest is (component, covariate, trend/step/periodic). The noise comes from repeated points,
else the manifest's [noise] sigma_mm / sigma_N, else a smoother estimate ("noise_source").

  cutting_force     runout, edge_forces, size_effect, structural_mode
  volumetric_error  squareness, scale_error, thermal_drift, spindle_tilt, backlash, cyclic_error
  wall_error        holder_compliance, runout

--update MODEL_FILE --model-out NEW_FILE writes MODEL_FILE with the effects found added (comments
name the diagnosis; everything else kept; written whole or not at all; no effect found: a copy).
MODEL_FILE is a machine TOML for a volumetric_error bundle (the diagnosis then runs against that
machine instead of the bundle's [model]), the tool TOML for a wall_error bundle, a cutter or
coefficients TOML for a cutting_force bundle.
"""

_EPILOG = """\
examples:
  netshape diagnose slot_tests/ --json diagnosis.json
  netshape diagnose machine_check/ --json d.json --report report/    (PNG plots + index.html)
  netshape diagnose machine_check/ --json d.json --update vmc.toml --model-out vmc_new.toml
  netshape diagnose machine_check/ --json d2.json --machine vmc_new.toml   (check: effect null)
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
    p.add_argument("--machine", metavar="MACHINE.toml",
                   help="volumetric bundles: diagnose against this machine instead of the bundle's [model]")
    p.add_argument("--update", metavar="MODEL_FILE", help="the model file to add the effects found to")
    p.add_argument("--model-out", metavar="NEW_FILE", help="where to write the updated model (with --update)")
    p.set_defaults(func=run)


def run(args) -> int:
    from netshape._atomic import all_or_nothing, atomic_write
    from netshape.cli._args import check_outputs
    from netshape.discrepancy import diagnose, load_bundle

    if (args.update is None) != (args.model_out is None):
        raise ValueError("--update and --model-out: give both (the model file and where to write its update)")
    check_outputs(args, files=("--json", "--model-out"), folders=("--report",))
    bundle = load_bundle(args.bundle)
    machine = args.machine
    if args.update is not None:
        from netshape.discrepancy.update import check_model

        check_model(bundle.kind, Path(args.update))  # the right kind of file, and an updater for it
        if bundle.kind == "volumetric_error":
            if machine is not None:
                raise ValueError("--machine and --update: give one (a volumetric diagnosis runs against the "
                                 "machine it updates)")
            machine = args.update
    d = diagnose(bundle, machine=machine)
    new_model = None
    if args.update is not None:
        from netshape.discrepancy.update import apply

        new_model = apply(d, Path(args.update))
    from netshape._json import dumps_json

    text = dumps_json(d.to_dict(), indent=2, cause=str(args.bundle))
    with all_or_nothing():
        with atomic_write(args.json) as fh:
            fh.write(text + "\n")
        if new_model is not None:
            with atomic_write(args.model_out) as fh:
                fh.write(new_model)
        if args.report:
            from netshape.discrepancy.report import write_report

            write_report(d, args.report)
    print(d.summary())
    if new_model is not None:
        what = "with " + ", ".join(e["effect"] for e in d.effects) + " added" if d.effects else "unchanged (no effect)"
        print(f"model: {args.model_out} ({what})")
    for e in d.experiments:
        if "flute1_angle_at_t0_deg" in e:
            print(
                f"  {e['file']}: flute 1 at t = 0 at {e['flute1_angle_at_t0_deg']:.1f} deg, "
                f"spindle {e['spindle_rpm_estimated']:.1f} rpm"
            )
    return 0
