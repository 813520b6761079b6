"""Make the pocket programs of this folder importable as ``pocket_cases`` (tests and bench/deflection.py)."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
