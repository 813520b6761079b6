"""Hardening: a seeded random-mutation fuzz test of the reader (bounded time) and a 1-million-line
program summarised in bounded memory."""

from __future__ import annotations

import os
import random
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

import netshape as ns

SEED_PROGRAM = """\
%
(seed)
#<s> = 2
#1 = [SQRT[16] + ATAN[1]/[1] MOD 7]
G21 G90 G17 G94
G0 X[#<s>*1.5] Y-2 Z5
G1 Z-1 F[300*#<s>]
G2 X10 Y0 I5 J1
G3 X0 Y0 R6
G18 G2 X3 Z0 I1 K1
G19 G3 Y4 Z2 J1 K0 P2
G91 G1 X1 Y1
G90 G4 P0.5
G20 G1 X1
G21 G0 Z#1
M2
"""

INSERTS = ["G2", "G3", "G91.1", "G90.1", "R", "R-", "[", "]", "#", "#<s>", "#<", "=", "99999999999999999999",
           "1" * 400, ".", "SQRT[-1]", "[0/0]", "[1/0]", "LN[0]", "EXP[1000]", "[10**400]", "ACOS[3]", "P",
           "P1000000", "G20", "(", ")", ";", "%", "G5.2", "G81", "**", "ATAN[1]/", "\x00", "\xff", "\t", "\n",
           "MOD", "EQ", "X", "I", "K", "F0", "F-1", "S-5", "T1.5", "M6", "M98", "O1", "/"]


def _mutate(rng: random.Random, text: str) -> str:
    for _ in range(rng.randint(1, 5)):
        at = rng.randrange(len(text) + 1)
        op = rng.randrange(5)
        if op == 0 and at < len(text):
            text = text[:at] + chr(rng.randrange(256)) + text[at + 1:]
        elif op == 1:
            text = text[:at]
        elif op == 2:
            text = text[:at] + rng.choice(INSERTS) + text[at:]
        elif op == 3:
            text = text[:at] + text[at + rng.randint(1, 6):]
        else:  # duplicate a slice
            j = rng.randrange(len(text) + 1)
            text = text[:at] + text[min(at, j):max(at, j)] + text[at:]
        if not text:
            text = "G0"
    return text


def test_fuzz_reader_never_crashes(shared_data):
    """Mutated programs either read (and then summarise and round-trip) or raise ParseError/ValueError.
    Any other exception, a crash (the process would die) or a hang (time bound) fails the test."""
    seeds = [SEED_PROGRAM]
    for name in ("tort.ngc", "cds.ngc", "arcspiral.ngc", "3D_Chips.ngc", "butterfly-xy_G5.2.ngc"):
        lines = (shared_data / "gcode" / name).read_text().splitlines()
        seeds.append("\n".join(lines[:60]))
    rng = random.Random(20261121)
    deadline = time.monotonic() + 12.0
    ok = bad = 0
    while time.monotonic() < deadline and ok + bad < 20000:
        text = _mutate(rng, rng.choice(seeds))
        try:
            tp = ns.toolpath.parse_gcode(text)
            s = tp.summary()
            assert s.feed_time >= 0 and s.feed_length >= 0
            back = ns.toolpath.parse_gcode(ns.toolpath.format_gcode(tp))
            assert len(back) == len(tp)
            ns.toolpath.parse_gcode_arrays(text, arcs="split", chord_tolerance=0.05)
            ok += 1
        except ValueError:  # ParseError is a ValueError
            bad += 1
    assert ok > 50 and bad > 50, (ok, bad)


_MEMORY_CHILD = textwrap.dedent(
    """
    import sys
    import netshape as ns

    def rss_kib():
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
        return 0

    ns.toolpath.summary_of_text("G0 X1")  # load everything first
    before = rss_kib()
    s = ns.toolpath.summary(sys.argv[1])
    after = rss_kib()
    print(s.blocks, s.source_lines, after - before)
    """
)


@pytest.mark.slow
def test_million_line_program_in_bounded_memory(tmp_path):
    """Summarising a 1,000,000-line program streams: peak RSS grows by a few MiB (the 1 MiB read buffer),
    far below the ~100 MiB that holding its 1 M blocks (≥ 100 bytes each) would take."""
    path = tmp_path / "million.ngc"
    with open(path, "w") as fh:
        fh.write("G21 G90 F1200\n")
        chunk = "".join(f"G1 X{(i % 1000) * 0.01:.3f} Y{(i % 777) * 0.013:.3f} Z-1.5\n" for i in range(1000))
        for _ in range(999):
            fh.write(chunk)
        fh.write("".join(f"G1 X{i * 0.01:.3f} Y1\n" for i in range(998)) + "M2\n")
    with open(path) as fh:
        n_lines = sum(1 for _ in fh)
    assert n_lines == 1_000_000
    # the child imports the same netshape as this process (installed or in-place build)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(Path(ns.__file__).parent.parent),
                                                      os.environ.get("PYTHONPATH", "")]))
    proc = subprocess.run([sys.executable, "-c", _MEMORY_CHILD, str(path)], capture_output=True, text=True,
                          env=env)
    assert proc.returncode == 0, proc.stderr
    blocks, lines, growth_kib = map(int, proc.stdout.split())
    assert lines == 1_000_000
    assert blocks == 999_998
    assert growth_kib < 16 * 1024, f"peak RSS grew by {growth_kib} KiB"
