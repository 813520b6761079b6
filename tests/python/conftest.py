"""Shared fixtures. `shared_data` is ../shared/data beside the checkout (public programs and
measurements, each folder with a README on its source and licence): tests that need it skip, with the
reason, where it is absent."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def _shared_data_dir() -> Path:
    env = os.environ.get("NETSHAPE_SHARED_DATA")
    return Path(env) if env else REPO.parent / "shared" / "data"


@pytest.fixture(scope="session")
def repo_root() -> Path:
    return REPO


@pytest.fixture(scope="session")
def shared_data() -> Path:
    d = _shared_data_dir()
    if not d.is_dir():
        pytest.skip(f"shared data folder {d} is absent (set NETSHAPE_SHARED_DATA to its path)")
    return d
