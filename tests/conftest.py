"""Shared fixtures: the real-data folder beside the repository; hypothesis's profile."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import settings

# No per-example deadline: tests never assert wall-clock times, and on a loaded
# 2-core machine a first example that imports SciPy or loads a compiled kernel
# can take longer than hypothesis's default 200 ms (a flaky DeadlineExceeded).
settings.register_profile("navkit", deadline=None)
settings.load_profile("navkit")

SHARED_DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data"


@pytest.fixture(scope="session")
def shared_data() -> Path:
    """Path of ``../shared/data``; skips the test when the folder is absent."""
    if not SHARED_DATA.is_dir():
        pytest.skip(f"real data folder {SHARED_DATA} is not available")
    return SHARED_DATA
