"""The instruction set of the C++ SIMD kernels (docs/simd.md): chosen once per process, lowered by
NETSHAPE_ISA, an unknown name reported on stderr and ignored; every choice gives the same results."""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

import netshape as ns

ORDER = ("baseline", "avx2", "avx512")
PROBE = """
import numpy as np, netshape as ns
z = ns.stock.ZMap(0, 40, 0, 40, 0.1, 20.0, 0.0)
rng = np.random.default_rng(3)
a = np.column_stack([5 + 30 * rng.random(60), 5 + 30 * rng.random(60), 20 - 3 * rng.random(60)])
b = a + np.column_stack([8 * rng.standard_normal(60), 8 * rng.standard_normal(60), -rng.random(60)])
st = ns.stock.sweep_lines(z, ns.stock.Cutter.ball_end(6.0, 2, 0.5), a, b)
np.save(__import__("sys").argv[1], np.asarray(z.heights))
print(ns.kernel_isa())
"""


def run(isa: str | None, out):
    env = dict(os.environ)
    env.pop("NETSHAPE_ISA", None)
    if isa is not None:
        env["NETSHAPE_ISA"] = isa
    r = subprocess.run([sys.executable, "-c", PROBE, str(out)], env=env, capture_output=True, text=True,
                       check=True)
    return r.stdout.strip(), r.stderr


def test_best_isa_is_one_of_the_known_names():
    assert ns.kernel_isa() in ORDER


@pytest.mark.parametrize("want", ORDER)
def test_netshape_isa_lowers_the_choice_and_results_do_not_change(want, tmp_path):
    best, _ = run(None, tmp_path / "best.npy")
    got, err = run(want, tmp_path / "forced.npy")
    # a name above what the CPU runs is lowered to the best it runs
    assert got == ORDER[min(ORDER.index(want), ORDER.index(best))]
    assert err == ""
    # flat and ball heights are bit-identical on every instruction set
    assert np.array_equal(np.load(tmp_path / "best.npy"), np.load(tmp_path / "forced.npy"))


def test_unknown_isa_name_is_reported_once_and_ignored(tmp_path):
    best, _ = run(None, tmp_path / "a.npy")
    got, err = run("avx9000", tmp_path / "b.npy")
    assert got == best
    assert err.count("NETSHAPE_ISA='avx9000'") == 1 and "baseline, avx2, avx512" in err
