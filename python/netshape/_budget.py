"""Work budgets: the size of the work a command's numbers imply, estimated before it starts.

One number can ask for unbounded work (``--ts2 1e-9``, ``--spacing 1e-6``, a grid of 10⁷ runs). Every
command estimates the count its inputs imply (samples, grid points, path points, CC points, runs,
triangles) with the helpers of its area, then calls :func:`refuse_over`, which raises the one-line
error naming the input and the limit. The defaults below fit one command on a 24 GiB, 2-core machine
with room to spare (each says what one unit costs); options such as ``--max-samples`` raise them.
"""

from __future__ import annotations

import math

#: `plan`: fine interpolation samples (≈ 200 B each while planned: 1e8 ≈ 20 GB is the machine; 5e7 ≈ 10 GB).
MAX_PLAN_SAMPLES = 50_000_000
#: `plan`: memory of the look-ahead ring [bytes] (≈ 32 kB per block of look-ahead depth).
MAX_LOOKAHEAD_BYTES = 2 * 1024**3
LOOKAHEAD_BYTES_PER_BLOCK = 32 * 1024
#: `volumetric map`: grid or program points (≈ 1 kB each in the map, its plot and its JSON).
MAX_MAP_POINTS = 2_000_000
#: `volumetric compensate`: output chords (≈ 100 B of G-code and a few hundred B of state each).
MAX_COMPENSATE_CHORDS = 20_000_000
#: `deflection predict/compensate`: path points (each a force and deflection profile evaluation).
MAX_PATH_POINTS = 2_000_000
#: `run`: cutter steps of the Z-map sweep and force stage, and wall-error samples along the path.
MAX_JOB_STEPS = 5_000_000
MAX_JOB_ERROR_SAMPLES = 10_000_000
#: `posture plan`: CC points (each a C-space search, ≈ 0.1 s: 100 000 points are hours of work).
MAX_POSTURE_POINTS = 100_000
#: `batch`: runs (grid combinations × jobs), expanded and kept in memory before any runs.
MAX_BATCH_RUNS = 10_000
#: Z-map nodes (heights files, stock spacing): 8 B each plus the sweep's work arrays.
MAX_ZMAP_NODES = 40_000_000
#: Triangles of the Z-map STL of a run (50 B each: 1e7 ≈ 500 MB).
MAX_STL_TRIANGLES = 10_000_000


def count(x: float) -> str:
    """A count as people read it: whole numbers below 1e9 in full (50000000), others to 3 digits
    (1.23e+09, 4.5e+03 for an estimate of 4502.7)."""
    if not math.isfinite(x):
        return str(x)
    return str(int(x)) if float(x).is_integer() and abs(x) < 1e9 else f"{x:.3g}"


def refuse_over(cause: str, estimate: float, limit: float, what: str, hint: str = "") -> None:
    """Raise ValueError ``{cause}: gives {estimate} {what}, over the limit of {limit}[; hint]`` when the
    estimate (NaN and inf count as over) exceeds the limit; ``cause`` names the input (``--ts2 = 1e-09``,
    ``job.toml: cutting.step_mm = 1e-06``)."""
    if not estimate <= limit:
        raise ValueError(f"{cause}: gives {count(estimate)} {what}, over the limit of {count(limit)}"
                         + (f"; {hint}" if hint else ""))
