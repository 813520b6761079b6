"""Fuzz every `netshape` entry point with seeded mutations of small valid inputs (issue 42, "What to
build" 7). Each case runs the command in this process and asserts what the CLI promises:

- exit 0, or 2 with one line ``netshape COMMAND: error: ...`` (batch: 1 when a run of the table failed,
  its documented code, with the reason in batch.csv);
- no traceback on stderr;
- every JSON file written is valid JSON without NaN or Infinity;
- after a refusal (exit 2) the output paths hold nothing new.

Mutation classes: TOML values replaced (wrong type, negative, zero, huge, non-finite, empty, table for a
value), keys deleted, duplicated or unknown, lines truncated, a Latin-1 byte, nesting 200 deep; G-code
numbers replaced, garbage words, Latin-1 comments, truncation; CSV cells replaced (text, empty, NaN,
huge), a column dropped or made constant; JSON values replaced by null, lists, strings, huge numbers,
deep nesting; numeric options replaced; output paths that are a file, a folder, under a file, a device (a FIFO).
Left out, with the issue 42 item that covers them: tiny positive spacings, steps, tolerances and feeds
(1e-3 and below: `--spacing 1e-3` or `F0.001` is unbounded work) and huge counts (`--points 100000`),
both item 4 (work bounded before it starts); huge feed scales (the G-code writer's range: item 2).
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import random
import re
import shutil
import signal
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from netshape.cli import main

REPO = Path(__file__).resolve().parents[2]
DEMO = REPO / "examples" / "demo"
SEED = 42
#: Largest time one case may take [s]: longer is unbounded work (a failure).
CASE_LIMIT_S = 20
#: NETSHAPE_FUZZ_TRACE=1 prints every case before it runs (to find one that hangs in C++).
TRACE = os.environ.get("NETSHAPE_FUZZ_TRACE") == "1"

MINI_NGC = """(netshape fuzz: a small square pocket wall)
G21 G90 G17 G94
G54
T1 M6
S8000 M3
G0 X-12 Y-12 Z5
G1 Z-2 F300
G1 X8 Y-12 F900
G3 X12 Y-8 R4
G1 X12 Y8
G1 X-12 Y8
G1 X-12 Y-12
G0 Z5
M30
"""

MINI_JOB = """name = "fuzz"
program = "mini.ngc"
tool = "tool.toml"
coefficients = "leekunhwee_flat_slot"

[stock]
min_mm = [-16.0, -16.0, -6.0]
max_mm = [16.0, 12.0, 0.0]
spacing_mm = 1.0

[offsets]
G54_mm = [-150.0, 80.0, -300.0]
tool_length_mm = 100.0

[machine]
file = "machine.toml"
error_scale = 1.0

[limits]
vmax_mm_s = 200.0
amax_mm_s2 = 2000.0
rule = "blend"
tolerance_mm = 0.01

[cutting]
step_mm = 1.0
samples_per_revolution = 24
disk_height_mm = 0.5
error_spacing_mm = 1.0

[predict]
forces = true
deflection = true
volumetric = true
feed_plan = true

[compensate]
deflection = false
volumetric = true

[report]
plots = false
zmap_stl = true
"""

STOCK = "min_mm = [-16.0, -16.0, -6.0]\nmax_mm = [16.0, 12.0, 0.0]\nspacing_mm = 1.0\n"
BALL = ('kind = "ball"\ndiameter_mm = 4.0\nflutes = 2\nhelix_deg = 30.0\nflute_length_mm = 20.0\n'
        'stick_out_mm = 40.0\nshank_diameter_mm = 4.0\nshank_length_mm = 35.0\nholder_diameter_mm = 24.0\n'
        'holder_length_mm = 80.0\n')
LIMITS = ("[limits]\nvmax_mm_s = 200.0\namax_mm_s2 = [2000.0, 2000.0, 1000.0]\n"
          "[axes.z]\nvmax_mm_s = 100.0\namax_mm_s2 = 1000.0\njmax_mm_s3 = 1.0e5\n")

# values a mutation puts in place of a TOML value, a G-code number, a CSV cell or an option
TOML_VALUES = ["-1", "0", "1e300", "-1e300", "nan", "inf", "-inf", '""', '"x"', "[]", "{}", "true", "[1, 2]",
               "[[1, 2], [3]]", "123456789012345678901234567890", "0.5", "3", '"Fr\xe4ser"']
GCODE_VALUES = ["0", "-1", "1e9", "1e30", "nan", "inf", "-0", "99999"]
CSV_VALUES = ["nan", "", "x", "1e300", "-1e300", "inf", "0", "1,2"]
OPTION_VALUES = ["-1", "0", "nan", "inf", "1e300", "x", "", "3", "0.5", "-0"]


class _Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise _Timeout


def _no_nan(name):
    raise ValueError(f"{name} in JSON")


def _outputs(folder: Path) -> dict:
    return {p.relative_to(folder).as_posix(): p.stat().st_size for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name != "input" and "input" not in p.relative_to(folder).parts}


def _run_case(argv: list[str], outdir: Path, label: str, *, allow_1: bool = False) -> tuple[int, str]:
    before = _outputs(outdir)
    err = io.StringIO()
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(CASE_LIMIT_S)
    try:
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()), \
                warnings.catch_warnings():
            warnings.simplefilter("ignore")  # as on the command line: warnings are notes, not errors
            code = main(argv)
    except _Timeout:
        pytest.fail(f"{label}: more than {CASE_LIMIT_S} s: {argv}")
    except BaseException as exc:  # noqa: BLE001 - anything escaping main is a traceback for the user
        pytest.fail(f"{label}: {type(exc).__name__} escaped main: {exc}: {argv}")
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    text = err.getvalue()
    ok_codes = (0, 1, 2) if allow_1 else (0, 2)
    assert code in ok_codes, f"{label}: exit {code}: {text[-800:]} {argv}"
    assert "Traceback" not in text, f"{label}: {text[-1500:]}"
    if code == 2:
        errors = [ln for ln in text.splitlines() if ": error: " in ln]
        assert len(errors) == 1 and errors[0].startswith("netshape"), f"{label}: {text[-800:]}"
        assert _outputs(outdir) == before, f"{label}: outputs after a refusal: {argv}"
    for p in outdir.rglob("*.json"):
        if "input" in p.relative_to(outdir).parts:
            continue
        try:
            json.loads(p.read_text(encoding="utf-8"), parse_constant=_no_nan)
        except ValueError as exc:
            pytest.fail(f"{label}: {p.name} is not valid JSON: {exc}")
    return code, text


# --- the inputs ---------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def base(tmp_path_factory) -> Path:
    """Small valid inputs of every command, in one folder."""
    from netshape import geometry as ng

    d = tmp_path_factory.mktemp("fuzz-base")
    (d / "mini.ngc").write_text(MINI_NGC)
    (d / "job.toml").write_text(MINI_JOB)
    for name in ("tool.toml", "machine.toml"):
        shutil.copy(DEMO / name, d / name)
    (d / "stock.toml").write_text(STOCK)
    (d / "ball.toml").write_text(BALL)
    (d / "limits.toml").write_text(LIMITS)
    (d / "o.var").write_text("5221 -150\n5222 80\n5223 -300\n")
    (d / "t.tbl").write_text("T1 P1 Z100\n")
    surf = ng.bilinear(np.array([0, 0, 0.0]), np.array([0, 20, 0.0]), np.array([-10, 0, 0.0]),
                       np.array([-10, 20, 0.0]))
    ng.save_json(surf, d / "floor.json")
    v = np.array([[9, -20, -5], [9, 40, -5], [9, 40, 30], [9, -20, 30]], float)
    ng.write_stl(d / "wall.stl", v, np.array([[0, 1, 2], [0, 2, 3]]))
    sys.path.insert(0, str(Path(__file__).parent / "discrepancy"))
    try:
        from generators import force_bundle
    finally:
        sys.path.pop(0)
    force_bundle(d / "bundle", revolutions=1, per_rev=36, conditions=[("slot", 10.0, 0.05), ("up", 5.0, 0.07)])
    return d


def _case_dir(base: Path, tmp: Path, i: int) -> tuple[Path, Path]:
    """A fresh copy of the inputs (``case/input``) and an empty output folder (``case/out``)."""
    case = tmp / f"case{i:03d}"
    shutil.copytree(base, case / "input")
    (case / "out").mkdir()
    return case / "input", case / "out"


# --- mutations ----------------------------------------------------------------------------------------

def mutate_toml(text: str, rng: random.Random) -> str:
    lines = text.split("\n")
    values = [i for i, ln in enumerate(lines) if re.match(r"^\s*[\w\".]+\s*=", ln)]
    kind = rng.choice(["value", "value", "value", "delete", "duplicate", "unknown", "truncate", "latin1", "deep",
                       "header"])
    if kind == "value" and values:
        i = rng.choice(values)
        key = lines[i].split("=", 1)[0]
        v = rng.choice(TOML_VALUES)
        lines[i] = f"{key}= {v}"
    elif kind == "delete" and values:
        del lines[rng.choice(values)]
    elif kind == "duplicate" and values:
        i = rng.choice(values)
        lines.insert(i, lines[i])
    elif kind == "unknown":
        lines.insert(rng.randrange(len(lines) + 1), "fuzz_key = 1")
    elif kind == "truncate":
        return text[:rng.randrange(len(text))]
    elif kind == "latin1":
        i = rng.randrange(len(lines))
        lines[i] += "  # Fr\udce4ser"
    elif kind == "deep":
        lines.append("deep = " + "[" * 200 + "]" * 200)
    else:
        headers = [i for i, ln in enumerate(lines) if ln.startswith("[")]
        if headers:
            lines[rng.choice(headers)] = rng.choice(["[fuzz]", "[[stock]]", "[stock.x]", "["])
    return "\n".join(lines)


def mutate_gcode(text: str, rng: random.Random) -> str:
    lines = text.split("\n")
    kind = rng.choice(["number", "number", "number", "garbage", "latin1", "delete", "truncate"])
    if kind == "number":
        i = rng.randrange(len(lines))
        nums = list(re.finditer(r"(?<=[A-Z])-?\d+(\.\d+)?", lines[i]))
        if nums:
            m = rng.choice(nums)
            lines[i] = lines[i][:m.start()] + rng.choice(GCODE_VALUES) + lines[i][m.end():]
    elif kind == "garbage":
        lines.insert(rng.randrange(len(lines)), rng.choice(["G999", "F0", "G1 X", "G2 X1 Y1", "M98 P1", "#<x> = [1/0]",
                                                            "G1 X1 F-5", "G20", "G43 H99", "(unclosed", "G0 Z1e400"]))
    elif kind == "latin1":
        lines.insert(rng.randrange(len(lines)), "(Fr\udce4ser \udcb0 gr\udcfcn)")
    elif kind == "delete":
        del lines[rng.randrange(len(lines))]
    else:
        return text[:rng.randrange(len(text))]
    return "\n".join(lines)


def mutate_csv(text: str, rng: random.Random) -> str:
    rows = [r.split(",") for r in text.split("\n")]
    data = [i for i, r in enumerate(rows) if i > 0 and len(r) > 1]
    kind = rng.choice(["cell", "cell", "cell", "drop", "constant", "latin1", "truncate"])
    if kind == "cell" and data:
        r = rng.choice(data)
        rows[r][rng.randrange(len(rows[r]))] = rng.choice(CSV_VALUES)
    elif kind == "drop":
        c = rng.randrange(len(rows[0]))
        rows = [r[:c] + r[c + 1:] if len(r) > c else r for r in rows]
    elif kind == "constant" and data:
        c = rng.randrange(len(rows[0]))
        for r in data:
            rows[r][c] = "10"
    elif kind == "latin1":
        rows.insert(1, ["# Kraft in N, Fr\udce4ser"])
    else:
        return text[:rng.randrange(len(text))]
    return "\n".join(",".join(r) for r in rows)


def mutate_json(text: str, rng: random.Random) -> str:
    doc = json.loads(text)
    kind = rng.choice(["value", "value", "value", "root", "deep", "latin1", "truncate"])
    if kind == "value":
        key = rng.choice(list(doc))
        doc[key] = rng.choice([None, [], "x", -1, 1e300, {}, [[0, 0]], True, 0])
    elif kind == "root":
        return rng.choice(["[]", "[1, 2, 3]", "null", "1", '"surface"'])
    elif kind == "deep":
        return "[" * 1000 + "]" * 1000
    elif kind == "latin1":
        doc["name"] = "Fl\udce4che"
    else:
        return text[:rng.randrange(len(text))]
    return json.dumps(doc)


def _write(path: Path, text: str) -> None:
    path.write_bytes(text.encode("utf-8", "surrogateescape"))  # \udcXX: the raw (Latin-1) byte XX


def mutate_file(path: Path, rng: random.Random) -> None:
    text = path.read_text(encoding="utf-8")
    fn = {".toml": mutate_toml, ".ngc": mutate_gcode, ".csv": mutate_csv, ".json": mutate_json}[path.suffix]
    _write(path, fn(text, rng))


def mutate_option(argv: list[str], rng: random.Random, numeric: list[str]) -> list[str] | None:
    opts = [i for i, a in enumerate(argv) if a in numeric and i + 1 < len(argv)]
    if not opts:
        return None
    i = rng.choice(opts)
    v = rng.choice(OPTION_VALUES)
    out = list(argv)
    out[i + 1] = v
    return out


def bad_output(argv: list[str], option: str, inp: Path, rng: random.Random, folder: bool) -> list[str]:
    afile = inp / "mini.ngc"
    device = inp / "device"  # a FIFO standing in for /dev/null (a regression must not replace the real one)
    if not device.exists():
        os.mkfifo(device)
    choices = [str(afile), str(afile / "x"), str(device)] if folder else [str(inp), str(afile / "x"), str(device)]
    out = list(argv)
    out[out.index(option) + 1] = rng.choice(choices)
    return out


# --- the entry points ---------------------------------------------------------------------------------

def _entry_points(inp: Path, out: Path) -> dict:
    """name → (argv, files one may mutate, numeric options, output options (file), output options (folder))."""
    ngc = str(inp / "mini.ngc")
    offsets = ["--var", str(inp / "o.var"), "--tool-table", str(inp / "t.tbl")]
    common = ["--tool", str(inp / "tool.toml"), "--stock", str(inp / "stock.toml"), "--coefficients",
              "leekunhwee_flat_slot", "--rpm", "8000", "--spacing", "1.0"]
    return {
        "info": (["info", ngc, "--json"], ["mini.ngc"], [], [], []),
        "forces": (["forces", "--diameter", "10", "--flutes", "2", "--rpm", "6000", "--feed-per-tooth", "0.1",
                    "--ap", "3", "--coefficient-set", "leekunhwee_flat_slot", "--samples", "36",
                    "--csv", str(out / "f.csv")], [], ["--diameter", "--flutes", "--rpm", "--feed-per-tooth", "--ap",
                                                       "--samples"], ["--csv"], []),
        "deflection wall": (["deflection", "wall", "--tool", str(inp / "tool.toml"), "--rpm", "8000",
                             "--feed-per-tooth", "0.05", "--ap", "2", "--ae", "1", "--coefficients",
                             "leekunhwee_flat_slot", "--levels", "11", "--json", str(out / "w.json")],
                            ["tool.toml"], ["--rpm", "--feed-per-tooth", "--ap", "--ae", "--levels"], ["--json"], []),
        "deflection predict": (["deflection", "predict", ngc, *common, "--json", str(out / "p.json")],
                               ["mini.ngc", "tool.toml", "stock.toml"], ["--rpm", "--spacing"], ["--json"], []),
        "deflection compensate": (["deflection", "compensate", ngc, *common, "--tolerance", "0.01",
                                   "-o", str(out / "c.ngc"), "--json", str(out / "c.json")],
                                  ["mini.ngc", "tool.toml", "stock.toml"], ["--rpm", "--tolerance", "--max-iterations"],
                                  ["-o", "--json"], []),
        "feeds": (["feeds", ngc, "--tool", str(inp / "tool.toml"), "--stock", str(inp / "stock.toml"),
                   "--coefficients", "leekunhwee_flat_slot", "--max-force", "400", "--max-wall-error", "0.05",
                   "--max-feed", "3000", "--vmax", "200", "--amax", "2000", "--step", "1.0",
                   "--samples", "24", "--disk-height", "0.5", "--var", str(inp / "o.var"),
                   "-o", str(out / "feeds.ngc"),
                   "--json", str(out / "feeds.json")],
                  ["mini.ngc", "tool.toml", "stock.toml"],
                  ["--max-force", "--max-wall-error", "--max-feed", "--vmax", "--amax", "--step",
                   "--samples"],
                  ["-o", "--json"], []),
        "volumetric map": (["volumetric", "map", str(inp / "machine.toml"), "--grid", "3,3,3",
                            "--json", str(out / "m.json")], ["machine.toml"], [], ["--json"], []),
        "volumetric compensate": (["volumetric", "compensate", ngc, "--machine", str(inp / "machine.toml"),
                                   *offsets, "-o", str(out / "v.ngc"), "--json", str(out / "v.json")],
                                  ["mini.ngc", "machine.toml"], ["--chord-tolerance"], ["-o", "--json"], []),
        "plan": (["plan", ngc, "--limits", str(inp / "limits.toml"), "--rule", "blend", "--tolerance", "0.01",
                  "--json", str(out / "plan.json"), "--samples", str(out / "s.csv")],
                 ["mini.ngc", "limits.toml"], ["--tolerance", "--feed-scale"], ["--json", "--samples"], []),
        "posture plan": (["posture", "plan", "--surface", str(inp / "floor.json"), "--obstacles",
                          str(inp / "wall.stl"), "--tool", str(inp / "ball.toml"), "--points", "6",
                          "--out", str(out / "posture")], ["floor.json", "ball.toml"],
                         ["--points", "--clearance", "--passes"], [], ["--out"]),
        "diagnose": (["diagnose", str(inp / "bundle"), "--json", str(out / "d.json")],
                     ["bundle/manifest.toml", "bundle/e1.csv", "bundle/e2.csv"], [], ["--json"], ["--report"]),
        "run": (["run", str(inp / "job.toml"), "--out", str(out / "run"), "--quiet"],
                ["job.toml", "mini.ngc", "tool.toml", "machine.toml"], [], [], ["--out"]),
        "batch": (["batch", str(inp / "job.toml"), "--scheduler", "none", "--out", str(out / "batch"), "--quiet"],
                  ["job.toml"], [], [], ["--out"]),
        "demo": (["demo", "--out", str(out / "demo"), "--quiet"], [], [], [], ["--out"]),
    }


#: mutations per entry point (a few hundred in all)
COUNTS = {"info": 30, "forces": 30, "deflection wall": 25, "deflection predict": 25, "deflection compensate": 20,
          "feeds": 25,
          "volumetric map": 25, "volumetric compensate": 25, "plan": 35, "posture plan": 30, "diagnose": 15,
          "run": 50, "batch": 12, "demo": 4}


def test_the_unmutated_inputs_run(base, tmp_path):
    """Each entry point's command as the fuzz starts from it exits 0 (else its mutations test nothing)."""
    for entry in COUNTS:
        if entry == "demo":
            continue
        inp, out = _case_dir(base, tmp_path, len(entry))
        argv = _entry_points(inp, out)[entry][0]
        import time
        t0 = time.time()
        code, err = _run_case(argv, out, f"{entry} (unmutated)")
        if TRACE:
            print(entry, round(time.time() - t0, 2), file=sys.__stderr__, flush=True)
        assert code == 0, (entry, err)
        shutil.rmtree(inp.parent)


@pytest.mark.parametrize("entry", list(COUNTS))
def test_fuzz_entry_point(base, tmp_path, entry):
    rng = random.Random(f"{SEED}-{entry}")
    outcomes = {0: 0, 1: 0, 2: 0}
    for i in range(COUNTS[entry]):
        inp, out = _case_dir(base, tmp_path, i)
        argv, files, numeric, out_files, out_folders = _entry_points(inp, out)[entry]
        if entry == "diagnose" and rng.random() < 0.3:
            argv = argv + ["--report", str(out / "report")]
            out_folders = ["--report"]
        kinds = (["file"] * 3 if files else []) + (["option"] if numeric else []) + \
                (["output"] if out_files or out_folders else [])
        kind = rng.choice(kinds)
        if kind == "file":
            mutate_file(inp / rng.choice(files), rng)
        elif kind == "option":
            argv = mutate_option(argv, rng, numeric) or argv
        else:
            opt = rng.choice(out_files + out_folders)
            if opt not in argv:
                continue
            argv = bad_output(argv, opt, inp, rng, folder=opt in out_folders)
        if TRACE:
            print(f"{entry} #{i} ({kind}): {argv}", file=sys.__stderr__, flush=True)
        code, _ = _run_case(argv, out, f"{entry} #{i} ({kind})", allow_1=entry == "batch")
        outcomes[code] += 1
    if TRACE:
        print(f"{entry}: exit codes {outcomes}", file=sys.__stderr__, flush=True)
    assert sum(outcomes.values()) > 0
