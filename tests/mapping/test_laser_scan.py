"""LaserScan: REP 117 readings, points, keyword-only geometry, real Hokuyo scans."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan
from navkit.mapping.io import scan_from_msg

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
        angle_min=0.0,
        angle_increment=0.1,
        range_min=0.05,
        range_max=10.0,
    )
    assert scan.valid_mask().tolist() == [True, False, False, False, False, False, False, True]
    assert len(scan.to_points()) == 2


def test_angles_are_wrapped_and_evenly_spaced() -> None:
    scan = LaserScan(
        np.ones(360), angle_min=0.0, angle_increment=2 * math.pi / 360, range_min=0.1, range_max=5.0
    )
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
    scan = LaserScan(ranges, angle_min=-1.0, angle_increment=0.07, range_min=0.1, range_max=10.0)
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
    scan = LaserScan(
        ranges,
        angle_min=0.0,
        angle_increment=0.1,
        range_min=0.1,
        range_max=5.0,
        intensities=[3.0, 4.0],
    )
    ranges[0] = 99.0
    assert scan.ranges[0] == 1.0
    with pytest.raises(ValueError):
        scan.ranges[0] = 5.0
    assert scan.intensities is not None and scan.intensities.tolist() == [3.0, 4.0]


def test_copied_and_unpickled_scans_stay_read_only(
    duplicate: Callable[[LaserScan], LaserScan],
) -> None:
    # pickle and deepcopy rebuild the fields without __post_init__; the copied
    # arrays used to come back writable, so the "frozen" scan could change.
    for intensities in ([3.0, 4.0], None):
        scan = LaserScan([1.0, math.inf], angle_min=-0.5, angle_increment=0.25, range_min=0.1,
                         range_max=5.0, intensities=intensities)  # fmt: skip
        twin = duplicate(scan)
        with pytest.raises(ValueError, match="read-only"):
            twin.ranges[0] = 2.0
        np.testing.assert_array_equal(twin.ranges, scan.ranges)
        if intensities is None:
            assert twin.intensities is None
        else:
            assert twin.intensities is not None
            with pytest.raises(ValueError, match="read-only"):
                twin.intensities[0] = 2.0
            np.testing.assert_array_equal(twin.intensities, intensities)
        assert (twin.angle_min, twin.angle_increment, twin.range_min, twin.range_max) == (
            -0.5, 0.25, 0.1, 5.0,
        )  # fmt: skip


def test_non_finite_intensities_are_kept_as_given() -> None:
    given_values = [math.nan, -math.inf, math.inf]
    scan = LaserScan([1.0, 2.0, 3.0], angle_min=0.0, angle_increment=0.1, range_min=0.1,
                     range_max=5.0, intensities=given_values)  # fmt: skip
    assert scan.intensities is not None
    np.testing.assert_array_equal(scan.intensities, given_values)


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
    scan = LaserScan([1.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0)
    with pytest.raises(ValueError, match="pose"):
        scan.to_points([0.0, math.nan, 0.0])
    with pytest.raises(ValueError, match="pose"):
        scan.to_points([0.0, 1.0])


def test_geometry_is_keyword_only() -> None:
    # Four floats in a row are easy to swap: only the ranges are positional.
    with pytest.raises(TypeError, match="positional"):
        LaserScan([1.0], 0.0, 0.1, 0.1, 5.0)  # type: ignore[call-arg]
    assert not hasattr(LaserScan, "from_msg")  # moved to navkit.mapping.io.scan_from_msg


def test_to_local_grid_options_are_keyword_only() -> None:
    scan = LaserScan([0.5], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0)
    grid = scan.to_local_grid(half_width=0.6, resolution=0.2)
    assert grid.size == 7 and grid.resolution == 0.2
    assert grid.half_width == pytest.approx(0.6)
    assert grid.occupied[3, 6] and grid.occupied.sum() == 1
    with pytest.raises(TypeError, match="positional"):
        scan.to_local_grid(0.6, 0.2)  # type: ignore[call-arg]


def test_real_hokuyo_scans(shared_data: Path) -> None:
    msgs = hokuyo_msgs(shared_data)
    assert len(msgs) == 360
    for msg in msgs[::30]:
        scan = scan_from_msg(msg)
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


# ------------------------------------------------------------ issue 12: bad input
def scan_args(**kwargs: object) -> dict[str, object]:
    args: dict[str, object] = {
        "ranges": [1.0, 2.0],
        "angle_min": 0.0,
        "angle_increment": 0.1,
        "range_min": 0.1,
        "range_max": 5.0,
    }
    args.update(kwargs)
    return args


def test_degrees_given_as_radians_are_refused() -> None:
    # The scan: 361 beams from -180 with 1.0 apart span 360 rad.
    with pytest.raises(ValueError, match=r"span 360 rad .*look like degrees"):
        LaserScan(np.ones(361), angle_min=-180.0, angle_increment=1.0, range_min=0.1, range_max=5)
    with pytest.raises(ValueError, match=r"angle_min \(-90 rad\) lies beyond ±2π.*degrees"):
        LaserScan(np.ones(3), angle_min=-90.0, angle_increment=0.01, range_min=0.1, range_max=5)
    with pytest.raises(ValueError, match=r"angle_max .* lies beyond ±2π"):
        LaserScan(np.ones(3), angle_min=6.0, angle_increment=0.5, range_min=0.1, range_max=5)
    with pytest.raises(ValueError, match=r"angle_increment \(10\.0 rad\) exceeds a full turn"):
        LaserScan([1.0], angle_min=0.0, angle_increment=10.0, range_min=0.1, range_max=5)


@pytest.mark.parametrize(
    ("n", "angle_min", "increment"),
    [
        (360, -math.pi, 2 * math.pi / 360),  # a full turn, last beam one step short of π
        (361, -math.pi, 2 * math.pi / 360),  # first and last beam both at ±π
        (1081, -2.356194, 0.004363323),  # a Hokuyo UTM-30LX, 270°
        (1440, float(np.float32(-math.pi)), float(np.float32(2 * math.pi / 1440))),  # float32
        (720, 2 * math.pi, -2 * math.pi / 720),  # clockwise from 2π
    ],
)
def test_real_scanner_geometries_are_accepted(n: int, angle_min: float, increment: float) -> None:
    scan = LaserScan(
        np.ones(n), angle_min=angle_min, angle_increment=increment, range_min=0.1, range_max=5
    )
    assert len(scan) == n and np.all(np.abs(scan.angles()) <= math.pi)


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"ranges": [1 + 1j, 2.0]}, TypeError, "ranges must hold real numbers"),
        ({"ranges": np.array([1.0, 2.0]) * (1 + 0j)}, TypeError, "ranges must hold real"),
        ({"ranges": ["1.0", "2.0"]}, TypeError, "ranges must hold real numbers"),
        ({"ranges": [True, False]}, TypeError, "ranges must hold real numbers"),
        ({"intensities": [1j, 2.0]}, TypeError, "intensities must hold real numbers"),
        ({"angle_min": "0.0"}, TypeError, "angle_min must be a real number"),
        ({"range_max": True}, TypeError, "range_max must be a real number"),
        ({"range_max": 2e9}, ValueError, r"range_max must be > 0 and <= 1e9 m"),
        ({"range_max": math.inf}, ValueError, "range_max must be finite"),
        ({"range_min": 5.0}, ValueError, "range_max .* must be greater than range_min"),
    ],
)
def test_scan_types_and_ranges(
    kwargs: dict[str, object], error: type[Exception], match: str
) -> None:
    with pytest.raises(error, match=match):
        LaserScan(**scan_args(**kwargs))  # type: ignore[arg-type]


def test_scan_built_from_lists_copies_and_never_freezes_the_callers_array() -> None:
    ranges = [1.0, 2.0]
    scan = LaserScan(ranges, angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0)
    ranges[0] = 9.0
    assert scan.ranges.tolist() == [1.0, 2.0] and not scan.ranges.flags.writeable
    mine = np.array([1.0, 2.0])
    intensities = np.array([3.0, 4.0])
    scan = LaserScan(
        mine,
        angle_min=0.0,
        angle_increment=0.1,
        range_min=0.1,
        range_max=5.0,
        intensities=intensities,
    )
    assert mine.flags.writeable and intensities.flags.writeable
    mine[0] = intensities[0] = 7.0
    assert scan.ranges[0] == 1.0 and scan.intensities is not None and scan.intensities[0] == 3.0


def test_to_local_grid_refuses_huge_grids_before_allocating() -> None:
    scan = LaserScan([1.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0)
    # MemoryError (364 TiB) in the issue.
    with pytest.raises(ValueError, match=r"would need 4e\+14 cells \(364 TiB of bool\)"):
        scan.to_local_grid(half_width=1e4, resolution=1e-3)
    with pytest.raises(ValueError, match=r"resolution must be >= 1e-6"):
        scan.to_local_grid(half_width=1e308, resolution=1e-308)


def test_scan_from_msg_checks_like_laser_scan() -> None:
    from navkit.mapping.io import scan_from_msg

    fields = {
        "ranges": [1.0, 2.0],
        "angle_min": 0.0,
        "angle_increment": 0.1,
        "range_min": 0.1,
        "range_max": 5.0,
    }
    with pytest.raises(TypeError, match="ranges must hold real numbers"):
        scan_from_msg(SimpleNamespace(**{**fields, "ranges": [1 + 1j, 2.0]}))
    with pytest.raises(TypeError, match="intensities must hold real numbers"):
        scan_from_msg(SimpleNamespace(**fields, intensities=["a", "b"]))
    with pytest.raises(ValueError, match="degrees"):
        scan_from_msg(SimpleNamespace(**{**fields, "angle_min": -135.0}))
