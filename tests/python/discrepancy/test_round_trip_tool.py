"""Issue 43 item 3 for the force and wall effects: hidden effect → diagnose → updated model (the tool
or coefficient TOML written by netshape.discrepancy.update_tool) → the re-diagnosis of the same bundle
says ``effect: None``, and the updated model's prediction (forces; deflection: the wall of a straight
cut) and compensation (a pocket's finish wall) against the hidden truth remove ≥ 90 % of the error
the original model left.

Hidden truths: forces from generators.oracle_forces (an independent NumPy element sum); walls from
generators.wall_bundle (the holder spring as the rigid translation F·n/k added to netshape's e₀); the
truth's straight cut and pocket from netshape.deflection with the true holder compliance in the tool.
Wider families (other sizes of each effect, noise levels): bench/discrepancy_round_trip.py.
"""

from __future__ import annotations

import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

import netshape as ns
import netshape.discrepancy as nd
from netshape import deflection as d
from netshape.discrepancy.update_tool import apply_to_coefficients, apply_to_tool

from generators import force_bundle, model_force_error, wall_bundle

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "deflection"))
from pocket_cases import Pocket, pocket_gcode, stock_bounds  # noqa: E402

K_TRUE = 10.0  # holder stiffness [N/µm]
COEFFS = "Ktc=900,Krc=270,Kac=150,Kte=16,Kre=20,Kae=10"


def _update(folder: Path, apply, diagnosis) -> None:
    """The bundle's manifest rewritten by ``apply`` (its [tool] or [model] table holds the model)."""
    m = folder / "manifest.toml"
    m.write_text(apply(diagnosis, m.read_text()))


@pytest.mark.parametrize(
    "hidden, effect, apply",
    [
        ({"edges": (32.0, 40.0, 4.0)}, "edge_forces", apply_to_coefficients),
        ({"runout": (0.012, 0.0)}, "runout", apply_to_tool),
        ({"exponent": 0.75}, "size_effect", apply_to_coefficients),
    ],
    ids=["edge_forces", "runout", "size_effect"],
)
def test_force_effect_round_trip(tmp_path, hidden, effect, apply):
    b = force_bundle(tmp_path, revolutions=1, per_rev=60, **hidden)
    first = nd.diagnose(nd.load_bundle(b))
    assert first.effect == effect
    before = tomllib.loads((b / "manifest.toml").read_text())
    _update(b, apply, first)
    after = tomllib.loads((b / "manifest.toml").read_text())
    again = nd.diagnose(nd.load_bundle(b))
    assert again.effect is None, again.summary()
    e0, e1 = model_force_error(before, hidden), model_force_error(after, hidden)
    assert e1 <= 0.1 * e0, (e0, e1)


def _cutter(compliance_um_per_N: float = 0.0, text: str | None = None):
    base = 'kind = "flat"\ndiameter_mm = 6.0\nflutes = 3\nhelix_deg = 30.0\nflute_length_mm = 20.0\n' \
           'stick_out_mm = 30.0\nyoungs_modulus_MPa = 600000.0\n'
    doc = tomllib.loads(text if text is not None else base)
    if text is None and compliance_um_per_N:
        doc["holder_compliance_um_per_N"] = compliance_um_per_N
    return ns.cutter.cutter_from_dict(doc), base


def _pocket_walls(cutter, truth_cutter):
    """(predicted wall error of the finish pass [mm], the hidden truth's wall error after compensating
    with ``cutter`` [mm]) at the middle of the cut, over the pocket's final wall."""
    p = Pocket(tool_diameter=6, half_x=14, half_y=10, corner_radius=5, rings=2, stepover=2.5, z=-3.0)
    lo, hi = stock_bounds(p)
    prog = ns.toolpath.parse_gcode(pocket_gcode(p))
    out = []
    for c in (cutter, truth_cutter):
        stock = ns.stock.ZMap(lo[0], hi[0], lo[1], hi[1], 0.2, hi[2], lo[2])
        out.append(d.setup_path(prog, c, stock, coefficients=COEFFS, rpm=8000, spacing=1.0, side="right"))
    setup, truth = out
    comp = d.compensate_path(setup, scheme="accelerated", tolerance=5e-4)
    n = len(truth.nominal)
    normals = d.wall_normals(truth.nominal, truth.side)
    honest = d.path_wall_errors(truth.model, truth.cutter, truth.stock, truth.nominal, normals,
                                np.asarray(comp.offsets), truth.options)
    # the finish loop, without its corner points (a turn of more than 30°: the compensation gives them
    # the next point's offset and does not target their own error)
    xy = np.asarray(truth.nominal)[:, :2]
    d_in, d_out = np.diff(xy, axis=0)[:-1], np.diff(xy, axis=0)[1:]
    cos = np.sum(d_in * d_out, axis=1) / (np.linalg.norm(d_in, axis=1) * np.linalg.norm(d_out, axis=1))
    corner = np.r_[False, cos < np.cos(np.radians(30.0)), False]
    on = (np.asarray(honest.engaged) > 0) & (np.arange(n) > n // 2) & ~corner
    return np.asarray(honest.error)[on, 1]


def test_holder_compliance_round_trip(tmp_path):
    b = wall_bundle(tmp_path, holder_stiffness=K_TRUE, form="x")
    first = nd.diagnose(nd.load_bundle(b))
    assert first.effect == "holder_compliance"
    _update(b, apply_to_tool, first)
    again = nd.diagnose(nd.load_bundle(b))
    assert again.effect is None, again.summary()

    original, text = _cutter()
    truth, _ = _cutter(1.0 / K_TRUE)
    updated, _ = _cutter(text=apply_to_tool(first, text))
    # straight cut: the steady wall of the bundle's first condition, predicted vs the hidden truth
    def wall(c):
        m = d.model_for_cutter(c, feed_per_tooth=0.15, coefficients=COEFFS, ap=4.0)
        m2 = d.make_model(diameter=6, flutes=3, helix_deg=30, stick_out=30, youngs_modulus=6e5, feed_per_tooth=0.15,
                          ap=4.0, ae=0.5, mode="down", coefficients=COEFFS, holder_compliance=c.holder_compliance)
        assert m.holder_compliance == m2.holder_compliance
        return np.asarray(d.wall_errors(m2, d.DeflectionWorkspace(m2), d.WallSide.right, np.linspace(0, 4, 9)).error)
    e0 = np.sqrt(np.mean((wall(original) - wall(truth)) ** 2))
    e1 = np.sqrt(np.mean((wall(updated) - wall(truth)) ** 2))
    assert e1 <= 0.1 * e0, (e0, e1)
    # pocket: compensated with the original / the updated tool, cut by the hidden truth
    r0 = np.sqrt(np.mean(_pocket_walls(original, truth) ** 2))
    r1 = np.sqrt(np.mean(_pocket_walls(updated, truth) ** 2))
    assert r1 <= 0.1 * r0, (r0, r1)
