"""Round trips of the force and wall effects over a family of hidden sizes (issue 43 item 3): hidden
effect → diagnose → the manifest's model updated by netshape.discrepancy.update_tool → re-diagnosis,
and the error the original and the updated model leave against the hidden truth.

    PYTHONPATH=python python bench/discrepancy_round_trip.py [--quick]

Family: edge forces (Kte, Kre, Kae) scaled 1.5–3× the model's, 2-flute runout ρ 5–20 µm, chip
exponent 0.6–0.9, holder stiffness 4–30 N/µm; noise as in tests/python/discrepancy/generators.py.
Prints, per case: the effect named, the re-diagnosis, the rms error of the original and the updated model
against the truth (forces [N] over the bundle's conditions; walls [µm] of the bundle's cuts at its
heights) and the fraction removed. --quick: two sizes per effect.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python" / "discrepancy"))

import netshape.discrepancy as nd  # noqa: E402
from netshape import deflection as d  # noqa: E402
from netshape.discrepancy.update_tool import apply_to_coefficients, apply_to_tool  # noqa: E402
from generators import (WALL_AP, WALL_CONDITIONS, WALL_MODEL, WALL_TOOL, force_bundle,  # noqa: E402
                        model_force_error, wall_bundle)


def _round_trip(folder: Path, apply):
    first = nd.diagnose(nd.load_bundle(folder))
    m = folder / "manifest.toml"
    before = tomllib.loads(m.read_text())
    if first.effect is not None:
        m.write_text(apply(first, m.read_text()))
    again = nd.diagnose(nd.load_bundle(folder))
    return first, again, before, tomllib.loads(m.read_text())


def _walls(tool: dict, compliance_mm_per_N: float) -> np.ndarray:
    """Wall errors [mm] of the bundle's conditions at 9 heights with the given holder compliance."""
    out = []
    for mode, ae, c in WALL_CONDITIONS:
        m = d.make_model(diameter=tool["diameter_mm"], flutes=tool["flutes"], helix_deg=tool["helix_deg"],
                         stick_out=tool["stick_out_mm"], youngs_modulus=tool["youngs_modulus_MPa"], feed_per_tooth=c,
                         ap=WALL_AP, ae=ae, mode=mode, coefficients=WALL_MODEL["coefficients"],
                         holder_compliance=compliance_mm_per_N)
        side = d.WallSide.left if mode == "up" else d.WallSide.right
        out.append(np.asarray(d.wall_errors(m, d.DeflectionWorkspace(m), side, np.linspace(0, WALL_AP, 9)).error))
    return np.concatenate(out)


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="two sizes per effect")
    quick = ap.parse_args().quick
    n = 2 if quick else 4
    cases = [("edge_forces", {"edges": (16 * s, 20 * s, 10 * s)}, apply_to_coefficients)
             for s in np.linspace(1.5, 3.0, n)]
    cases += [("runout", {"runout": (float(r), 0.0)}, apply_to_tool) for r in np.linspace(0.005, 0.02, n)]
    cases += [("size_effect", {"exponent": float(p)}, apply_to_coefficients) for p in np.linspace(0.6, 0.9, n)]
    cases += [("holder_compliance", {"holder_stiffness": float(k)}, apply_to_tool) for k in np.geomspace(4, 30, n)]
    print(f"{'hidden':38s} {'named':18s} {'again':8s} {'original':>10s} {'updated':>10s} {'removed':>8s}")
    for effect, hidden, apply in cases:
        t0 = time.perf_counter()
        with tempfile.TemporaryDirectory() as tmp:
            if effect == "holder_compliance":
                b = wall_bundle(Path(tmp), form="x", **hidden)
                first, again, before, after = _round_trip(b, apply)
                truth = _walls(WALL_TOOL, 1e-3 / hidden["holder_stiffness"])
                c1 = 1e-3 * after["tool"].get("holder_compliance_um_per_N", 0.0)
                e0 = 1e3 * np.sqrt(np.mean((_walls(WALL_TOOL, 0.0) - truth) ** 2))
                e1 = 1e3 * np.sqrt(np.mean((_walls(WALL_TOOL, c1) - truth) ** 2))
                unit = "µm"
            else:
                b = force_bundle(Path(tmp), **hidden)
                first, again, before, after = _round_trip(b, apply)
                e0, e1, unit = model_force_error(before, hidden), model_force_error(after, hidden), "N"
        label = ", ".join(f"{k}={np.round(v, 4)}" for k, v in hidden.items())
        print(f"{label:38s} {str(first.effect):18s} {str(again.effect):8s} {e0:8.3f}{unit:>2s} {e1:8.3f}{unit:>2s} "
              f"{100 * (1 - e1 / e0):7.1f}%   ({time.perf_counter() - t0:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
