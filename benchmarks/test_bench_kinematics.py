"""Omni-wheel inverse kinematics on 10^6 twists against NumPy and a pure-Python loop.

Run with ``python -m pytest benchmarks/test_bench_kinematics.py --benchmark-only``.

The drive is the three-wheel Y layout (wheels at 30°, 150°, 270°, r = 0.05 m,
L = 0.2 m); the input 10^6 random body twists (seeded, |vx|, |vy| ≤ 1.5 m/s,
|ω| ≤ 3 rad/s) as a (10^6, 3) float64 array.

* ``navkit``: :meth:`OmniDrive.inverse_batch` (validation of the input, the
  matrix product, the overflow check of the result);
* ``numpy``: the bare product ``twists @ drive.jacobian.T`` (what
  ``inverse_batch`` computes, without the checks);
* ``pure_python``: the wheel-speed formula per twist and wheel on Python floats
  (input as a list of tuples prepared outside the timer), three rounds.

``benchmarks/compare_peers.py`` runs the same workload (``omni-ik``).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from functools import cache
from typing import Any

import numpy as np
import pytest

from navkit.kinematics import OmniDrive

N_TWISTS = 1_000_000
DRIVE = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)


@cache
def twists_1e6() -> np.ndarray:
    """10^6 seeded body twists ``[vx, vy, omega]`` (read-only)."""
    rng = np.random.default_rng(1_000_000)
    twists: np.ndarray = rng.uniform(-1.0, 1.0, size=(N_TWISTS, 3)) * np.array([1.5, 1.5, 3.0])
    twists.flags.writeable = False
    return twists


def numpy_inverse(jacobian: np.ndarray, twists: np.ndarray) -> np.ndarray:
    """Wheel speeds as one NumPy matrix product (no validation)."""
    out: np.ndarray = twists @ jacobian.T
    return out


def python_inverse(drive: OmniDrive, twists: list[tuple[float, float, float]]) -> list[list[float]]:
    """The wheel-speed formula (-sin θi vx + cos θi vy + L ω) / r on Python floats."""
    r = drive.wheel_radius
    lever = drive.base_radius
    wheels = [(-math.sin(a) / r, math.cos(a) / r) for a in drive.wheel_angles.tolist()]
    out = []
    for vx, vy, omega in twists:
        spin = lever * omega / r
        out.append([sx * vx + cy * vy + spin for sx, cy in wheels])
    return out


def make_call(who: str) -> Callable[[], Any]:
    """The timed call of contestant ``who`` ("navkit", "numpy" or "pure_python")."""
    twists = twists_1e6()
    if who == "navkit":
        return functools.partial(DRIVE.inverse_batch, twists)
    if who == "numpy":
        return functools.partial(numpy_inverse, DRIVE.jacobian, twists)
    rows = [tuple(row) for row in twists.tolist()]
    return functools.partial(python_inverse, DRIVE, rows)


def check_result(who: str, ours: np.ndarray, theirs: Any) -> str:
    """Check a contestant's wheel speeds against navkit's; a one-line verdict."""
    if who == "numpy":
        np.testing.assert_array_equal(theirs, ours)
        return "same wheel speeds"
    np.testing.assert_allclose(theirs, ours, rtol=1e-12, atol=1e-9)
    return "same wheel speeds (1e-12)"


@pytest.mark.parametrize("who", ["navkit", "numpy", "pure_python"])
def test_inverse_batch(benchmark: Any, who: str) -> None:
    call = make_call(who)
    benchmark.group = "omni inverse kinematics, 10^6 twists"
    if who == "pure_python":
        speeds = benchmark.pedantic(call, rounds=3, iterations=1)
    else:
        speeds = benchmark(call)
    check_result(who, DRIVE.inverse_batch(twists_1e6()), speeds)
