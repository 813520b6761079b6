"""Error synthesis of netshape.machine against independent computations and textbook cases."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import netshape as ns

ROOT = Path(__file__).resolve().parents[3]
HMC = ROOT / "examples" / "machines" / "hmc_yang_kweon.toml"
AXES = "XYZ"


def _rot(axis: int, a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    r = np.eye(3)
    r[i, i], r[i, j], r[j, i], r[j, j] = c, -s, s, c
    return r


def _hom(r, t) -> np.ndarray:
    h = np.eye(4)
    h[:3, :3], h[:3, 3] = r, t
    return h


def _random_machine(rng, scale=1.0):
    order = rng.permutation(3)
    ntool = int(rng.integers(0, 4))
    doc = {"tool_chain": [AXES[k] for k in order[:ntool]], "workpiece_chain": [AXES[k] for k in order[ntool:]],
           "tool": {"length_mm": float(rng.uniform(50, 200)), "nose_mm": list(rng.uniform(-50, 50, 3)),
                    "direction": list(v / np.linalg.norm(v) for v in [rng.normal(size=3)])[0].tolist()},
           "spindle": {"tilt_a_rad": scale * 1e-4 * rng.uniform(-1, 1), "tilt_b_rad": scale * 1e-4 * rng.uniform(-1, 1)},
           "squareness": {k: scale * 1e-4 * rng.uniform(-1, 1) for k in ("EC0Y_rad", "EB0Z_rad", "EA0Z_rad")},
           "axes": {}}
    for a in AXES:
        polys = {}
        for c, name in enumerate(ns.machine.iso_names(a)):
            size = 0.05 if c < 3 else 1e-4
            polys[name + ("_mm" if c < 3 else "_rad")] = [
                scale * size * rng.uniform(-1, 1) / 500.0**j for j in range(4)]
        doc["axes"][a] = {"origin_mm": list(rng.uniform(-100, 100, 3)), "polynomials": polys}
    return ns.machine.machine_from_dict(doc), doc


def _reference(doc, p):
    """Direct composition of 4x4 homogeneous matrices (NumPy, np.sin/np.cos), independent of C++."""
    def comp(a, name, q):
        ax = doc["axes"][a]["polynomials"]
        for key, coef in ax.items():
            if key.split("_")[0] == name:
                return sum(c * q**j for j, c in enumerate(coef))
        return 0.0

    sq = doc["squareness"]
    u = [np.array([1.0, 0, 0]), _rot(2, sq["EC0Y_rad"]) @ [0, 1.0, 0],
         _rot(0, sq["EA0Z_rad"]) @ _rot(1, sq["EB0Z_rad"]) @ [0, 0, 1.0]]

    def motion(k, q, actual):
        if not actual:
            return np.eye(3), q * np.eye(3)[k]
        a = AXES[k]
        e = [comp(a, n, q) for n in ns.machine.iso_names(a)]
        r = _rot(2, e[5]) @ _rot(1, e[4]) @ _rot(0, e[3])
        return r, q * u[k] + np.array(e[:3])

    def W(actual):
        ht = np.eye(4)
        for a in doc["tool_chain"]:
            k = AXES.index(a)
            r, t = motion(k, p[k], actual)
            ht = ht @ _hom(np.eye(3), doc["axes"][a]["origin_mm"]) @ _hom(r, t)
        hw = np.eye(4)
        for a in doc["workpiece_chain"]:
            k = AXES.index(a)
            r, t = motion(k, p[k], actual)
            hw = hw @ _hom(np.eye(3), doc["axes"][a]["origin_mm"]) @ _hom(r.T, -t)
        d = np.array(doc["tool"]["direction"])
        if actual:
            d = _rot(0, doc["spindle"]["tilt_a_rad"]) @ _rot(1, doc["spindle"]["tilt_b_rad"]) @ d
        tip = np.append(np.array(doc["tool"]["nose_mm"]) + doc["tool"]["length_mm"] * d, 1.0)
        return (np.linalg.inv(hw) @ ht @ tip)[:3]

    return W(True) - W(False)


@pytest.mark.parametrize("scale", [1.0, 100.0])
def test_exact_synthesis_equals_direct_4x4_composition(scale):
    """Random chains and random cubic error polynomials; scale 100 gives 5 mm / 1e-2 rad errors
    where second-order terms are large, so dropped terms would show."""
    rng = np.random.default_rng(2026)
    for _ in range(15):
        m, doc = _random_machine(rng, scale)
        pts = rng.uniform(-400, 400, (8, 3))
        got = ns.machine.tip_error(m, pts)
        ref = np.array([_reference(doc, p) for p in pts])
        assert np.abs(got - ref).max() <= 1e-10 * (1 + np.abs(ref).max())


def test_first_order_differs_from_exact_by_second_order():
    rng = np.random.default_rng(7)
    pts = rng.uniform(-400, 400, (50, 3))
    diffs = []
    for s in (4.0, 8.0, 16.0):
        m, _ = _random_machine(np.random.default_rng(11), s)
        diffs.append(ns.machine.compare_orders(m, pts)["max_difference_mm"])
    assert diffs[1] / diffs[0] == pytest.approx(4.0, rel=0.05)
    assert diffs[2] / diffs[1] == pytest.approx(4.0, rel=0.05)


def test_positioning_error_moves_only_its_axis():
    for tool, work in ((["X", "Y", "Z"], []), ([], ["X", "Y", "Z"]), (["Z"], ["Y", "X"])):
        for a in AXES:
            doc = {"tool_chain": tool, "workpiece_chain": work, "tool": {"length_mm": 100.0},
                   "axes": {a: {"polynomials": {f"E{a}{a}_mm": [0.001, 2e-5]}, "origin_mm": [10, 20, 30]}}}
            m = ns.machine.machine_from_dict(doc)
            p = np.array([[150.0, -80.0, 240.0]])
            e = ns.machine.tip_error(m, p)[0]
            k = AXES.index(a)
            expected = np.zeros(3)
            expected[k] = 0.001 + 2e-5 * p[0, k]
            np.testing.assert_allclose(e, expected, atol=1e-15)


def test_pitch_error_gives_abbe_error_proportional_to_offset():
    """Tool-side X with pitch EBX = ε: the tip L below the carriage moves by −ε·L along X (Abbe)."""
    eps = 3e-5
    errs = []
    for L in (50.0, 100.0, 200.0):
        doc = {"tool_chain": ["X"], "workpiece_chain": ["Y", "Z"], "tool": {"length_mm": L},
               "axes": {"X": {"polynomials": {"EBX_rad": [eps]}}}}
        e = ns.machine.tip_error(ns.machine.machine_from_dict(doc), [[100.0, 0.0, 0.0]], order="first")[0]
        errs.append(e[0])
        assert abs(e[1]) < 1e-18 and abs(e[2]) < 1e-18
    np.testing.assert_allclose(errs, [-eps * 50, -eps * 100, -eps * 200], rtol=1e-12)


def test_yang_kweon_eq9_terms():
    """Single components of the Yang & Kweon HMC give the terms of eq. (9) and (11) (first order):
    ΔW_x ∋ (T_z + L + Oxy_z)·ε_yx, (T_z + L)·ε_yy, −(T_y + Oxy_y + y)·ε_zx, −y·S_xy and
    −(T_z + L + Ozx_z + Oxy_z − z_table)·ε_yz; ΔW_z ∋ −(T_x + Oxy_x)·ε_yx. The paper's table (Z) is
    on the workpiece side: ε_yz = −EBZ, z_table = −z (docs/machine.md)."""
    import tomllib

    doc = tomllib.loads(HMC.read_text())
    T = np.array(doc["tool"]["nose_mm"])
    L = doc["tool"]["length_mm"]
    Oxy = np.array(doc["axes"]["Y"]["origin_mm"])
    Ozx = np.array(doc["axes"]["X"]["origin_mm"])
    p = np.array([[300.0, 200.0, 150.0]])
    x, y, z = p[0]
    eps = 1e-5

    def only(axis, key, value, square=None):
        d = {k: v for k, v in doc.items() if k not in ("axes", "spindle", "squareness")}
        d["axes"] = {a: {"origin_mm": doc["axes"][a]["origin_mm"]} for a in AXES}
        if axis:
            d["axes"][axis]["polynomials"] = {key: [value]}
        if square:
            d["squareness"] = {square: value}
        return ns.machine.tip_error(ns.machine.machine_from_dict(d), p, order="first")[0]

    assert only("X", "EBX_rad", eps)[0] == pytest.approx((T[2] + L + Oxy[2]) * eps, rel=1e-12)
    assert only("X", "EBX_rad", eps)[2] == pytest.approx(-(T[0] + Oxy[0]) * eps, abs=1e-15)
    assert only("Y", "EBY_rad", eps)[0] == pytest.approx((T[2] + L) * eps, rel=1e-12)
    assert only("X", "ECX_rad", eps)[0] == pytest.approx(-(T[1] + Oxy[1] + y) * eps, rel=1e-12)
    assert only(None, None, eps, "EC0Y_rad")[0] == pytest.approx(-y * eps, rel=1e-12)
    eps_yz = -eps  # paper's table pitch for EBZ = eps
    z_table = -z
    assert only("Z", "EBZ_rad", eps)[0] == pytest.approx(
        -(T[2] + L + Ozx[2] + Oxy[2] - z_table) * eps_yz, rel=1e-12)


def test_tables_interpolate_linearly_and_respect_policy(tmp_path):
    csv = tmp_path / "x.csv"
    csv.write_text("# comment\nX_mm,EXX_um,EBX_arcsec\n0,0,0\n100,10,1\n200,-10,2\n")
    doc = {"tool_chain": ["X"], "workpiece_chain": ["Y", "Z"],
           "axes": {"X": {"table": "x.csv", "out_of_range": "error"}}}
    m = ns.machine.machine_from_dict(doc, tmp_path)
    e = ns.machine.tip_error(m, [[50.0, 0, 0], [150.0, 0, 0]])
    np.testing.assert_allclose(e[:, 0], [0.005, 0.0], atol=1e-15)
    f = m.axes[0].errors[4]
    assert f(150.0) == pytest.approx(1.5 * np.pi / 648000)
    with pytest.raises(ValueError, match="EXX position = 250.*outside the table range"):
        ns.machine.tip_error(m, [[250.0, 0, 0]])
    doc["axes"]["X"]["out_of_range"] = "clamp"
    m = ns.machine.machine_from_dict(doc, tmp_path)
    assert ns.machine.tip_error(m, [[250.0, 0, 0]])[0, 0] == pytest.approx(-0.01)


def test_error_map_and_plots():
    m = ns.machine.load_machine(HMC)
    emap = ns.machine.grid_error_map(m, (4, 3, 2))
    assert emap.points.shape == (24, 3) and emap.shape == (2, 3, 4)
    s = emap.summary()
    assert 0 < s["min_um"] < s["max_um"]
    assert s["max_exact_minus_first_order_um"] < 1e-2 * s["max_um"]
    from matplotlib.figure import Figure

    assert isinstance(ns.machine.plot_error_map(emap), Figure)
    surf = emap.points.reshape(6, 4, 3)
    assert isinstance(ns.machine.plot_surface_error(surf, emap.errors.reshape(6, 4, 3)), Figure)
    with pytest.raises(ValueError, match="points shape"):
        ns.machine.tip_error(m, np.zeros((3, 2)))
    with pytest.raises(ValueError, match="finite"):
        ns.machine.tip_error(m, [[np.nan, 0, 0]])


def test_yang_kweon_symbol_map_is_one_to_one():
    names = [v[0] for v in ns.machine.SEEDS003_SYMBOLS.values()]
    assert len(names) == len(set(names)) == 9 + 9 + 3 + 2
