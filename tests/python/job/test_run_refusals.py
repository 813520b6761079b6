"""Job values that made `netshape run` fail with an internal message (issue 42 item 7): the one-line
error names the job key and the value instead."""

from __future__ import annotations

import pytest

from netshape.cli import main

from ..test_cli_outputs import quick_job


@pytest.mark.parametrize("old, new, needles", [
    ("error_scale = 1.0", "error_scale = 1e300", ["machine.error_scale = 1e+300", "volumetric error of"]),
    ("error_scale = 1.0", "error_scale = 1e6", ["machine.error_scale = 1e+06", "more than 1000 mm"]),
    ("G54_mm = [-150.0, 80.0, -300.0]", "G54_mm = [-150.0, 80.0, -3e300]",
     ["offsets.G54_mm[2] = -3e+300: must be within ±100000 [mm]"]),
    ("tool_length_mm = 100.0", "tool_length_mm = 1e200", ["offsets.tool_length_mm = 1e+200"]),
])
def test_key_named_instead_of_an_internal_error(tmp_path, capsys, old, new, needles):
    job = quick_job(tmp_path)
    text = job.read_text()
    assert old in text
    job.write_text(text.replace(old, new))
    out = tmp_path / "o"
    assert main(["run", str(job), "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    for n in needles:
        assert n in err, (n, err)
    assert "out of bounds" not in err and "must be finite, check" not in err
    assert not out.exists() or not any(out.iterdir())
