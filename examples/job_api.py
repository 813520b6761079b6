"""The main job from Python: read the bundled demo job, change a key, run it, read the summary.

    python examples/job_api.py [OUT_DIR] [--quick]

Runs examples/demo/job.toml twice — as written and with the machine's errors doubled
(`machine.error_scale = 2`) — and prints the volumetric error before and after compensation and the
cycle time of each run. --quick leaves out the force and deflection stages and the plots.
"""

from __future__ import annotations

import sys
from pathlib import Path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from netshape.job import job_from_dict, run_job, set_dotted

DEMO = Path(__file__).resolve().parent / "demo"


def main(argv: list[str]) -> dict:
    quick = "--quick" in argv
    args = [a for a in argv if a != "--quick"]
    out = Path(args[0]) if args else Path("job-api-example")
    doc = tomllib.loads((DEMO / "job.toml").read_text())
    if quick:
        doc["predict"].update(forces=False, deflection=False)
        doc["compensate"]["deflection"] = False
        doc["report"] = {"plots": False, "zmap_stl": False}
    results = {}
    for name, d in (("as written", doc), ("errors x2", set_dotted(doc, "machine.error_scale", 2.0))):
        job = job_from_dict(d, source=str(DEMO / "job.toml"), base_dir=DEMO)
        s = run_job(job, out / name.replace(" ", "_"))
        v = s["errors"]["volumetric"]
        print(f"{name:<11} volumetric error {1e3 * v['max_before_mm']:.3f} µm -> {1e3 * v['max_after_mm']:.4f} µm, "
              f"cycle time {s['cycle_time_s']['original']:.2f} s; report {out / name.replace(' ', '_') / 'report.html'}")
        results[name] = s
    return results


if __name__ == "__main__":
    main(sys.argv[1:])
