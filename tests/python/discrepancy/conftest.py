"""Make the bundle generators of this folder importable as ``generators``."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
