"""``rollout`` equals repeated ``integrate`` calls, also when a step's partial sum overflows.

When one step overflowed part-way (its pose within the float range), rollout used
to redo the whole rollout an eighth of the size, so every other row, those before
the step included, was rounded at that scale: subnormal coordinates moved (a robot
standing still at x = 7 * 5e-324 came back at 8 * 5e-324).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import Pose2D, integrate, rollout

_TINY = st.integers(-64, 64).map(lambda k: k * 5e-324)
_COORD = st.one_of(_TINY, st.floats(-1e3, 1e3), st.floats(-1.7e308, 1.7e308))
_SPEED = st.one_of(st.just(0.0), _TINY, st.floats(-1e3, 1e3), st.floats(-1.7e308, 1.7e308))
_ROW = st.tuples(_SPEED, _SPEED, st.one_of(st.just(0.0), st.floats(-5.0, 5.0)))


def _repeated(start: tuple[float, float, float], rows: list[tuple[float, float, float]],
              dt: float) -> np.ndarray:
    pose = Pose2D(*start)
    out = [pose.as_array()]
    for row in rows:
        pose = integrate(pose, row, dt)
        out.append(pose.as_array())
    return np.array(out)


@settings(max_examples=50, deadline=None)
@given(st.tuples(_COORD, _COORD, st.floats(-3.0, 3.0)), st.lists(_ROW, min_size=1, max_size=5),
       st.sampled_from([0.0, 1e-3, 0.5, 1.0, 2.0]))
@example((7 * 5e-324, 3 * 5e-324, 0.0), [(0.0, 0.0, 0.0), (1.7e308, -1.7e308, 1.0)], 0.5)
# The draws never overflowed (8 seeds of 50): the refusal branch below ran for no example.
@example((0.0, -1.7e308, 0.0), [(0.0, 0.0, 0.0), (1.0, -1.7e308, 0.0)], 2.0)
def test_rollout_equals_repeated_integrate(
    start: tuple[float, float, float], rows: list[tuple[float, float, float]], dt: float
) -> None:
    try:
        want = _repeated(start, rows, dt)
    except ValueError as err:
        with pytest.raises(ValueError) as info:
            rollout(start, rows, dt)
        assert str(info.value) == str(err).replace("twist,", "twists,")
        return
    np.testing.assert_array_equal(rollout(start, rows, dt), want)


test_rollout_equals_repeated_integrate_thoroughly = slow_twin(
    test_rollout_equals_repeated_integrate, max_examples=400
)


def test_a_robot_standing_still_keeps_its_subnormal_position() -> None:
    start = (7 * 5e-324, 3 * 5e-324, 0.0)
    rows = rollout(start, [[0.0, 0.0, 0.0], [1.7e308, -1.7e308, 1.0]], 0.5)
    assert tuple(rows[1]) == start
    assert np.isfinite(rows).all()
