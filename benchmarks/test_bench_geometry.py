"""``rollout`` of 10^5 body twists against a pure-Python loop and a NumPy prefix-sum form.

Run with ``python -m pytest benchmarks/test_bench_geometry.py --benchmark-only``.

Input: 10^5 seeded random twists (vx in [0, 1] m/s, vy in [-0.2, 0.2] m/s,
ω in [-1, 1] rad/s, 1 in 50 exactly zero so the straight-line branch runs too),
each held for dt = 0.01 s, from the pose (1, -2, 0.5).

* ``navkit``: :func:`navkit.geometry.rollout` (validation, one compiled loop of
  exact SE(2) steps, the overflow check);
* ``pure_python``: the same exact SE(2) step (arc or straight line) written
  with ``math`` on Python floats, input as a list of tuples prepared outside
  the timer;
* ``numpy``: headings as a prefix sum of ω·dt, each step's body displacement
  vectorised, rotated into the world frame and prefix-summed (exact, but not
  the sequential order of operations, so it agrees to about 1e-9 m, not to the
  last bit).

``benchmarks/compare_peers.py`` runs the same workload (``rollout``).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from functools import cache
from typing import Any

import numpy as np
import pytest

from navkit.geometry import rollout

N_STEPS = 100_000
DT = 0.01
START = (1.0, -2.0, 0.5)


@cache
def twists_1e5() -> np.ndarray:
    """10^5 seeded twists ``[vx, vy, omega]``, 2 % with omega exactly 0 (read-only)."""
    rng = np.random.default_rng(100_000)
    twists = np.column_stack(
        (
            rng.uniform(0.0, 1.0, N_STEPS),
            rng.uniform(-0.2, 0.2, N_STEPS),
            rng.uniform(-1.0, 1.0, N_STEPS),
        )
    )
    twists[::50, 2] = 0.0
    twists.flags.writeable = False
    return twists


def python_rollout(
    start: tuple[float, float, float], twists: list[tuple[float, float, float]], dt: float
) -> list[tuple[float, float, float]]:
    """Exact SE(2) steps on Python floats; headings wrapped with ``math.remainder``."""
    x, y, th = start
    out = [(x, y, th)]
    for vx, vy, omega in twists:
        dth = omega * dt
        if abs(dth) < 1e-9:  # straight line (the arc formula's limit)
            a, b = 1.0, 0.5 * dth
        else:
            a = math.sin(dth) / dth
            b = (1.0 - math.cos(dth)) / dth
        dx = dt * (a * vx - b * vy)
        dy = dt * (b * vx + a * vy)
        c, s = math.cos(th), math.sin(th)
        x, y = x + c * dx - s * dy, y + s * dx + c * dy
        th = math.remainder(th + dth, 2.0 * math.pi)
        out.append((x, y, th))
    return out


def numpy_rollout(start: tuple[float, float, float], twists: np.ndarray, dt: float) -> np.ndarray:
    """The same poses from prefix sums: headings first, then world-frame displacements."""
    vx, vy, omega = twists.T
    dth = omega * dt
    with np.errstate(divide="ignore", invalid="ignore"):
        straight = np.abs(dth) < 1e-9
        a = np.where(straight, 1.0, np.sin(dth) / dth)
        b = np.where(straight, 0.5 * dth, (1.0 - np.cos(dth)) / dth)
    dx = dt * (a * vx - b * vy)
    dy = dt * (b * vx + a * vy)
    heading = start[2] + np.concatenate(([0.0], np.cumsum(dth)))
    c, s = np.cos(heading[:-1]), np.sin(heading[:-1])
    out = np.empty((len(twists) + 1, 3))
    out[0, :2] = start[:2]
    out[1:, 0] = start[0] + np.cumsum(c * dx - s * dy)
    out[1:, 1] = start[1] + np.cumsum(s * dx + c * dy)
    out[:, 2] = np.remainder(heading + math.pi, 2.0 * math.pi) - math.pi
    return out


def assert_same_poses(got: Any, want: np.ndarray, atol: float) -> None:
    """Poses equal to ``atol`` (m and rad), headings compared modulo 2π."""
    got = np.asarray(got, dtype=np.float64)
    np.testing.assert_allclose(got[:, :2], want[:, :2], rtol=0.0, atol=atol)
    dth = np.remainder(got[:, 2] - want[:, 2] + math.pi, 2.0 * math.pi) - math.pi
    assert float(np.max(np.abs(dth))) <= atol


def make_call(who: str) -> Callable[[], Any]:
    """The timed call of contestant ``who`` ("navkit", "numpy" or "pure_python")."""
    twists = twists_1e5()
    if who == "navkit":
        return functools.partial(rollout, START, twists, DT)
    if who == "numpy":
        return functools.partial(numpy_rollout, START, twists, DT)
    rows = [tuple(row) for row in twists.tolist()]
    return functools.partial(python_rollout, START, rows, DT)


def check_result(who: str, ours: np.ndarray, theirs: Any) -> str:
    """Check a contestant's poses against navkit's; a one-line verdict."""
    atol = 1e-8 if who == "numpy" else 1e-9
    assert_same_poses(theirs, ours, atol=atol)
    return f"same poses (to {atol:.0e} m)".replace("e-0", "e-")


@pytest.mark.parametrize("who", ["navkit", "numpy", "pure_python"])
def test_rollout(benchmark: Any, who: str) -> None:
    call = make_call(who)
    benchmark.group = "rollout, 10^5 twists"
    if who == "pure_python":
        poses = benchmark.pedantic(call, rounds=3, iterations=1)
    else:
        poses = benchmark(call)
    check_result(who, rollout(START, twists_1e5(), DT), poses)
