"""The committed type stubs of the extension (python/netshape/_core/*.pyi) describe what it binds.

The stubs are generated with pybind11-stubgen (scripts/stubs.sh). This test generates them again from the
extension under test and compares the names they declare — modules, classes, functions, methods and
properties — with the committed ones, so a binding changed without regenerating the stubs fails here.
Names, not text, are compared: the exact spelling of annotations depends on the pybind11 version.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("pybind11_stubgen", reason="pybind11-stubgen is in the 'test' extra")

STUBS = Path(__file__).resolve().parents[2] / "python" / "netshape" / "_core"


def _names(path: Path) -> set[str]:
    """Qualified names declared in a stub file: top-level and one level into classes."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    out: set[str] = set()

    def target(node) -> list[str]:
        if isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            return [node.target.id]
        if isinstance(node, ast.Assign):
            return [t.id for t in node.targets if isinstance(t, ast.Name)]
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            return [node.name]
        return []

    for node in tree.body:
        for name in target(node):
            if name == "__all__":
                continue
            out.add(name)
            if isinstance(node, ast.ClassDef):
                for member in node.body:
                    out.update(f"{name}.{m}" for m in target(member))
    return out


def test_committed_stubs_match_the_extension(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "pybind11_stubgen", "netshape._core", "--exit-code",
                           "-o", str(tmp_path)], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, f"pybind11-stubgen failed (a default value without a Python repr?):\n{proc.stderr}"
    fresh = {p.name: _names(p) for p in (tmp_path / "netshape" / "_core").glob("*.pyi")}
    committed = {p.name: _names(p) for p in STUBS.glob("*.pyi")}
    assert sorted(fresh) == sorted(committed), "stub files differ: run scripts/stubs.sh"
    problems = []
    for name in sorted(fresh):
        missing, stale = fresh[name] - committed[name], committed[name] - fresh[name]
        if missing or stale:
            problems.append(f"{name}: not in the committed stub {sorted(missing)}; no longer bound {sorted(stale)}")
    assert not problems, "stubs are out of date, run scripts/stubs.sh:\n" + "\n".join(problems)
    assert len(fresh["motion.pyi"]) > 20  # the comparison saw real content
