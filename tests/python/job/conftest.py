"""Fixtures of the job tests: the bundled demo job run once (through the CLI) per session."""

from __future__ import annotations

import json
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
DEMO = REPO / "examples" / "demo"


@pytest.fixture(scope="session")
def demo_run(tmp_path_factory):
    """`netshape demo --out DIR --quiet` once: (folder, summary dict, wall time [s])."""
    from netshape.cli import main

    out = tmp_path_factory.mktemp("demo") / "netshape-demo"
    t0 = time.perf_counter()
    assert main(["demo", "--out", str(out), "--quiet"]) == 0
    wall = time.perf_counter() - t0
    return out, json.loads((out / "summary.json").read_text()), wall
