"""Text input (issue 42 items 5 and 6): a non-UTF-8 byte in a TOML/CSV/JSON input, a TOML or JSON nested
1000 deep, or a NURBS file of the wrong shape is refused with one line naming the file (and line); a
G-code program whose comments are Latin-1 is read and its comments kept byte for byte by every writer."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from netshape.cli import main

REPO = Path(__file__).resolve().parents[2]
DEMO = REPO / "examples" / "demo"
MACHINES = REPO / "examples" / "machines"
LATIN1 = "(Fräser 6 mm, Schlichten)".encode("latin-1")


def _one_line(capsys, argv, *needles) -> str:
    code = main(argv)
    cap = capsys.readouterr()
    assert code == 2, (code, cap.err)
    lines = cap.err.splitlines()
    assert len(lines) == 1 and "Traceback" not in cap.err, cap.err
    for n in needles:
        assert n in lines[0], (n, lines[0])
    return lines[0]


def _demo(tmp_path) -> Path:
    d = tmp_path / "demo"
    shutil.copytree(DEMO, d)
    return d


def _latin1_line(path: Path, line_no: int) -> None:
    """Append a Latin-1 comment to line ``line_no`` (1-based) of a TOML/CSV file."""
    lines = path.read_bytes().split(b"\n")
    lines[line_no - 1] += b"  # Fr\xe4ser"
    path.write_bytes(b"\n".join(lines))


@pytest.mark.parametrize("name", ["job.toml", "tool.toml", "machine.toml", "rougher.toml"])
def test_latin1_byte_in_a_job_toml_names_file_and_line(tmp_path, capsys, name):
    d = _demo(tmp_path)
    _latin1_line(d / name, 2)
    _one_line(capsys, ["run", str(d / "job.toml"), "--out", str(tmp_path / "o"), "--quiet"],
              f"{name}:2: not UTF-8 text (byte 0xE4")
    assert not (tmp_path / "o").exists()


def test_latin1_byte_in_machine_and_error_table(tmp_path, capsys):
    m = tmp_path / "m"
    shutil.copytree(MACHINES, m)
    _latin1_line(m / "vmc.toml", 3)
    _one_line(capsys, ["volumetric", "map", str(m / "vmc.toml")], "vmc.toml:3: not UTF-8 text")
    shutil.copy(MACHINES / "vmc.toml", m / "vmc.toml")
    csv = m / "vmc_x_errors.csv"
    data = csv.read_bytes().split(b"\n")
    data.insert(1, b"# gemessen mit Laser, Ma\xdfe in mm")
    csv.write_bytes(b"\n".join(data))
    _one_line(capsys, ["volumetric", "map", str(m / "vmc.toml")], "vmc_x_errors.csv:2: not UTF-8 text (byte 0xDF")


def test_deep_toml_and_json_refused(tmp_path, capsys):
    d = _demo(tmp_path)
    (d / "tool.toml").write_bytes((d / "tool.toml").read_bytes() + b"\nx = " + b"[" * 1000 + b"]" * 1000 + b"\n")
    _one_line(capsys, ["run", str(d / "job.toml"), "--out", str(tmp_path / "o"), "--quiet"],
              "tool.toml", "nested more than 64 levels deep")
    deep = tmp_path / "deep.toml"
    deep.write_text("a = " + "{b = " * 1000 + "1" + "}" * 1000 + "\n")
    _one_line(capsys, ["plan", str(DEMO / "part.ngc"), "--limits", str(deep), "--rule", "vector",
                       "--json", str(tmp_path / "p.json")],
              "deep.toml:1: nested more than 64 levels deep")
    surf = tmp_path / "s.json"
    surf.write_text("[" * 1000 + "]" * 1000)
    _one_line(capsys, ["posture", "plan", "--surface", str(surf), "--obstacles", "o.stl", "--tool", "t.toml",
                       "--out", str(tmp_path / "p")], "s.json:1: nested more than 64 levels deep")


@pytest.mark.parametrize("doc, needle", [
    ([1, 2, 3], "document = list: must be an object"),
    ({"type": "surface", "degree_u": None, "degree_v": 2, "knots_u": [], "knots_v": [], "control_points": []},
     "degree_u = None: must be an integer"),
    ({"type": "surface", "degree_u": 2, "degree_v": 2, "knots_u": [0, "a"], "knots_v": [], "control_points": []},
     "knots_u = [0, 'a']: must be a list of finite numbers"),
    ({"type": "surface", "degree_u": 1, "degree_v": 1, "knots_u": [0, 0, 1, 1], "knots_v": [0, 0, 1, 1],
      "control_points": [[0, 0, None]] * 4}, "control_points"),
])
def test_surface_json_of_the_wrong_shape(tmp_path, capsys, doc, needle):
    surf = tmp_path / "s.json"
    surf.write_text(json.dumps(doc))
    _one_line(capsys, ["posture", "plan", "--surface", str(surf), "--obstacles", "o.stl", "--tool", "t.toml",
                       "--out", str(tmp_path / "p")], f"{surf}: {needle}")


def test_latin1_in_surface_json(tmp_path, capsys):
    surf = tmp_path / "s.json"
    surf.write_bytes(b'{\n"type": "surface", "name": "Fl\xe4che"}')
    _one_line(capsys, ["posture", "plan", "--surface", str(surf), "--obstacles", "o.stl", "--tool", "t.toml",
                       "--out", str(tmp_path / "p")], "s.json:2: not UTF-8 text (byte 0xE4")


# --- G-code comments in Latin-1 -------------------------------------------------------------------

def _latin1_program(src: Path, dst: Path) -> Path:
    """``src`` with a Latin-1 comment line after its first line."""
    lines = src.read_bytes().split(b"\n")
    lines.insert(1, LATIN1)
    dst.write_bytes(b"\n".join(lines))
    return dst


def test_latin1_comment_through_info_and_plan(tmp_path, capsys):
    prog = _latin1_program(DEMO / "part.ngc", tmp_path / "part.ngc")
    assert main(["info", str(prog), "--json"]) == 0
    assert main(["plan", str(prog), "--vmax", "250", "--amax", "3000", "--rule", "vector",
                 "--json", str(tmp_path / "p.json")]) == 0
    from netshape.toolpath import gcode_encoding, read_gcode

    assert gcode_encoding(prog) == "latin-1" and gcode_encoding(DEMO / "part.ngc") == "utf-8"
    texts = [c.text for c in read_gcode(prog).commands]
    assert any("Fräser" in t for t in texts)


def test_latin1_comment_kept_by_volumetric_compensate(tmp_path):
    prog = _latin1_program(DEMO / "part.ngc", tmp_path / "part.ngc")
    out = tmp_path / "comp.ngc"
    (tmp_path / "o.var").write_text("5221 -150\n5222 80\n5223 -300\n")  # the demo job's G54 and tool length
    (tmp_path / "t.tbl").write_text("T1 P1 Z100\n")
    offsets = ["--var", str(tmp_path / "o.var"), "--tool-table", str(tmp_path / "t.tbl")]
    assert main(["volumetric", "compensate", str(prog), "--machine", str(DEMO / "machine.toml"), "-o", str(out),
                 *offsets]) == 0
    assert LATIN1 in out.read_bytes()
    # a UTF-8 program stays UTF-8
    utf = tmp_path / "utf.ngc"
    utf.write_bytes(prog.read_bytes().replace(LATIN1, LATIN1.decode("latin-1").encode("utf-8")))
    assert main(["volumetric", "compensate", str(utf), "--machine", str(DEMO / "machine.toml"), "-o", str(out),
                 *offsets]) == 0
    assert LATIN1.decode("latin-1").encode("utf-8") in out.read_bytes()


CONTOUR = b"""(contour)
G21 G90 G17
G0 X-5 Y0 Z5
G0 Z-2
G1 X0 Y0 F600
G1 X30 Y0
G1 X30 Y20
M2
"""


def test_latin1_comment_kept_by_deflection_compensate(tmp_path):
    prog = tmp_path / "c.nc"
    prog.write_bytes(CONTOUR.replace(b"(contour)", b"(contour)\n" + LATIN1))
    stock = tmp_path / "stock.toml"
    stock.write_text("min_mm = [-10.0, -10.0, -10.0]\nmax_mm = [40.0, 5.0, 0.0]\nspacing_mm = 0.5\n")
    out = tmp_path / "comp.nc"
    code = main(["deflection", "compensate", str(prog), "--tool", str(DEMO / "tool.toml"), "--stock", str(stock),
                 "--coefficients", "leekunhwee_flat_slot", "--rpm", "8000", "-o", str(out), "--tolerance", "0.01"])
    assert code == 0
    assert LATIN1 in out.read_bytes()


def test_latin1_comment_kept_by_run(tmp_path):
    from .test_cli_outputs import quick_job

    job = quick_job(tmp_path)
    _latin1_program(job.parent / "part.ngc", job.parent / "part.ngc")
    out = tmp_path / "o"
    assert main(["run", str(job), "--out", str(out), "--quiet"]) == 0
    assert LATIN1 in (out / "part_compensated.ngc").read_bytes()


def test_latin1_byte_in_a_deflection_stock_and_heights_csv(tmp_path, capsys):
    stock = tmp_path / "stock.toml"
    stock.write_bytes(b"# Rohteil Alu, 60 x 50 Ma\xdfe\nmin_mm = [-10.0, -10.0, -10.0]\nmax_mm = [40.0, 5.0, 0.0]\n"
                      b"spacing_mm = 0.5\n")
    _one_line(capsys, ["deflection", "predict", str(DEMO / "part.ngc"), "--tool", str(DEMO / "tool.toml"),
                       "--stock", str(stock), "--coefficients", "leekunhwee_flat_slot", "--rpm", "8000"],
              "stock.toml:1: not UTF-8 text (byte 0xDF")
    from .test_cli_outputs import quick_job

    job = quick_job(tmp_path)
    (job.parent / "h.csv").write_bytes(b"# H\xf6hen\n" + b"\n".join([b"0,0,0"] * 3) + b"\n")
    job.write_text(job.read_text().replace("\nspacing_mm = 1.0", '\nheights = "h.csv"'))
    _one_line(capsys, ["run", str(job), "--out", str(tmp_path / "o"), "--quiet"], "h.csv:1: not UTF-8 text (byte 0xF6")


def test_controller_files_read_latin1_labels_and_refuse_bytes_in_numbers(tmp_path):
    """Tool tables, .var files and DynoWare exports hold their comments and labels in the machine's
    code page: Latin-1 text is read (nothing replaced), a stray byte inside a number is refused naming
    the line."""
    import netshape.force as nf
    import netshape.toolpath as tpm

    tbl = tmp_path / "tool.tbl"
    tbl.write_bytes("T1 P1 Z10.5 ;Fräser Ø10\nT2 P2 Z35.25 ;Bohrer\n".encode("latin-1"))
    assert tpm.read_tool_table(tbl) == {1: 10.5, 2: 35.25}
    tbl.write_bytes("T1 P1 Z10.5\nT2 P2 Z3\xe45.25\n".encode("latin-1"))
    with pytest.raises(ValueError, match=r"tool.tbl:2: word 'Z3ä5.25'"):
        tpm.read_tool_table(tbl)
    var = tmp_path / "m.var"
    var.write_bytes("5221 10.5 ; Nullpunkt Spannvorrichtung für Teil\n5222 -2\n".encode("latin-1"))
    assert list(tpm.read_var_file(var)[0]) == [10.5, -2.0, 0.0]
    dyn = tmp_path / "d.csv"
    dyn.write_bytes("DynoWare,Version 2\nKommentar:,Fräsen µ-Test\nTime,Fx,Fy,Fz\ns,N,N,N\n0,1,2,3\n"
                    "0.5,1,2,3\n".encode("latin-1"))
    r = nf.read_dynoware(dyn, to_cutter=np.eye(3))
    assert r.metadata["Kommentar"] == "Fräsen µ-Test"
    dyn.write_bytes("Time,Fx,Fy,Fz\ns,N,N,N\n0,1,2,3\n0.5,1,\xb52,3\n".encode("latin-1"))
    with pytest.raises(ValueError, match=":4"):
        nf.read_dynoware(dyn)
