"""PotentialFieldController.stalled after stall_timeout seconds still, not one step later.

The stall timer adds each step's ``dt``; ten steps of 0.1 s sum to
0.9999999999999999 in floating point, so with ``stall_timeout=1.0`` the robot
was reported stalled after 1.1 s (found by a user's-eye review: a 20 Hz loop
with ``stall_timeout=0.5`` reported after 0.55 s).
"""

from __future__ import annotations

from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D

HERE = Pose2D(0.0, 0.0, 0.0)
TARGET = (5.0, 0.0, 0.0)  # far beyond goal_tolerance: standing here is a stall


@settings(deadline=None, max_examples=200)
@given(dt_ms=st.integers(1, 1000), k=st.integers(1, 300))
@example(dt_ms=100, k=10)  # 0.1 s steps, 1 s: stalled after 1.1 s before
@example(dt_ms=50, k=10)  # 20 Hz, 0.5 s: stalled after 0.55 s before
@example(dt_ms=700, k=3)  # 3 × 0.7 s sum to 2.0999999999999996 < 2.1
def test_stalled_once_still_for_the_timeout(dt_ms: int, k: int) -> None:
    # The timeout and the period as a user writes them: decimal numbers, k periods.
    dt, timeout = dt_ms / 1000, k * dt_ms / 1000
    ctl = PotentialFieldController(stall_timeout=timeout)
    ctl.step(HERE, TARGET, dt)  # the first step marks the spot: still for 0 s
    for _ in range(k - 1):
        ctl.step(HERE, TARGET, dt)
        assert not ctl.stalled  # still for less than k periods
    ctl.step(HERE, TARGET, dt)
    assert ctl.stalled, (ctl.stall_time, timeout)  # still for k periods


@settings(deadline=None, max_examples=50)
@given(dt_ms=st.integers(1, 1000), k=st.integers(2, 300))
def test_a_timeout_a_microsecond_longer_is_not_met_early(dt_ms: int, k: int) -> None:
    # The tolerance that absorbs the sum's rounding is far below anything a
    # controller could tell: a timeout a microsecond longer than k periods is
    # not met after k periods.
    dt = dt_ms / 1000
    ctl = PotentialFieldController(stall_timeout=k * dt_ms / 1000 + 1e-6)
    for _ in range(k + 1):
        ctl.step(HERE, TARGET, dt)
    assert not ctl.stalled
    ctl.step(HERE, TARGET, dt)
    assert ctl.stalled
