"""Errors at the ends of the mapping ranges name the argument and the value (seventh review)."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from navkit.mapping import LaserScan, ScanMapper, rasterize_polygons


def _scan() -> LaserScan:
    return LaserScan(
        np.ones(10), angle_min=-1.0, angle_increment=0.2, range_min=0.1, range_max=10.0
    )


def test_mapper_odometry_increment_overflow_names_odometry() -> None:
    mapper = ScanMapper(resolution=0.1)
    mapper.update(_scan(), odometry=(0.0, 0.0, 0.0))
    mapper.update(_scan(), odometry=(1.7e308, 0.0, 0.0))
    trajectory = mapper.trajectory.copy()
    with pytest.raises(ValueError, match=r"^odometry: .*beyond ±1\.8e308"):
        mapper.update(_scan(), odometry=(-1.7e308, 0.0, 0.0))
    assert np.array_equal(mapper.trajectory, trajectory)  # nothing recorded
    assert len(mapper) == 2


def test_mapper_repeated_motion_overflow_says_so() -> None:
    mapper = ScanMapper(resolution=0.1)
    mapper.update(_scan(), odometry=(0.0, 0.0, 0.0))
    mapper.update(_scan(), odometry=(1.7e308, 0.0, 0.0))  # kept: outside the map
    with pytest.raises(ValueError, match="previous scan-to-scan motion") as info:
        mapper.update(_scan())
    assert "other" not in str(info.value) and "frame" not in str(info.value)
    assert len(mapper) == 2


@pytest.mark.parametrize(
    "bounds",
    [
        (1e9 - 1.0, 0.0, np.nextafter(1e9, 2e9), 1.0),
        (np.nextafter(-1e9, -2e9), 0.0, 0.0, 1.0),
    ],
)
def test_rasterize_bounds_message_shows_the_refused_value(bounds: tuple[float, ...]) -> None:
    with pytest.raises(ValueError, match="within ±1e9") as info:
        rasterize_polygons([], bounds=bounds, resolution=1.0)
    shown = [float(v) for v in re.findall(r"-?\d[\d.e+-]*", str(info.value).split("got", 1)[1])]
    assert shown == [float(v) for v in bounds]


def test_rasterize_empty_bounds_message_shows_the_values() -> None:
    bounds = (0.0, 0.1 + 0.2, 1.0, 0.30000000000000004)
    with pytest.raises(ValueError, match="max > min") as info:
        rasterize_polygons([], bounds=bounds, resolution=1.0)
    assert "0.30000000000000004" in str(info.value)


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_scan_angle_message_shows_the_refused_value(sign: float) -> None:
    angle = sign * (2 * math.pi + 1.0001e-5)  # just past the 1e-5 rad of slack
    with pytest.raises(ValueError, match="beyond ±2π") as info:
        LaserScan(np.ones(1), angle_min=angle, angle_increment=0.1, range_min=0.0, range_max=1.0)
    assert repr(angle) in str(info.value)
    edge = sign * (2 * math.pi + 1e-5)  # the limit itself is accepted
    assert LaserScan(np.ones(1), angle_min=edge, angle_increment=0.1, range_min=0.0, range_max=1.0)
