"""LaserScan (REP 117 readings, points, ROS look-alikes) and the robot-centred LocalGrid."""

from __future__ import annotations

import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, LocalGrid

HOKUYO = "rosbag-hokuyo-laserscan-demo/demo_scans.csv"


def hokuyo_msgs(shared_data: Path) -> list[SimpleNamespace]:
    """The demo bag's scans as sensor_msgs/LaserScan look-alikes (header from the README)."""
    table = np.loadtxt(shared_data / HOKUYO, delimiter=",", skiprows=1)
    return [
        SimpleNamespace(
            ranges=row[3:].astype(np.float32),
            angle_min=-2.0862,
            angle_max=2.0862,
            angle_increment=0.0061359,
            range_min=0.02,
            range_max=5.6,
            intensities=[],
            scan_time=0.1,
        )
        for row in table
    ]


def test_rep117_readings() -> None:
    scan = LaserScan(
        [1.0, math.inf, -math.inf, math.nan, 0.01, 10.0, 12.0, 9.99],
        0.0,
        0.1,
        range_min=0.05,
        range_max=10.0,
    )
    assert scan.valid_mask().tolist() == [True, False, False, False, False, False, False, True]
    assert len(scan.to_points()) == 2


def test_angles_are_wrapped_and_evenly_spaced() -> None:
    scan = LaserScan(np.ones(360), 0.0, 2 * math.pi / 360, 0.1, 5.0)
    angles = scan.angles()
    assert angles.min() > -math.pi and angles.max() <= math.pi
    assert np.allclose(np.cos(angles), np.cos(np.arange(360) * 2 * math.pi / 360))
    assert scan.angle_max == pytest.approx(359 * 2 * math.pi / 360)


@settings(max_examples=50, deadline=None)
@given(
    st.floats(-50, 50),
    st.floats(-50, 50),
    st.floats(-10, 10),
    st.lists(st.floats(0.2, 9.9), min_size=1, max_size=30),
)
def test_world_points_follow_the_papers_formula(
    x: float, y: float, theta: float, ranges: list[float]
) -> None:
    scan = LaserScan(ranges, -1.0, 0.07, 0.1, 10.0)
    pose = Pose2D(x, y, theta)
    pts = scan.to_points(pose)
    th = np.array([-1.0 + 0.07 * n for n in range(len(ranges))])
    d = np.asarray(ranges)
    # X_o = X + d cos(θ_n + θ), Y_o = Y + d sin(θ_n + θ)
    assert np.allclose(pts[:, 0], x + d * np.cos(th + theta), atol=1e-9)
    assert np.allclose(pts[:, 1], y + d * np.sin(th + theta), atol=1e-9)
    assert np.allclose(pose.transform_points(scan.to_points()), pts, atol=1e-9)
    assert np.allclose(scan.to_points([x, y, theta]), pts)


def test_scan_copies_and_freezes_its_arrays() -> None:
    ranges = np.array([1.0, 2.0])
    scan = LaserScan(ranges, 0.0, 0.1, 0.1, 5.0, intensities=[3.0, 4.0])
    ranges[0] = 99.0
    assert scan.ranges[0] == 1.0
    with pytest.raises(ValueError):
        scan.ranges[0] = 5.0
    assert scan.intensities is not None and scan.intensities.tolist() == [3.0, 4.0]


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"ranges": [[1.0]]}, "ranges must be 1-D"),
        ({"ranges": []}, "at least one beam"),
        ({"angle_increment": 0.0}, "angle_increment must be non-zero"),
        ({"angle_min": math.nan}, "angle_min must be finite"),
        ({"range_min": -1.0}, "range_min must be >= 0"),
        ({"range_max": 0.05}, "range_max .* must be greater than range_min"),
        ({"intensities": [1.0]}, "intensities must have the same length"),
    ],
)
def test_bad_scan_arguments(kwargs: dict[str, object], match: str) -> None:
    args: dict[str, object] = {
        "ranges": [1.0, 2.0],
        "angle_min": 0.0,
        "angle_increment": 0.1,
        "range_min": 0.1,
        "range_max": 5.0,
    }
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        LaserScan(**args)  # type: ignore[arg-type]


def test_bad_pose_is_named() -> None:
    scan = LaserScan([1.0], 0.0, 0.1, 0.1, 5.0)
    with pytest.raises(ValueError, match="pose"):
        scan.to_points([0.0, math.nan, 0.0])
    with pytest.raises(ValueError, match="pose"):
        scan.to_points([0.0, 1.0])


def test_from_msg_requires_the_ros_fields() -> None:
    with pytest.raises(TypeError, match="'range_max'"):
        LaserScan.from_msg(
            SimpleNamespace(ranges=[1.0], angle_min=0.0, angle_increment=0.1, range_min=0.1)
        )


def test_real_hokuyo_scans(shared_data: Path) -> None:
    msgs = hokuyo_msgs(shared_data)
    assert len(msgs) == 360
    for msg in msgs[::30]:
        scan = LaserScan.from_msg(msg)
        assert len(scan) == 681
        assert scan.intensities is None
        assert scan.angle_max == pytest.approx(2.0862, abs=1e-3)
        raw = np.asarray(msg.ranges, dtype=np.float64)
        # The driver reports 0 for beams without a valid echo: below range_min.
        expected = (raw >= 0.02) & (raw < 5.6)
        assert np.array_equal(scan.valid_mask(), expected)
        pts = scan.to_points()
        assert len(pts) == expected.sum()
        dist = np.hypot(pts[:, 0], pts[:, 1])
        assert np.allclose(np.sort(dist), np.sort(raw[expected]))
        # The scanner sees ±119.5° (README header values, rounded): no point behind it.
        bearing = np.arctan2(pts[:, 1], pts[:, 0])
        assert np.all(np.abs(bearing) <= 2.0862 + 1e-4)


# --------------------------------------------------------------------- LocalGrid
def test_turtlebot3_local_grid_indexing() -> None:
    # Eight beams 45° apart from -π; known returns, the rest +inf (nothing in range).
    r = math.inf
    ranges = [r, r, 0.7, r, 0.5, 0.4, 1.3, math.sqrt(2.0)]
    scan = LaserScan(ranges, -math.pi, math.pi / 4, 0.05, 3.5)
    grid = scan.to_local_grid()
    assert grid.occupied.shape == (21, 21)
    expected = {
        (math.floor(10 * y + 10 + 0.5), math.floor(10 * x + 10 + 0.5))  # i = 10y+10, j = 10x+10
        for x, y in scan.to_points()
        if abs(x) <= 1.05 and abs(y) <= 1.05
    }
    got = {(int(i), int(j)) for i, j in np.argwhere(grid.occupied)}
    assert got == expected
    # (0.5, 0) ahead, (0, -0.7) right, (-1, 1) back-left corner, (0.28, 0.28) diagonal;
    # the return 1.3 m to the left is outside the ±1 m grid.
    assert got == {(10, 15), (3, 10), (20, 0), (13, 13)}


@settings(max_examples=60, deadline=None)
@given(
    st.floats(0.1, 3.0),
    st.sampled_from([0.05, 0.1, 0.2, 0.25]),
    st.lists(st.tuples(st.floats(-4, 4), st.floats(-4, 4)), max_size=20),
)
def test_local_grid_any_size(
    half_width: float, resolution: float, points: list[tuple[float, float]]
) -> None:
    grid = LocalGrid.from_points(np.array(points).reshape(-1, 2), half_width, resolution)
    n = 2 * round(half_width / resolution) + 1
    assert grid.occupied.shape == (n, n)
    assert grid.half_width == pytest.approx((n - 1) / 2 * resolution)
    cells = grid.point_to_cell(np.array(points).reshape(-1, 2))
    inside = grid.contains(np.array(points).reshape(-1, 2))
    assert np.array_equal(inside, np.all((cells >= 0) & (cells < n), axis=1))
    assert grid.occupied.sum() == len({tuple(c) for c in cells[inside]})
    if inside.any():
        centres = grid.cell_to_point(cells[inside])
        assert np.all(np.abs(centres - np.array(points)[inside]) <= resolution / 2 + 1e-9)
    assert np.array_equal(grid.cell_to_point([n // 2, n // 2]), [[0.0, 0.0]])


def test_local_grid_validation() -> None:
    with pytest.raises(ValueError, match="n odd"):
        LocalGrid(np.zeros((4, 4), dtype=bool), 0.1, 0.15)
    with pytest.raises(ValueError, match="half_width must be"):
        LocalGrid(np.zeros((21, 21), dtype=bool), 0.1, 1.5)
    with pytest.raises(TypeError, match="boolean"):
        LocalGrid(np.zeros((3, 3)), 0.1, 0.1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="resolution must be > 0"):
        LocalGrid.from_points([[0.0, 0.0]], 1.0, -0.1)
    with pytest.raises(ValueError, match="integer"):
        LocalGrid.from_points([], 1.0, 0.1).cell_to_point([0.5, 1.0])
