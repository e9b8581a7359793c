"""The shared goal test refuses a NaN offset in either coordinate (review 48, FRESH).

:func:`navkit._shared.goal.at_goal` (the controllers' test, whose ``hypot``
verdict is compiled into the simulator's run kernels, review 49) states that a
NaN offset is not at the goal. It
took the offset's longer and shorter sides with ``max`` and ``min``, which
drop a NaN second argument (Python's and numba's alike): a NaN ``dy`` beside
a short ``dx`` left a finite offset of ``(dx, dx)`` and was "at the goal".
"""

from __future__ import annotations

import math

import numba
import pytest

from navkit._shared.goal import INSIDE, OUTSIDE, UNDECIDED, at_goal, goal_verdict_kernel


@numba.njit(cache=False)
def _verdict(px: float, py: float, gx: float, gy: float, tolerance: float) -> int:
    return goal_verdict_kernel(px, py, gx, gy, tolerance)  # type: ignore[no-any-return]


def _compiled(px: float, py: float, gx: float, gy: float, tolerance: float) -> bool:
    """The run kernels' decision: their compiled verdict, else at_goal (review 49)."""
    verdict = _verdict(px, py, gx, gy, tolerance)
    return verdict == INSIDE if verdict != UNDECIDED else at_goal(px, py, gx, gy, tolerance)


NAN = math.nan
# (robot, goal, tolerance): a NaN in each of the four coordinates, beside a short,
# a zero and a long other side, and where the goal's resolution is the radius.
CASES = [
    ((0.0, NAN), (0.01, 0.0), 0.05),
    ((0.0, 0.0), (0.01, NAN), 0.05),
    ((NAN, 0.0), (0.0, 0.01), 0.05),
    ((0.0, 0.0), (NAN, 0.01), 0.05),
    ((1.0, NAN), (1.0, 2.0), 0.05),
    ((0.0, NAN), (10.0, 0.0), 0.05),
    ((NAN, NAN), (0.0, 0.0), 0.05),
    ((4.6e6, NAN), (4.6e6, 4.6e6), 1e-12),
    ((0.0, NAN), (0.0, 0.0), 1e300),
]


@pytest.mark.parametrize(("robot", "goal", "tolerance"), CASES)
def test_a_nan_offset_is_not_at_the_goal(
    robot: tuple[float, float], goal: tuple[float, float], tolerance: float
) -> None:
    args = (*robot, *goal, tolerance)
    assert at_goal(*args) is False
    # Decided in the kernel: a NaN offset never stops a run for Python to decide.
    assert _verdict(*args) == OUTSIDE


def test_the_finite_neighbours_are_decided_as_before() -> None:
    # The same offsets with the NaN replaced: inside, on and beyond the radius.
    assert at_goal(0.0, 0.0, 0.01, 0.0, 0.05)
    assert at_goal(0.0, 0.0, 0.03, 0.04, 0.05)
    assert not at_goal(0.0, 0.0, 0.03, 0.0400001, 0.05)
    assert _compiled(0.0, 0.0, 0.01, 0.0, 0.05)
    assert not _compiled(0.0, 0.0, 10.0, 0.0, 0.05)
