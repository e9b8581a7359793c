"""``LaserScan.to_local_grid(mount=)``: a scan from a sensor off the robot's centre (review 46).

The repulsion functions and ``PotentialFieldController`` took ``mount=`` this
session; the greedy laser grid assumed a scan from the robot's centre, facing
forward, with no way to say otherwise. The grid is the robot's: each return
is placed at its end point seen from the sensor's pose on the robot.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, LocalGrid


def _scan(ranges: list[float], angle_min: float, increment: float) -> LaserScan:
    return LaserScan(
        ranges, angle_min=angle_min, angle_increment=increment, range_min=0.05, range_max=3.0
    )


def _reference_points(scan: LaserScan, mount: tuple[float, float, float]) -> np.ndarray:
    """End points in the robot frame written from the equations: ``m + r·(cos, sin)(θ_k + θ_m)``."""
    mx, my, mth = mount
    rows = []
    for k, r in enumerate(scan.ranges):
        if scan.range_min <= r < scan.range_max:
            phi = scan.angle_min + k * scan.angle_increment + mth
            rows.append((mx + r * math.cos(phi), my + r * math.sin(phi)))
    return np.array(rows, dtype=np.float64).reshape(-1, 2)


@settings(max_examples=60, deadline=None)
@given(
    ranges=st.lists(st.floats(0.0, 4.0), min_size=1, max_size=30),
    angle_min=st.floats(-math.pi, 0.0),
    mount=st.tuples(st.floats(-0.5, 0.5), st.floats(-0.5, 0.5), st.floats(-math.pi, math.pi)),
    resolution=st.sampled_from([0.05, 0.1, 0.25]),
)
def test_the_cells_are_those_of_the_end_points_in_the_robot_frame(
    ranges: list[float],
    angle_min: float,
    mount: tuple[float, float, float],
    resolution: float,
) -> None:
    scan = _scan(ranges, angle_min, 3.0 / len(ranges))
    grid = scan.to_local_grid(half_width=1.0, resolution=resolution, mount=mount)
    expected = LocalGrid.from_points(
        _reference_points(scan, mount), half_width=1.0, resolution=resolution
    )
    # Cells of points within rounding of a cell border may differ: compare away from them.
    points = _reference_points(scan, mount)
    on_border = np.abs((points / resolution + 0.5) % 1.0 - 0.5) > 0.5 - 1e-9
    if not on_border.any():
        np.testing.assert_array_equal(grid.occupied, expected.occupied)
    assert grid.occupied.shape == expected.occupied.shape


def test_a_sensor_ahead_of_the_centre_moves_every_return_ahead() -> None:
    scan = _scan([0.5, 0.5], 0.0, math.pi / 2)
    plain = np.argwhere(scan.to_local_grid().occupied)
    ahead = np.argwhere(scan.to_local_grid(mount=(0.3, 0.0, 0.0)).occupied)
    np.testing.assert_array_equal(ahead, plain + np.array([0, 3]))  # 0.3 m: three columns


def test_a_turned_sensor_is_the_scan_turned() -> None:
    scan = _scan([0.5, 0.9, 0.7, 1.2], -1.0, 0.5)
    turned = _scan([0.5, 0.9, 0.7, 1.2], -1.0 + 0.5, 0.5)
    np.testing.assert_array_equal(
        scan.to_local_grid(mount=(0.0, 0.0, 0.5)).occupied, turned.to_local_grid().occupied
    )


@pytest.mark.parametrize("mount", [None, (0.0, 0.0, 0.0), Pose2D(0.0, 0.0, 0.0)])
def test_no_mount_and_a_zero_mount_agree(mount: object) -> None:
    scan = _scan([0.4, 1.1, 2.5, 0.8], -math.pi / 2, 0.6)
    np.testing.assert_array_equal(
        scan.to_local_grid(mount=mount).occupied,  # type: ignore[arg-type]
        scan.to_local_grid().occupied,
    )


def test_the_mount_is_not_modified() -> None:
    mount = np.array([0.2, -0.1, 0.3])
    _scan([0.5, 1.0], 0.0, 0.5).to_local_grid(mount=mount)
    np.testing.assert_array_equal(mount, [0.2, -0.1, 0.3])


@pytest.mark.parametrize(
    ("mount", "error", "match"),
    [
        ((0.1, 0.2), ValueError, "mount must have length 3"),
        ((0.1, 0.2, math.nan), ValueError, "mount must contain only finite"),
        ((0.1, math.inf, 0.0), ValueError, "mount must contain only finite"),
        ("abc", TypeError, "mount must be a Pose2D"),
    ],
)
def test_a_bad_mount_is_refused_by_name(mount: object, error: type, match: str) -> None:
    with pytest.raises(error, match=match):
        _scan([0.5], 0.0, 0.1).to_local_grid(mount=mount)  # type: ignore[arg-type]
