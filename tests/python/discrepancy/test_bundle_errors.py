"""Malformed bundles: one clear error naming the file and the field; the CLI exits 2 with one line
and writes nothing."""

from __future__ import annotations

import json

import pytest

import netshape.discrepancy as nd
from netshape.cli import main

from generators import force_bundle, replace_once, volumetric_bundle


@pytest.fixture()
def fb(tmp_path):
    return force_bundle(tmp_path / "b", revolutions=2, per_rev=60, conditions=[("slot", 10.0, 0.05)])


@pytest.mark.parametrize(
    "edit, words",
    [
        (("manifest.toml", "spindle_rpm = 6000.0\n", ""), ["manifest.toml", "experiment", "spindle_rpm"]),
        (("manifest.toml", 'mode = "slot"', 'mode = "sideways"'), ["manifest.toml", "mode", "sideways"]),
        (("manifest.toml", "Ktc_N_per_mm2 = 900.0\n", ""), ["manifest.toml", "[model]", "Ktc_N_per_mm2"]),
        (("manifest.toml", "Ktc_N_per_mm2", "Ktc"), ["manifest.toml", "[model]", "Ktc"]),
        (("manifest.toml", "flutes = 2", "flutes = 0"), ["manifest.toml", "[tool]", "flutes"]),
        (
            ("manifest.toml", 'kind = "cutting_force"', 'kind = "acoustic"'),
            ["manifest.toml", "kind", "acoustic"],
        ),
        (
            ("manifest.toml", 'kind = "cutting_force"', 'kind = "wall_error"'),
            ["manifest.toml", "[tool]", "stick_out_mm"],
        ),
        (
            ("manifest.toml", "feed_per_tooth_mm = 0.05", "feed_per_tooth_mm = -0.05"),
            ["feed_per_tooth_mm", "-0.05"],
        ),
        (("manifest.toml", "axial_depth_mm = 3.0", 'axial_depth_mm = "3"'), ["axial_depth_mm"]),
        (("e1.csv", "angle_deg,fx_N", "angle_deg,fx_kN"), ["e1.csv", "fx_kN"]),
        (("e1.csv", "angle_deg,", "angle_rad,"), ["e1.csv", "angle_rad"]),
        (("e1.csv", "angle_deg,fx_N,fy_N,fz_N", "fx_N,fy_N,fz_N,fz_N"), ["e1.csv"]),
    ],
)
def test_malformed_force_bundle(fb, edit, words):
    replace_once(fb / edit[0], edit[1], edit[2])
    with pytest.raises(ValueError) as exc:
        nd.load_bundle(fb)
    for w in words:
        assert w in str(exc.value), (w, str(exc.value))


def test_non_finite_value_names_line_and_column(fb):
    lines = (fb / "e1.csv").read_text().splitlines()
    parts = lines[5].split(",")
    parts[2] = "nan"
    lines[5] = ",".join(parts)
    (fb / "e1.csv").write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=r"e1.csv: line 6, column 'fy_N': 'nan' is not finite"):
        nd.load_bundle(fb)


def test_missing_files(fb, tmp_path):
    (fb / "e1.csv").unlink()
    with pytest.raises(FileNotFoundError, match="e1.csv"):
        nd.load_bundle(fb)
    with pytest.raises(FileNotFoundError, match="manifest.toml"):
        nd.load_bundle(tmp_path / "nothing")


def test_malformed_volumetric_bundle(tmp_path):
    vb = volumetric_bundle(tmp_path / "v", experiments=1)
    replace_once(vb / "manifest.toml", 'tool_side = ["Z"]', 'tool_side = ["Z", "X"]')
    with pytest.raises(ValueError, match=r"manifest.toml: \[machine\].*every axis X, Y, Z exactly once"):
        nd.load_bundle(vb)
    vb = volumetric_bundle(tmp_path / "w", experiments=1)
    replace_once(vb / "manifest.toml", "EXX = ", "EXQ = ")
    with pytest.raises(ValueError, match=r"\[model\]: unknown key 'EXQ'"):
        nd.load_bundle(vb)
    vb = volumetric_bundle(tmp_path / "x", experiments=1)
    text = (vb / "v1.csv").read_text().splitlines()
    text[3] = text[3].rsplit(",", 1)[0] + ",0"
    (vb / "v1.csv").write_text("\n".join(text) + "\n")
    with pytest.raises(ValueError, match=r"v1.csv: line 4, column 'direction': 0.0 must be \+1 or -1"):
        nd.load_bundle(vb)


def test_cli_bad_bundle_exits_2_and_writes_nothing(fb, tmp_path, capsys):
    replace_once(fb / "manifest.toml", "spindle_rpm = 6000.0\n", "")
    out = tmp_path / "d.json"
    assert main(["diagnose", str(fb), "--json", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "spindle_rpm" in err[0] and "manifest.toml" in err[0]
    assert not out.exists()


def test_cli_end_to_end_with_report(tmp_path, capsys):
    vb = volumetric_bundle(tmp_path / "v", squareness={"EC0Y": 30.0})
    out, rep = tmp_path / "d.json", tmp_path / "report"
    assert main(["diagnose", str(vb), "--json", str(out), "--report", str(rep)]) == 0
    d = json.loads(out.read_text())
    assert list(d)[:8] == [  # the keys before issue 37, in order; its keys follow
        "kind",
        "effect",
        "parameters",
        "effects",
        "rms_before",
        "rms_after",
        "noise_estimate",
        "candidates",
    ]
    assert {"noise_source", "noise_assumption", "unexplained"} <= set(d)
    assert d["kind"] == "volumetric_error" and d["effect"] == "squareness"
    assert abs(d["parameters"]["EC0Y_urad"] - 30.0) < 1.0
    html = (rep / "index.html").read_text()
    for png in ("residuals.png", "squareness.png"):
        assert (rep / png).stat().st_size > 1000 and f'src="{png}"' in html
    assert "squareness" in capsys.readouterr().out


def test_user_registered_effect(tmp_path):
    """A user effect (the probe shifted along X after the first experiment; an offset common to all
    points would be the registered frame's translation) is fitted, chosen and reported."""
    import dataclasses

    import numpy as np

    class ProbeOffset(nd.Effect):
        name, kind, parameters, covariate = "probe_offset", "volumetric_error", ("dx_um",), "position"

        def starts(self, problem, spec):
            return [np.zeros(1)]

        def apply(self, problem, spec, x):
            def add(exp, pts, v=float(x[0]), first=problem.experiments[0].file):
                out = np.zeros((len(pts), 3))
                out[:, 0] = v * 1e-3 if exp.file != first else 0.0
                return out

            return dataclasses.replace(spec, additive=spec.additive + (add,))

        def parameters_of(self, x):
            return {"dx_um": float(x[0])}

    vb = volumetric_bundle(tmp_path / "v")
    for name in ("v2.csv",):
        data = np.loadtxt(vb / name, delimiter=",", skiprows=1)
        data[:, 3] += 0.004
        np.savetxt(
            vb / name,
            data,
            delimiter=",",
            header="x_mm,y_mm,z_mm,ex_mm,ey_mm,ez_mm,t_s,direction",
            comments="",
        )
    nd.register_effect(ProbeOffset())
    try:
        with pytest.raises(ValueError, match="already in the volumetric_error catalogue"):
            nd.register_effect(ProbeOffset())
        d = nd.diagnose(vb)
        assert d.effect == "probe_offset" and abs(d.parameters["dx_um"] - 4.0) < 0.2
    finally:
        nd.unregister_effect("volumetric_error", "probe_offset")
    assert "probe_offset" not in nd.catalogue("volumetric_error")


def test_ball_end_mill_is_refused_by_the_force_workflow(fb):
    """The force catalogue extends the flat linear edge-force model: a ball end mill bundle loads but
    diagnose says why it cannot be diagnosed."""
    replace_once(fb / "manifest.toml", 'type = "flat"', 'type = "ball"')
    b = nd.load_bundle(fb)
    with pytest.raises(ValueError, match=r"\[tool\] type = 'ball'.*flat end mills"):
        nd.diagnose(b)


def test_force_angles_that_do_not_advance(fb, capsys):
    """A force CSV whose angle_deg column holds one value (issue 42 item 5: was a ZeroDivisionError)."""
    path = fb / "e1.csv"
    lines = path.read_text().splitlines()
    path.write_text("\n".join([lines[0]] + ["10," + ln.split(",", 1)[1] for ln in lines[1:]]) + "\n")
    with pytest.raises(ValueError, match=r"e1.csv: column 'angle_deg': the angle must advance"):
        nd.load_bundle(fb)
    assert main(["diagnose", str(fb), "--json", str(fb / "d.json")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "angle_deg" in err and "Traceback" not in err
    assert not (fb / "d.json").exists()


def test_latin1_byte_in_a_force_csv(fb, capsys):
    path = fb / "e1.csv"
    path.write_bytes(path.read_bytes().replace(b"\n", b"\n# Kraftmessung, Fr\xe4ser 2\n", 1))
    assert main(["diagnose", str(fb), "--json", str(fb / "d.json")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "e1.csv:2: not UTF-8 text (byte 0xE4" in err
