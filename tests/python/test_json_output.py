"""netshape._json: the one JSON writer refuses NaN/±inf before writing, naming the result key and the
input that caused it, and writes NumPy values as plain numbers."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from netshape._json import NonFiniteResult, dumps_json, first_non_finite, write_json


def test_numpy_values_are_plain_json():
    text = dumps_json({"a": np.float64(1.5), "b": np.arange(3), "c": [np.int32(2)]}, indent=None)
    assert json.loads(text) == {"a": 1.5, "b": [0, 1, 2], "c": [2]}


@pytest.mark.parametrize("doc, key", [
    ({"a": {"b": [1.0, math.inf]}}, "a.b[1]"),
    ({"x": np.array([[0.0, np.nan]])}, "x[0][1]"),
    ({"s": 1, "t": (2.0, {"u": -math.inf})}, "t[1].u"),
])
def test_the_first_non_finite_number_is_named(doc, key):
    assert first_non_finite(doc)[0] == key
    with pytest.raises(NonFiniteResult, match=rf"^--stick-out = 1e\+300: gives a non-finite result \({re.escape(key)} = "):
        dumps_json(doc, cause="--stick-out = 1e+300")


def test_nothing_is_written_when_a_number_is_not_finite(tmp_path):
    out = tmp_path / "o.json"
    with pytest.raises(ValueError, match=r"^r = nan: the result is not a finite number; nothing written$"):
        write_json(out, {"r": float("nan")})
    assert list(tmp_path.iterdir()) == []
    write_json(out, {"r": 1.0})
    assert out.read_text() == '{\n  "r": 1.0\n}\n'


@pytest.mark.parametrize("doc", [
    {"a": 1, "b": [1, 2, {"c": None, "d": []}], "e": {}, "f": "x\u00e9", "g": {1: 2, 2.5: 3, True: 1, None: 0}},
    [1.5, -0.0, 1e300, 3], {"p": [[1, 2, 3]] * 10}, "s", 1, None, [], {}, {"z": list(range(64))},
])
def test_short_documents_are_laid_out_as_json_dumps_does(doc):
    assert dumps_json(doc) == json.dumps(doc, indent=2)
    assert dumps_json(doc, indent=1) == json.dumps(doc, indent=1)


def test_a_long_list_has_one_compact_item_per_line_and_reads_back_equal():
    doc = {"n": 3, "points": [{"xyz": [i, 0.5 * i, -i], "e": np.array([0.1 * i])} for i in range(1000)]}
    text = dumps_json(doc)
    lines = text.splitlines()
    assert len(lines) == 1000 + 5
    assert lines[4] == '    {"xyz": [1, 0.5, -1], "e": [0.1]},'
    back = json.loads(text)
    assert back["points"][999] == {"xyz": [999, 499.5, -999], "e": [99.9]}
    doc["points"][500]["xyz"][1] = math.nan
    with pytest.raises(NonFiniteResult, match=r"points\[500\]\.xyz\[1\] = nan"):
        dumps_json(doc)
