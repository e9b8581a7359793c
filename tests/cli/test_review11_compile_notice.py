"""The compilation notice where numba cannot cache navkit's kernels, or compiles nothing."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import write_map

# numba with no cache locator: what a read-only installation without
# NUMBA_CACHE_DIR looks like to it ("cannot cache function ...").
_NO_CACHE = (
    "import numba.core.caching as caching\n"
    "impl = getattr(caching, 'CacheImpl', None) or getattr(caching, '_CacheImpl')\n"
    "impl._locator_classes = []\n"
)
_MAIN = "import sys\nfrom navkit.cli import main\nsys.exit(main(sys.argv[1:]))\n"


def _env(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env.update(extra)
    return env


@pytest.fixture
def corridor(tmp_path: Path) -> Path:
    grid = OccupancyGrid.from_occupancy(np.zeros((10, 30), dtype=bool), resolution=0.1)
    write_map(grid, tmp_path / "corridor.yaml")
    return tmp_path / "corridor.yaml"


def _plan(corridor: Path, script: str, env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    argv = ["plan", str(corridor), "--start", "0.25,0.5", "--goal", "2.75,0.5"]
    return subprocess.run(
        [sys.executable, "-c", script, *argv], env=env, capture_output=True, text=True,
        timeout=600, cwd=corridor.parent,
    )  # fmt: skip


def test_without_a_cache_the_notice_promises_none(corridor: Path) -> None:
    # The notice was left out (the cache's index files exist, numba just cannot
    # use them), or promised "cached afterwards"; the library's warning came as
    # two lines, the second a line of the caller's source.
    done = _plan(corridor, _NO_CACHE + _MAIN, _env())
    assert done.returncode == 0, done.stderr[-2000:]
    lines = done.stderr.splitlines()
    warnings = [line for line in lines if "numba cannot cache navkit's compiled kernels" in line]
    assert len(warnings) == 1 and warnings[0].startswith("navkit: warning: ")
    assert "NUMBA_CACHE_DIR" in warnings[0]
    notices = [line for line in lines if "compiling navkit's kernels" in line]
    assert len(notices) == 1
    assert "again in every run" in notices[0] and "cached afterwards" not in notices[0]
    assert len(lines) == 2
    assert "length (m)" in done.stdout


def test_no_notice_when_the_jit_is_disabled(corridor: Path, tmp_path: Path) -> None:
    # An empty cache folder and NUMBA_DISABLE_JIT=1 announced a compilation
    # that never happens.
    env = _env(NUMBA_DISABLE_JIT="1", NUMBA_CACHE_DIR=str(tmp_path / "empty-cache"))
    done = _plan(corridor, _MAIN, env)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stderr == ""


@pytest.mark.slow
def test_workers_without_a_cache_warn_once() -> None:
    # Each worker process warned again, two lines each naming the pool's source.
    done = subprocess.run(
        [sys.executable, "-c", _NO_CACHE + _MAIN, "run", "soccer", "--trials", "1",
         "--workers", "2", "--quiet"],
        env=_env(), capture_output=True, text=True, timeout=900,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stderr.count("numba cannot cache") == 1
    assert done.stderr.startswith("navkit: warning: ")
    assert len(done.stderr.splitlines()) == 1
