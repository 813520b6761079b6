"""Issue 3 in one run: force element evaluations (bench/force_eval.py), the Z-map sweep
(bench/stock_sweep.py: random ramps and the 10 000-block surfacing program on a 0.1 mm grid), then
one summary of the three figures against their targets. Every ratio is a same-process CPU-time ratio
to a vectorised NumPy implementation of the same algorithm.

    PYTHONPATH=python python bench/cutting.py [--quick]
"""

from __future__ import annotations

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import force_eval  # noqa: E402  (the scripts beside this one)
import stock_sweep  # noqa: E402


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="small sizes (a smoke run; no surfacing program)")
    a = p.parse_args(argv)
    forces = force_eval.main(["--angles", "360", "--repeat", "2"] if a.quick else [])
    print()
    stock = stock_sweep.main(["--quick", "--repeats", "1"] if a.quick else ["--repeats", "5"])
    print()
    print(f"summary (load average {os.getloadavg()[0]:.1f}; targets: ratios >= 20x)")
    print(f"  force element evaluations   {forces['cpp_evals_per_s'] / 1e6:8.1f} M/s   ratio to NumPy {forces['ratio']:6.1f}x")
    for key, r in stock.items():
        if key.startswith("ramps"):
            print(f"  Z-map {key:22s}{r['cpp_node_updates_per_s'] / 1e6:8.1f} M node updates/s   "
                  f"ratio to NumPy {r['ratio']:6.1f}x")
    for key, r in stock.items():
        if key.startswith("surfacing"):
            print(f"  10 000-block {key:15s} {r['per_block_s']:.3f} s block by block, {r['merged_s']:.3f} s with "
                  f"collinear runs merged (grid {r['grid']})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
