"""Per-beam repulsion from a LaserScan against the point fields on ``scan.to_points()``."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.mapping import LaserScan
from navkit.planning import (
    KhatibRepulsion,
    PiecewiseRepulsion,
    piecewise_repulsive_force_from_scan,
    repulsive_force_from_scan,
)

# Real scanners report >= 1 cm; 0.0 and 0.005 exercise range_min and the zero-range guard.
reading = st.one_of(
    st.floats(0.01, 6.0),
    st.sampled_from([math.nan, math.inf, -math.inf, 0.0, 0.005]),
)


@st.composite
def scans(draw: st.DrawFn) -> LaserScan:
    inc = draw(st.floats(1e-3, 0.1)) * draw(st.sampled_from([1.0, -1.0]))
    # At most half a turn, so every angle stays within ±2π: larger ones can only be
    # degrees, which LaserScan refuses.
    n = draw(st.integers(1, min(400, int(3.1 / abs(inc)))))
    ranges = draw(st.lists(reading, min_size=n, max_size=n))
    angle_min = draw(st.floats(-math.pi, math.pi))
    range_min = draw(st.one_of(st.just(0.0), st.floats(0.01, 0.2)))
    range_max = draw(st.floats(range_min + 0.5, 8.0))
    return LaserScan(ranges, angle_min=angle_min, angle_increment=inc, range_min=range_min,
                     range_max=range_max)


def scan_of(ranges: list[float], angle_min: float, angle_increment: float) -> LaserScan:
    return LaserScan(ranges, angle_min=angle_min, angle_increment=angle_increment,
                     range_min=0.1, range_max=5.0)


def close(a: np.ndarray, b: np.ndarray, scale: float) -> bool:
    return bool(np.linalg.norm(a - b) <= 1e-12 * max(1.0, scale))


@settings(max_examples=50, deadline=None)
@given(scans(), st.floats(0.1, 10.0), st.floats(0.1, 3.0))
def test_khatib_kernel_equals_point_field(scan: LaserScan, k: float, d0: float) -> None:
    got = repulsive_force_from_scan(scan, k_rep=k, influence_radius=d0)
    points = scan.to_points()
    field = KhatibRepulsion(points, k_rep=k, influence_radius=d0)
    want = field.force([0.0, 0.0])[0]
    dist = np.linalg.norm(points, axis=1)
    dist = dist[(dist > 0.0) & (dist <= d0)]
    scale = k * float(np.sum(dist**-3.0))
    assert got.shape == (2,)
    assert close(got, want, scale), (got, want)


test_khatib_kernel_equals_point_field_thoroughly = slow_twin(
    test_khatib_kernel_equals_point_field, max_examples=150
)


@settings(max_examples=50, deadline=None)
@given(scans(), st.floats(0.1, 10.0), st.floats(0.1, 10.0), st.floats(0.0, 1.0),
       st.floats(0.1, 2.0))
def test_piecewise_kernel_equals_point_field(
    scan: LaserScan, delta: float, beta: float, r: float, s: float
) -> None:
    points = scan.to_points()
    # The force jumps at d = r; hypot(ρ cos, ρ sin) may round ρ across it.
    assume(bool(np.all(np.abs(np.linalg.norm(points, axis=1) - r) > 1e-9)))
    got = piecewise_repulsive_force_from_scan(scan, delta=delta, beta=beta, obstacle_radius=r,
                                              spread=s)
    want = PiecewiseRepulsion(points, delta=delta, beta=beta, obstacle_radius=r,
                              spread=s).force([0.0, 0.0])[0]
    assert close(got, want, (delta + beta * s) * len(scan)), (got, want)


test_piecewise_kernel_equals_point_field_thoroughly = slow_twin(
    test_piecewise_kernel_equals_point_field, max_examples=150
)


def test_invalid_and_distant_beams_contribute_nothing() -> None:
    ranges = [math.nan, math.inf, -math.inf, 0.05, 9.0, 10.0, 1.5, 2.0]
    geometry = {"angle_min": -1.0, "angle_increment": 0.25, "range_min": 0.1, "range_max": 9.0}
    scan = LaserScan(ranges, **geometry)
    # 0.05 < range_min, 9.0 == range_max (no return), 10 > range_max, 1.5 and 2.0 > d0.
    assert np.all(repulsive_force_from_scan(scan, k_rep=5.0, influence_radius=1.4) == 0.0)
    assert np.all(
        piecewise_repulsive_force_from_scan(scan, obstacle_radius=0.2, spread=1.0) == 0.0
    )
    # The same scan with a beam inside d0 pushes straight away from it.
    near = LaserScan([*ranges, 0.5], **geometry)
    force = repulsive_force_from_scan(near, k_rep=1.0, influence_radius=1.0)
    angle = -1.0 + 0.25 * 8
    np.testing.assert_allclose(force, -4.0 * np.array([math.cos(angle), math.sin(angle)]),
                               rtol=1e-14)


def test_beam_tables_follow_the_scan_geometry() -> None:
    a = scan_of([0.5, 0.5], 0.0, math.pi / 2)
    b = scan_of([0.5, 0.5], math.pi, math.pi / 2)
    c = scan_of([0.5, 0.5, 0.5], 0.0, math.pi / 2)
    for scan in (a, b, c, a):
        want = KhatibRepulsion(scan.to_points(), influence_radius=1.0).force([0.0, 0.0])[0]
        np.testing.assert_allclose(repulsive_force_from_scan(scan), want, atol=1e-12)


def test_gains_and_scan_type_are_checked() -> None:
    scan = scan_of([0.5], 0.0, 0.1)
    with pytest.raises(TypeError, match="scan"):
        repulsive_force_from_scan(np.array([0.5]))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="influence_radius"):
        repulsive_force_from_scan(scan, influence_radius=0.0)
    with pytest.raises(ValueError, match="influence_radius"):
        repulsive_force_from_scan(scan, influence_radius=math.inf)
    with pytest.raises(ValueError, match="k_rep"):
        repulsive_force_from_scan(scan, k_rep=-1.0)
    with pytest.raises(TypeError, match="k_rep"):
        repulsive_force_from_scan(scan, k_rep="1")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="spread"):
        piecewise_repulsive_force_from_scan(scan, spread=0.0)
    with pytest.raises(ValueError, match="obstacle_radius"):
        piecewise_repulsive_force_from_scan(scan, obstacle_radius=-0.1)
    with pytest.raises(ValueError, match="delta"):
        piecewise_repulsive_force_from_scan(scan, delta=-1.0)
    with pytest.raises(TypeError, match="beta"):
        piecewise_repulsive_force_from_scan(scan, beta=None)  # type: ignore[arg-type]
    # Integers and numpy scalars are accepted as gains.
    np.testing.assert_allclose(
        repulsive_force_from_scan(scan, k_rep=1, influence_radius=np.float64(1.0)), [-4.0, 0.0]
    )
    np.testing.assert_allclose(
        piecewise_repulsive_force_from_scan(scan, beta=np.float32(2.0), spread=1), [-1.0, 0.0]
    )


def test_gains_are_keyword_only() -> None:
    # Positional gains are easy to swap (k_rep and the radius are both floats).
    scan = scan_of([0.5], 0.0, 0.1)
    with pytest.raises(TypeError, match="positional"):
        repulsive_force_from_scan(scan, 1.0, 1.0)  # type: ignore[misc]
    with pytest.raises(TypeError, match="positional"):
        piecewise_repulsive_force_from_scan(scan, 1.0)  # type: ignore[misc]


def load_hokuyo(folder: Path, limit: int) -> list[LaserScan]:
    """The Hokuyo demo bag's scans (681 beams over ±2.0862 rad, 0.02-5.6 m)."""
    data = np.loadtxt(folder / "demo_scans.csv", delimiter=",", skiprows=1, max_rows=limit)
    return [
        LaserScan(row[3:], angle_min=-2.0862, angle_increment=0.0061359, range_min=0.02,
                  range_max=5.6)
        for row in data
    ]


def test_real_hokuyo_scans_match_the_point_field(shared_data: Path) -> None:
    scans_ = load_hokuyo(shared_data / "rosbag-hokuyo-laserscan-demo", 60)
    assert len(scans_) == 60 and len(scans_[0]) == 681
    pushed = 0
    for scan in scans_:
        got = repulsive_force_from_scan(scan, k_rep=0.5, influence_radius=1.5)
        want = KhatibRepulsion(scan.to_points(), k_rep=0.5,
                               influence_radius=1.5).force([0.0, 0.0])[0]
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12)
        pw = piecewise_repulsive_force_from_scan(scan, delta=3.0, beta=1.0, obstacle_radius=0.3,
                                                 spread=1.0)
        pw_want = PiecewiseRepulsion(scan.to_points(), delta=3.0, beta=1.0, obstacle_radius=0.3,
                                     spread=1.0)
        np.testing.assert_allclose(pw, pw_want.force([0.0, 0.0])[0], rtol=1e-12, atol=1e-12)
        pushed += bool(np.any(got != 0.0))
    # The recording has walls within 1.5 m: the test exercised real contributions.
    assert pushed > 0
