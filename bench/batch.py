"""Speed-up of `netshape batch` on a Dask LocalCluster against the same runs one by one in one process.

    python bench/batch.py [--workers 2] [--runs 4]

The study is the bundled demo job (examples/demo/job.toml) with forces and volumetric errors, a
coarse Z-map and no plots, over a grid of machine error scalings (``--runs`` values). The cluster's
start-up (worker processes importing netshape) is timed apart. Rows of both ways must be equal.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
import warnings
from pathlib import Path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

REPO = Path(__file__).resolve().parents[1]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--runs", type=int, default=4)
    args = ap.parse_args()
    warnings.simplefilter("ignore")
    from dask.distributed import Client, LocalCluster

    from netshape.job.batch import ERROR_COLUMNS, expand, run_specs

    demo = REPO / "examples" / "demo"
    doc = tomllib.loads((demo / "job.toml").read_text())
    with tempfile.TemporaryDirectory() as tmp:
        import tomli_w

        doc["predict"] = {"forces": True, "deflection": False, "volumetric": True, "feed_plan": True}
        doc["compensate"] = {"volumetric": True, "chord_tolerance_mm": 0.001}
        doc["stock"]["spacing_mm"] = 0.5
        doc["report"] = {"plots": False, "zmap_stl": False}
        doc["grid"] = {"machine.error_scale": [0.5 + 0.5 * i for i in range(args.runs)]}
        doc["program"] = str(demo / "part.ngc")
        doc["tool"] = str(demo / "tool.toml")
        doc["machine"]["file"] = str(demo / "machine.toml")
        for pc in doc["stock"]["pre_cut"]:
            pc["program"], pc["tool"] = str(demo / pc["program"]), str(demo / pc["tool"])
        study = Path(tmp) / "study.toml"
        study.write_text(tomli_w.dumps(doc))
        specs = expand([study])
        t = time.perf_counter()
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
        client.run(lambda: __import__("netshape.job.run") and None)
        t_start = time.perf_counter() - t
        t = time.perf_counter()
        rows_d = run_specs(specs, Path(tmp) / "dask", client=client)
        t_dask = time.perf_counter() - t
        client.close()
        cluster.close()
        t = time.perf_counter()
        rows_1 = run_specs(specs, Path(tmp) / "one", scheduler="none")
        t_one = time.perf_counter() - t
    same = all(all(a[c] == b[c] for c in ERROR_COLUMNS) for a, b in zip(rows_d, rows_1))
    print(f"{len(specs)} runs: one by one {t_one:.1f} s; LocalCluster {args.workers} workers {t_dask:.1f} s "
          f"after a {t_start:.1f} s start; speed-up {t_one / t_dask:.2f} ({t_one / (t_dask + t_start):.2f} with "
          f"the start); rows equal: {same}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
