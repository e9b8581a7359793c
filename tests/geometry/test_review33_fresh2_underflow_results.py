"""A caller's ``np.seterr(under="raise")`` and normal inputs whose *results* underflow.

Review 31 made navkit give NumPy's default answer under any error state for valid
inputs whose non-zero values are normal floats (docs/getting-started.md), with
products of tiny components underflowing to 0. Three places still raised
``FloatingPointError`` where the products, from normal inputs, are subnormal:

* ``Pose2D.transform_points`` (and so ``OccupancyGrid.cell_to_world``'s general
  way) on a pose of yaw 1e-307 and points 1e-2 m off: ``px * sin(yaw)`` is
  1.25e-309, while the cell_to_world fast paths (a compiled kernel, Python
  floats) answered;
* ``quaternion_to_yaw`` of ``(1e-160, 1e-160, 0, 1)`` (yaw 2e-320, from
  ``x * y``) or ``(0, 0, 1e-300, 1e10)``: ``arctan2`` of a subnormal argument,
  outside the function's ``np.errstate`` (both its fast and general ways);
* ``yaw_to_quaternion`` and ``rpy_to_quaternion`` of an angle of 4.4e-308 (half of
  it is subnormal).
"""

from __future__ import annotations

import numpy as np
import pytest

from errstate_checks import assert_default_answer
from navkit.geometry import Pose2D, quaternion_to_yaw, rpy_to_quaternion, yaw_to_quaternion
from navkit.mapping import OccupancyGrid

_MODES = ["under", "all"]


@pytest.mark.parametrize("mode", _MODES)
def test_transform_points_with_subnormal_products(mode: str) -> None:
    pose = Pose2D(0.0, 0.0, 1e-307)  # a normal yaw; sin(yaw) * 0.0125 is subnormal
    pts = [[0.0125, 0.0125], [-3.0, 2.0]]
    assert_default_answer(lambda: pose.transform_points(pts), mode)
    # The default answer, as the values say (the subnormal terms vanish in the sums).
    assert pose.transform_points(pts).tolist() == [[0.0125, 0.0125], [-3.0, 2.0]]


@pytest.mark.parametrize("mode", _MODES)
def test_cell_to_world_general_way_as_fast(mode: str) -> None:
    grid = OccupancyGrid.empty(
        width=2.0, height=2.0, resolution=0.05, origin=Pose2D(0.0, 0.0, 1e-307)
    )
    cells = [[-0.25, -0.25], [0.0, 0.0]]
    fast = grid.cell_to_world(np.array(cells))  # the compiled kernel
    for spelling in (cells, np.array(cells, dtype=">f8"), np.array(cells, dtype=">i8")[1:]):
        assert_default_answer(lambda s=spelling: grid.cell_to_world(s), mode)
    with np.errstate(**{mode: "raise"}):  # type: ignore[arg-type]
        assert grid.cell_to_world(cells).tobytes() == fast.tobytes()


_TINY_YAWS = [
    [1e-160, 1e-160, 0.0, 1.0],  # x y = 1e-320: yaw 2e-320
    [0.0, 0.0, 1e-300, 1e10],  # z / w = 1e-310 once normalised
    [0.0, 0.0, -1e-300, 1e12],
]


@pytest.mark.parametrize("spelling", [list, np.array, lambda q: np.array([q, q])])
@pytest.mark.parametrize("q", _TINY_YAWS, ids=repr)
def test_quaternion_to_yaw_of_a_subnormal_yaw(q: list[float], spelling: object) -> None:
    value = spelling(q)  # type: ignore[operator]
    assert_default_answer(lambda: quaternion_to_yaw(value), "under")
    yaw = np.asarray(quaternion_to_yaw(value))
    assert np.all((yaw != 0.0) & (np.abs(yaw) < 2.2e-308))  # the default answer: subnormal


@pytest.mark.parametrize("axis", ["yaw", "roll", "pitch", "yaw_to_quaternion"])
def test_half_of_a_tiny_normal_angle(axis: str) -> None:
    angle = 4.4e-308  # normal; half of it is subnormal
    if axis == "yaw_to_quaternion":
        assert_default_answer(lambda: yaw_to_quaternion([angle, 0.5]), "under")
        return
    rpy = {"roll": 0.0, "pitch": 0.0, "yaw": 0.0, axis: angle}
    assert_default_answer(lambda: rpy_to_quaternion(**rpy), "under")
