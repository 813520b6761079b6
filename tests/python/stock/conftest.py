"""Make the NumPy Z-map oracle of this folder importable as ``zmap_reference`` (tests and bench)."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
