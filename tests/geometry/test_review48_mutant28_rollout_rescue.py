"""``rollout``'s step-by-step retry after an overflowing partial sum keeps each row's ``dt``.

Review 48 (mutation testing, MUTANT28). Where the compiled rollout overflows
(a partial sum ``x + c*dx`` beyond the float range, the pose itself not),
``rollout`` redoes the steps from there one by one as ``integrate`` does.
That retry read with the first step's ``dt`` for every row passed every test:
they all used one scalar ``dt``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.geometry import Pose2D, integrate, rollout

START = Pose2D(1.7e308, 0.0, math.pi / 4)
TWISTS = np.array(
    [
        [0.0, 0.0, 0.1],  # a turn only: finite in the compiled rollout
        [1e308, 1e308, 0.0],  # x + c*dx overflows, the pose does not
        [-1e308, 1e308, 0.2],
        [0.0, -1e308, 0.0],
    ]
)


@pytest.mark.parametrize(
    "dts", [[0.25, 1.0, 0.5, 0.75], [1.0, 0.5, 0.75, 0.25], [0.75, 1.0, 0.5, 0.25]]
)
def test_the_retried_rows_are_repeated_integrate_calls_with_their_own_dt(
    dts: list[float],
) -> None:
    rows = rollout(START, TWISTS, np.array(dts))
    assert np.isfinite(rows).all()
    pose = START
    np.testing.assert_array_equal(rows[0], pose.as_array())
    for i, (twist, dt) in enumerate(zip(TWISTS.tolist(), dts, strict=True)):
        pose = integrate(pose, twist, dt)
        np.testing.assert_array_equal(rows[i + 1], pose.as_array(), err_msg=f"row {i + 1}")
    # The retry is reached: the second step's partial sum x + c*dx overflows.
    first = integrate(START, TWISTS[0], dts[0])
    assert math.isinf(first.x + math.cos(first.theta) * (1e308 * dts[1]))
