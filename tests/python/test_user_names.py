"""User-facing names carry no internal indices and no library text points at files users do not have
(issue 40 item 5): no module or example is named after a seed index except the deprecated alias
`netshape.motion.seeds002`, and nothing under python/, docs/ or examples/ names the project's private
`shared/data` folder."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TEXT = {".py", ".pyi", ".md", ".toml", ".txt", ".cpp", ".hpp", ".csv", ".ngc", ".json", ".html"}
ALIASES = {"python/netshape/motion/seeds002.py"}  # deprecated for one release; warns on import


def _files(*dirs):
    for d in dirs:
        for p in sorted((ROOT / d).rglob("*")):
            if p.is_file() and "__pycache__" not in p.parts:
                yield p


def test_no_seed_index_in_module_or_example_names():
    named = [str(p.relative_to(ROOT)) for p in _files("python", "examples")
             if re.search(r"seeds?_?\d{3}", p.name) and str(p.relative_to(ROOT)) not in ALIASES]
    assert named == []


def test_no_text_points_at_shared_data():
    hits = [f"{p.relative_to(ROOT)}:{n}" for p in _files("python", "docs", "examples") if p.suffix in TEXT
            for n, line in enumerate(p.read_text(encoding="utf-8", errors="replace").splitlines(), 1)
            if "shared/data" in line]
    assert hits == []
