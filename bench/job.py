"""Time per stage of `netshape run` on ../shared/data/gcode/3D_Chips.ngc with every prediction and
the volumetric compensation (job file tests/python/job/data/chips_job.toml, program path set here).

Each stage's time is also given as a ratio to a reference measured in the same process: reading the
program into NumPy arrays (netshape.toolpath.read_gcode_arrays), the cheapest full pass over it.

    python bench/job.py [--step 2.0] [--spacing 1.0]
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

REPO = Path(__file__).resolve().parents[1]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--step", type=float, default=2.0, help="force sample spacing [mm] (2.0)")
    ap.add_argument("--spacing", type=float, default=1.0, help="Z-map spacing [mm] (1.0)")
    args = ap.parse_args()
    data = Path(os.environ.get("NETSHAPE_SHARED_DATA", REPO.parent / "shared" / "data"))
    program = data / "gcode" / "3D_Chips.ngc"
    if not program.is_file():
        print(f"skipped: {program} is absent")
        return 0
    from netshape import toolpath
    from netshape.job import job_from_dict, run_job

    job_dir = REPO / "tests" / "python" / "job" / "data"
    doc = tomllib.loads((job_dir / "chips_job.toml").read_text())
    doc["program"] = str(program)
    doc["cutting"]["step_mm"] = args.step
    doc["cutting"]["samples_per_revolution"] = 24
    doc["cutting"]["disk_height_mm"] = 0.5
    doc["stock"]["spacing_mm"] = args.spacing
    job = job_from_dict(doc, source="chips_job.toml", base_dir=job_dir)
    ref = min(_time(lambda: toolpath.read_gcode_arrays(program)) for _ in range(5))
    with tempfile.TemporaryDirectory() as out:
        t0 = time.perf_counter()
        s = run_job(job, out, quiet=True)
        total = time.perf_counter() - t0
    print(f"3D_Chips.ngc: force step {args.step} mm, Z-map spacing {args.spacing} mm, "
          f"{s['forces']['samples']} force samples")
    print(f"reference: read_gcode_arrays {1e3 * ref:.1f} ms")
    print(f"{'stage':<26}{'time [s]':>10}{'share':>8}{'x reference':>13}")
    for k, v in s["run_time_s"].items():
        if k == "total":
            continue
        print(f"{k:<26}{v:>10.3f}{v / total:>8.1%}{v / ref:>13.1f}")
    print(f"{'total':<26}{total:>10.3f}")
    e = s["errors"]["volumetric"]
    print(f"volumetric error {1e3 * e['max_before_mm']:.2f} -> {1e3 * e['max_after_mm']:.4f} µm; cycle time "
          f"{s['cycle_time_s']['original']:.2f} s -> {s['cycle_time_s']['compensated']:.2f} s")
    return 0


def _time(fn) -> float:
    t = time.perf_counter()
    fn()
    return time.perf_counter() - t


if __name__ == "__main__":
    sys.exit(main())
