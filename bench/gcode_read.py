"""G-code reading speed: netshape (Python API into NumPy arrays) against pure-Python RS274 parsers
from PyPI (gcodeparser, pygcode) on the same file, in the same run.

The file is ../shared/data/gcode/3D_Chips.ngc (dense 3-D surfacing with #<param> and [expr] words)
repeated to about 1 M lines. The peers do not evaluate NGC parameters, so they parse the same lines
with the parameters substituted (plain numbers, i.e. easier text); they are timed on a slice and
scaled per line. Prints lines/s, ratios, and wall and CPU time (the machine may be shared).

    python bench/gcode_read.py [--lines 1000000] [--peer-lines 20000]
"""

from __future__ import annotations

import argparse
import re
import tempfile
import time
import warnings
from pathlib import Path

import netshape as ns

HERE = Path(__file__).resolve().parent
CHIPS = HERE.parent.parent / "shared" / "data" / "gcode" / "3D_Chips.ngc"


def make_program(n_lines: int, folder: Path) -> tuple[Path, Path, int]:
    lines = CHIPS.read_text().splitlines()
    head, body = lines[:24], [ln for ln in lines[24:] if ln.strip() and not ln.strip().upper().startswith("N6941M2")]
    reps = max(1, (n_lines - len(head)) // len(body))
    text = "\n".join(head + body * reps) + "\nM2\n"
    path = folder / "chips_1M.ngc"
    path.write_text(text)
    # the same program with parameters substituted, for the peers (they do not evaluate NGC expressions)
    plain = re.sub(r"\[#<[a-z]+>\*([-0-9.]+)\]", r"\1", text)
    plain = re.sub(r"^#<.*$", "", plain, flags=re.M).replace("T#<toolno>", "T1").replace("S#<rpm>", "S1600")
    plain = re.sub(r"(\d)\.(?!\d)", r"\1.0", plain)  # "10." -> "10.0" (gcodeparser needs it)
    plain_path = folder / "chips_1M_plain.ngc"
    plain_path.write_text(plain)
    return path, plain_path, text.count("\n")


def timed(fn, repeat: int = 3):
    best_wall = best_cpu = float("inf")
    result = None
    for _ in range(repeat):
        w, c = time.perf_counter(), time.process_time()
        result = fn()
        best_wall = min(best_wall, time.perf_counter() - w)
        best_cpu = min(best_cpu, time.process_time() - c)
    return result, best_wall, best_cpu


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lines", type=int, default=1_000_000)
    ap.add_argument("--peer-lines", type=int, default=20_000)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        path, plain, n = make_program(args.lines, Path(tmp))
        arrays, wall, cpu = timed(lambda: ns.toolpath.read_gcode_arrays(path))
        print(f"file: 3D_Chips.ngc repeated, {n} lines, {len(arrays['kind'])} blocks")
        print(f"netshape read_gcode_arrays : {n / wall / 1e6:6.2f} M lines/s wall, {n / cpu / 1e6:6.2f} M lines/s CPU")
        _, swall, scpu = timed(lambda: ns.toolpath.summary(path))
        print(f"netshape summary (stream)  : {n / swall / 1e6:6.2f} M lines/s wall, {n / scpu / 1e6:6.2f} M lines/s CPU")
        peer_text = "\n".join(plain.read_text().splitlines()[: args.peer_lines]) + "\n"
        m = peer_text.count("\n")
        peers = {}
        try:
            from gcodeparser import parse_gcode_lines

            def run_gcodeparser():
                return sum(1 for _ in parse_gcode_lines(peer_text))

            peers["gcodeparser"] = run_gcodeparser
        except ImportError:
            print("gcodeparser: not installed")
        try:
            from pygcode import Line

            def run_pygcode():
                return sum(len(Line(t).block.gcodes) for t in peer_text.splitlines())

            peers["pygcode"] = run_pygcode
        except ImportError:
            print("pygcode: not installed")
        for name, fn in peers.items():
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                _, pw, pc = timed(fn, repeat=1)
            print(f"{name:<27}: {m / pw / 1e6:6.3f} M lines/s wall ({m} lines); "
                  f"netshape is {(m / pw) and (n / wall) / (m / pw):6.1f}x faster (wall), "
                  f"{(n / cpu) / (m / pc):6.1f}x (CPU)")


if __name__ == "__main__":
    main()
