"""Fast paths of the small per-reading calls give the general path's results bit for bit.

``DiffOdometry.update`` (scalar arithmetic instead of a one-row batch),
``PlanarFusion.update_odometry`` (no generic dispatch) and
``OccupancyGrid.world_to_cell`` (float64 (N, 2) arrays straight to the kernel).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import DiffOdometry, PlanarFusion
from navkit.geometry import Pose2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid


@settings(max_examples=25, deadline=None)
@given(
    method=st.sampled_from(["arc", "midpoint", "first_order"]),
    bits=st.sampled_from([None, 8, 16, 32, 64]),
    track=st.floats(0.05, 3.0),
    radius=st.floats(0.01, 1.0),
    tpr=st.integers(1, 100_000),
    theta=st.floats(-3.14, 3.14),
    steps=st.lists(st.tuples(st.integers(-2000, 2000), st.integers(-2000, 2000)), max_size=30),
    start=st.integers(0, 2**31),
)
def test_diff_odometry_update_equals_batch(
    method: str,
    bits: int | None,
    track: float,
    radius: float,
    tpr: int,
    theta: float,
    steps: list[tuple[int, int]],
    start: int,
) -> None:
    drive = DiffDrive(track=track, wheel_radius=radius)
    kw = {"ticks_per_rev": tpr, "bits": bits, "method": method, "pose": (1.0, -2.0, theta)}
    fast = DiffOdometry(drive, **kw)  # type: ignore[arg-type]
    batch = DiffOdometry(drive, **kw)  # type: ignore[arg-type]
    modulus = 2 ** min(bits or 63, 63)
    left = right = start % modulus
    for i, (dl, dr) in enumerate(steps):
        left = (left + dl) % modulus
        right = (right + dr) % modulus
        # Python and NumPy integers both take the fast path.
        a, b = (left, right) if i % 2 else (np.int64(left), np.uint32(right % 2**32))
        if i % 2 == 0:
            right = int(b)
        pose = fast.update(a, b)  # type: ignore[arg-type]
        row = batch.update_batch([left], [right])[-1]
        assert (pose.x, pose.y, pose.theta) == (row[0], row[1], row[2])
        assert fast.pose == pose


def test_diff_odometry_update_bad_input_unchanged() -> None:
    odo = DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000, bits=16)
    odo.update(10, 10)
    for bad in (True, 1.0, "3", None, [1]):  # wrong types: the argument named, not the other
        with pytest.raises(TypeError, match=r"^left_ticks must "):
            odo.update(bad, 10)  # type: ignore[arg-type]
        with pytest.raises(TypeError, match=r"^right_ticks must "):
            odo.update(10, bad)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="16-bit counter"):
        odo.update(2**16, 10)
    assert odo.update(1010, 1010).x == pytest.approx(2 * math.pi * 0.1)


def test_diff_odometry_update_is_fast_for_ints() -> None:
    # Not a timing test: the scalar path must not build a batch (which allocates arrays).
    odo = DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000)
    calls = []
    original = DiffOdometry.update_batch

    def spy(self: DiffOdometry, *args: object) -> object:
        calls.append(args)
        return original(self, *args)  # type: ignore[arg-type]

    DiffOdometry.update_batch = spy  # type: ignore[method-assign,assignment]
    try:
        for i in range(5):
            odo.update(i, 2 * i)
    finally:
        DiffOdometry.update_batch = original  # type: ignore[method-assign]
    assert calls == []


@settings(max_examples=20, deadline=None)
@given(
    readings=st.lists(
        st.tuples(st.floats(0.0, 0.2), st.floats(-3.0, 3.0), st.floats(-2.0, 2.0)),
        min_size=1,
        max_size=20,
    )
)
def test_update_odometry_fast_path_equals_general(
    readings: list[tuple[float, float, float]],
) -> None:
    fast = PlanarFusion(t0=0.0)
    general = PlanarFusion(t0=0.0)
    t = 0.0
    for dt, v, w in readings:
        t += dt
        a = fast.update_odometry(t, v, w, v_variance=1e-3, omega_variance=2e-3)
        # np.float64 arguments skip the fast path.
        b = general.update_odometry(
            np.float64(t), v, w, v_variance=1e-3, omega_variance=2e-3  # type: ignore[arg-type]
        )
        assert a.accepted == b.accepted and a.reason == b.reason
        assert np.array_equal(a.residual, b.residual) and (a.nis == b.nis or math.isnan(a.nis))
        assert np.array_equal(fast.x, general.x) and np.array_equal(fast.P, general.P)
        assert fast.t == general.t


def test_update_odometry_fast_path_errors() -> None:
    fusion = PlanarFusion(t0=1.0)
    assert fusion.update_odometry(0.5, 1.0, 0.0, v_variance=1e-3, omega_variance=1e-3).reason
    with pytest.raises(ValueError, match="omega_variance"):
        fusion.update_odometry(2.0, 1.0, 0.0, v_variance=1e-3, omega_variance=0.0)
    with pytest.raises(ValueError, match="v"):
        fusion.update_odometry(2.0, math.inf, 0.0, v_variance=1e-3, omega_variance=1e-3)
    assert fusion.t == 1.0


def test_world_to_cell_fast_path() -> None:
    grid = OccupancyGrid.empty(width=5.0, height=4.0, resolution=0.1, origin=Pose2D(-1, -2, 0.3))
    pts = np.random.default_rng(1).uniform(-10, 10, size=(50, 2))
    fast = grid.world_to_cell(pts)
    general = grid.world_to_cell(pts.tolist())  # a list goes the general way
    assert fast.dtype == np.int64 and np.array_equal(fast, general)
    strided = np.asfortranarray(pts)
    assert np.array_equal(grid.world_to_cell(strided), fast)
    assert np.array_equal(grid.world_to_cell(pts[::2]), fast[::2])
    before = pts.copy()
    bad = pts.copy()
    bad[7, 1] = math.nan
    with pytest.raises(ValueError, match="points_xy"):
        grid.world_to_cell(bad)
    bad[7, 1] = -math.inf
    with pytest.raises(ValueError, match="points_xy"):
        grid.world_to_cell(bad)
    assert np.array_equal(pts, before)
    with pytest.raises(TypeError, match="continuous"):
        grid.world_to_cell(pts, continuous=1)  # type: ignore[call-overload]
