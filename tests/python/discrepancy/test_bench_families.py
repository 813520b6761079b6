"""Issue 37 item 6: the scored bench families (bench/discrepancy_families.py) in their --quick form —
three bundles per kind of the check half (a control and two hidden effects), the table per kind and
effect. The full families (50 check bundles per kind) and their scores are in docs/discrepancy.md."""

from __future__ import annotations

import importlib.util
from pathlib import Path

BENCH = Path(__file__).resolve().parents[3] / "bench" / "discrepancy_families.py"


def _bench():
    spec = importlib.util.spec_from_file_location("discrepancy_families", BENCH)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_quick_families_table(capsys):
    bench = _bench()
    rows = bench.main(["--quick"])
    out = capsys.readouterr().out
    assert len(rows) == 3 * len(bench.EFFECTS)
    for kind in bench.EFFECTS:
        mine = [r for r in rows if r["kind"] == kind]
        # not trivially passing: each kind hides an effect in two of its three bundles, found and measured
        hidden = [r for r in mine if r["effect"] != "none"]
        assert len(hidden) == 2 and all(r["exact"] and r["named"] == [r["effect"]] for r in hidden), mine
        assert all(r["perr"] is not None and r["perr"] < 0.1 for r in hidden), hidden
        assert [r["named"] for r in mine if r["effect"] == "none"] == [[]]
        assert f"| {kind} | **all** | 3 | 3 (100 %) | 0 (0 %) | 0 | 2/2 |" in out
    header = "| kind | hidden effect | bundles | exact | false naming | missed |"
    lines = out[out.index(header):].strip().splitlines()
    assert len(lines) == 2 + 3 * 4 and all(line.count("|") == 10 for line in lines)
    # the scorer: another effect, or the right one on another axis, is a false naming
    assert bench.classify(None, {}, []) == (True, False)
    assert bench.classify(None, {}, [("squareness", {})]) == (False, True)
    assert bench.classify("backlash", {"axis": "X"}, [("backlash", {"axis": "X"})]) == (True, False)
    assert bench.classify("backlash", {"axis": "X"}, [("backlash", {"axis": "Y"})]) == (False, True)
    assert bench.classify("thermal_drift", {"axis": "Z"}, [("scale_error", {})]) == (False, True)
    assert bench.classify("runout", {}, []) == (False, False)
    err = bench.parameter_error("backlash", {"reversal_um": 5.5}, {"reversal_um": 5.0}, "")
    assert abs(err - 0.1) < 1e-12
