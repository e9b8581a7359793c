"""The suite's per-test time limit ends a test hung inside a numba kernel.

Two mutants of the LiDAR kernels (review 50) and one of review 49 looped for
ever in nopython code: the suite hung until CI's 90 minutes ran out, with no
word of where. pyproject.toml sets pytest's ``faulthandler_timeout`` with
``faulthandler_exit_on_timeout``: faulthandler's watchdog is a C thread that
needs no GIL, so it prints every thread's stack and ends the process even then.
pytest-timeout could not: its signal handler and its watchdog thread both wait
for a GIL that a kernel without ``nogil`` never gives back (tried: the hung test
below ran on until killed).
"""

from __future__ import annotations

import os
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

_HUNG_TEST = """
import numba
import numpy as np


@numba.njit
def spin(state):
    # Never ends: state[0] stays 1.0; the writes keep LLVM from dropping the loop.
    while state[0] > 0.0:
        state[1] += 1.0
    return state[1]


def test_hangs_in_a_kernel():
    spin(np.array([1.0, 0.0]))
"""


def _pytest_options() -> dict[str, object]:
    with (ROOT / "pyproject.toml").open("rb") as file:
        options: dict[str, object] = tomllib.load(file)["tool"]["pytest"]["ini_options"]
    return options


def test_the_suite_has_a_time_limit_that_ends_the_process() -> None:
    options = _pytest_options()
    assert options["faulthandler_exit_on_timeout"] is True
    # A guard, not a speed check: far above the slowest test on a busy machine.
    limit = options["faulthandler_timeout"]
    assert isinstance(limit, int)
    assert 600 <= limit <= 3600


def _run_hung_test(tmp_path: Path, *options: str) -> str:
    """pytest on the hung test with the project's settings, the limit cut to 5 s."""
    (tmp_path / "test_hung.py").write_text(_HUNG_TEST)
    environment = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba-cache"))
    environment.pop("NUMBA_DISABLE_JIT", None)
    command = [
        sys.executable,
        "-m",
        "pytest",
        "-c",
        str(ROOT / "pyproject.toml"),
        "--rootdir",
        str(tmp_path),
        "-p",
        "no:cacheprovider",
        "-o",
        "faulthandler_timeout=5",
        "-o",
        "addopts=",
        *options,
        str(tmp_path / "test_hung.py"),
    ]
    try:
        outcome = subprocess.run(
            command, cwd=tmp_path, env=environment, capture_output=True, text=True, timeout=300
        )
    except subprocess.TimeoutExpired:
        pytest.fail("the hung kernel was not stopped by the suite's time limit")
    report = outcome.stdout + outcome.stderr
    assert outcome.returncode != 0, report
    return report


def test_a_test_hung_in_a_kernel_is_ended_with_its_stack(tmp_path: Path) -> None:
    report = _run_hung_test(tmp_path, "-p", "no:xdist")
    assert "Timeout" in report, report
    # The stack names the kernel's caller: where the suite hung.
    assert "test_hangs_in_a_kernel" in report, report


@pytest.mark.slow
def test_under_xdist_the_hung_test_is_named(tmp_path: Path) -> None:
    pytest.importorskip("xdist")
    report = _run_hung_test(tmp_path, "-n", "1")
    assert "crashed" in report, report
    assert "test_hung.py::test_hangs_in_a_kernel" in report, report
