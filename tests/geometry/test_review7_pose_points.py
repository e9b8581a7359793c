"""``Pose2D.transform_points`` maps each point as it maps it alone.

When one point's partial sum overflowed, every point of the call was computed
again an eighth of the size, so a point with subnormal coordinates came back
rounded differently (4e-323 instead of 2.5e-323) than in a call of its own.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit.geometry import Pose2D

_TINY = st.integers(-64, 64).map(lambda k: k * 5e-324)
_COORD = st.one_of(_TINY, st.floats(-1e3, 1e3), st.floats(-1.7e308, 1.7e308))


def _alone(pose: Pose2D, point: tuple[float, float]) -> np.ndarray | None:
    try:
        row: np.ndarray = pose.transform_points([point])[0]
        return row
    except ValueError:
        return None


@settings(max_examples=300, deadline=None)
@given(st.tuples(_COORD, _COORD, st.floats(-3.2, 3.2)),
       st.lists(st.tuples(_COORD, _COORD), min_size=1, max_size=4))
@example((0.0, -1e308, math.pi / 4), [(1.7e308, 1.7e308), (9 * 5e-324, 2 * 5e-324)])
def test_each_point_as_alone(
    pose_values: tuple[float, float, float], points: list[tuple[float, float]]
) -> None:
    pose = Pose2D(*pose_values)
    alone = [_alone(pose, p) for p in points]
    if any(a is None for a in alone):
        return  # (refusal covered by the geometry contract tests)
    np.testing.assert_array_equal(pose.transform_points(points), np.array(alone))
