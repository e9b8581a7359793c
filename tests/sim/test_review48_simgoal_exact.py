"""Review 48 (SIMGOAL): the simulator's "goal reached" is the controllers' goal test.

The controllers decide "within ``goal_tolerance``" exactly (``dx² + dy² <= t²``
in real arithmetic, review 47); the simulator's run kernel decided "reached" by
``math.hypot(dx, dy) <= goal_tolerance`` (libm's hypot, as ``np.hypot``), which
rounds offsets a hair beyond the tolerance onto it and ones a hair inside
beyond it. A robot standing on such an offset was "goal reached" for the run
while its controller was not done, or the reverse. Both now call one exact
test, ``navkit._shared.goal.at_goal`` (the kernels its ``hypot`` verdict,
``goal_verdict_kernel``, leaving the band around the tolerance to ``at_goal``
in Python: review 49), checked here against rational arithmetic in Python and
compiled (whole runs: ``test_review48_simgoal_runs.py``).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numba
import numpy as np

from navkit._shared.goal import INSIDE, UNDECIDED, at_goal, goal_verdict_kernel, resolution

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from goal_oracle import boundary_cases, exact_at_goal


@numba.njit(cache=False)
def _kernel_verdicts(cases: np.ndarray, out: np.ndarray) -> None:
    for i in range(cases.shape[0]):
        out[i] = goal_verdict_kernel(
            cases[i, 0], cases[i, 1], cases[i, 2], cases[i, 3], cases[i, 4]
        )


def test_the_goal_test_is_exact_in_python_and_compiled() -> None:
    cases = boundary_cases(48, 3000)
    array = np.array(cases)
    verdicts = np.zeros(len(cases), dtype=np.int64)
    _kernel_verdicts(array, verdicts)
    rounded = 0
    for case, verdict in zip(cases, verdicts, strict=True):
        want = exact_at_goal(*case)
        assert at_goal(*case) == want, case
        # The run kernels' decision: their verdict, else at_goal in Python.
        kernel = verdict == INSIDE if verdict != UNDECIDED else at_goal(*case)
        assert kernel == want, case
        dx, dy = case[2] - case[0], case[3] - case[1]
        rounded += (float(np.hypot(dx, dy)) <= max(case[4], resolution(case[2], case[3]))) != want
    # The cases do reach the boundary: hypot's rounding decides many of them wrongly.
    assert rounded > 150


def test_the_inlined_resolution_is_math_ulp() -> None:
    # at_goal lifts a tolerance below the goal's resolution to it, computing it with
    # Rump's leading power of two (numba has no math.ulp): one ulp off the goal is at
    # it, two are not.
    for g in (1e-310, 1e-300, 0.3, 3.0, 4.6e6 + 0.5, 1e15 + 1.0, 1e300):
        res = math.ulp(g)
        assert resolution(g, -2.0 * g) == res
        one = math.nextafter(g, 0.0)
        two = math.nextafter(one, 0.0)
        assert (g - one, g - two) == (res, 2.0 * res)
        tolerance = 0.75 * res
        assert at_goal(one, g, g, g, tolerance)
        assert at_goal(g, one, g, g, tolerance)
        assert not at_goal(two, g, g, g, tolerance)
        assert not at_goal(one, one, g, g, tolerance)  # sqrt(2) resolutions off
    # Powers of two (the resolution steps there) and goals up to 1e308, upward.
    for g in (2.0**-1022, 0.5, 4.0, 2.0**52, 2.0**900, 1e300, 2.0**1023):
        res = math.ulp(g)
        one = math.nextafter(g, math.inf)
        two = math.nextafter(one, math.inf)
        assert (one - g, two - g) == (res, 2.0 * res)
        assert at_goal(one, g, g, g, 0.75 * res)
        assert not at_goal(two, g, g, g, 0.75 * res)
