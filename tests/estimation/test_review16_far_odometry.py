"""Dead reckoning far from the origin: DiffOdometry / OmniOdometry at UTM coordinates.

A robot started at a UTM pose (x ~ 5e5 m, y ~ 5e6 m, where float64 values lie
5.8e-11 m and 9.3e-10 m apart) must move as the same robot started at the
origin, shifted: the motion does not depend on where it starts. Adding every
small step to the absolute coordinate rounds each sum at the coordinate's size,
and with steady steps the rounding has one sign: 1 mm steps at a northing of
5e6 m drifted by 0.3 mm per 1.5 km (2 cm per 100 km), 10^5 times what the
coordinates' own spacing forces, and :meth:`update` disagreed with
:meth:`update_batch` (which summed the steps first). The odometries now sum
the steps since the last set pose and add that pose at the end.

Checks, against the same run from the origin (whose own results are those of
the plain step-by-step model, bit for bit) and exact rational arithmetic:

* one reading at a time, in batches of any split, or mixed, gives the
  origin run's positions plus the start, to within a few spacings of the
  coordinates (hypothesis over starts, steps, methods and splits);
* a straight run of 10^5 equal steps at a UTM northing ends within 1e-8 m of
  the exact sum (it ended 2e-5 m off);
* ``update`` and ``update_batch`` agree far from the origin too (``OmniOdometry``'s
  bit for bit; ``DiffOdometry``'s to within a few spacings: a batch sums the
  turns, one reading at a time wraps each, so headings differ in the last bits);
* a start at the origin keeps its results bit for bit (the plain recurrence);
* copies and pickles (also a pickle from before the change) carry on alike.
"""

from __future__ import annotations

import copy
import math
import pickle
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import DiffOdometry, OmniOdometry
from navkit.geometry import Pose2D
from navkit.kinematics import DiffDrive, OmniDrive

DRIVE = DiffDrive(track=0.5, wheel_radius=0.1)
OMNI = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
#: UTM-like starts: eastings 4e5-8e5 m, northings 1e6-9e6 m, and a pose at 1e7 m.
EASTINGS = st.floats(4e5, 8e5)
NORTHINGS = st.floats(1e6, 1e7)
METHODS = st.sampled_from(["arc", "midpoint", "first_order"])


def _tolerance(*coordinates: float) -> float:
    """A few spacings of float64 at the coordinates' size: what the start itself forces."""
    return 4.0 * max(float(np.spacing(abs(c))) for c in coordinates)


def _diff_run(start: tuple[float, float, float], left: np.ndarray, right: np.ndarray,
              method: str, splits: list[int]) -> np.ndarray:
    """Poses after each reading; ``splits``: batch sizes (0 = one ``update`` call)."""
    odo = DiffOdometry(DRIVE, ticks_per_rev=4096, pose=start, method=method)  # type: ignore[arg-type]
    rows: list[np.ndarray] = []
    i = 0
    k = 0
    while i < left.shape[0]:
        size = splits[k % len(splits)]
        k += 1
        if size == 0:
            p = odo.update(int(left[i]), int(right[i]))
            rows.append(np.array([p.x, p.y, p.theta]))
            i += 1
        else:
            rows.extend(odo.update_batch(left[i : i + size], right[i : i + size]))
            i += size
    return np.array(rows)


@settings(max_examples=25, deadline=None)
@given(
    x0=EASTINGS,
    y0=NORTHINGS,
    theta=st.floats(-math.pi, math.pi),
    step=st.integers(1, 40),
    turn=st.integers(-3, 3),
    method=METHODS,
    splits=st.lists(st.integers(0, 120), min_size=1, max_size=4),
)
def test_diff_odometry_far_start_is_the_origin_run_shifted(
    x0: float, y0: float, theta: float, step: int, turn: int, method: str, splits: list[int]
) -> None:
    n = 1000
    # Steady wheel steps (the worst case for one-signed rounding), a slight curve.
    left = np.arange(n, dtype=np.int64) * step
    right = np.arange(n, dtype=np.int64) * (step + turn)
    # The same splits: a batch turns the heading by running sums, one reading at a
    # time by wrapped steps (the headings may differ in the last bits).
    near = _diff_run((0.0, 0.0, theta), left, right, method, splits)
    far = _diff_run((x0, y0, theta), left, right, method, splits)
    tol = _tolerance(x0 + 1e3, y0 + 1e3)
    assert np.abs(far[:, 0] - (x0 + near[:, 0])).max() <= tol
    assert np.abs(far[:, 1] - (y0 + near[:, 1])).max() <= tol
    np.testing.assert_array_equal(far[:, 2], near[:, 2])


@pytest.mark.parametrize("method", ["arc", "midpoint", "first_order"])
def test_diff_odometry_long_straight_run_at_a_utm_northing_matches_exact_sum(method: str) -> None:
    n = 100_000
    y0 = 5123456.5
    odo = DiffOdometry(DRIVE, ticks_per_rev=4096, pose=(512345.25, y0, math.pi / 2),
                       method=method)  # type: ignore[arg-type]
    for i in range(n + 1):
        odo.update(10 * i, 10 * i)
    step = 2.0 * math.pi * 0.1 / 4096 * 10.0  # metres per reading, as the odometry computes
    # Exact: the y step is sin(pi/2) * step = step in float64 (sin gives 1.0).
    assert math.sin(math.pi / 2) == 1.0
    exact = Fraction(y0) + n * Fraction(step)
    assert abs(Fraction(odo.pose.y) - exact) <= Fraction(1, 10**8)


@settings(max_examples=25, deadline=None)
@given(x0=EASTINGS, y0=NORTHINGS, method=METHODS, seed=st.integers(0, 2**32 - 1))
def test_diff_odometry_update_and_batch_agree_far_from_origin(
    x0: float, y0: float, method: str, seed: int
) -> None:
    rng = np.random.default_rng(seed)
    left = np.cumsum(rng.integers(-5, 30, 500))
    right = np.cumsum(rng.integers(-5, 30, 500))
    one_by_one = _diff_run((x0, y0, 0.5), left, right, method, [0])
    batch = _diff_run((x0, y0, 0.5), left, right, method, [500])
    # The headings may differ in the last bits (summed turns against wrapped steps).
    np.testing.assert_allclose(one_by_one[:, 2], batch[:, 2], rtol=0, atol=1e-12)
    tol = _tolerance(x0 + 1e3, y0 + 1e3)
    assert np.abs(one_by_one[:, :2] - batch[:, :2]).max() <= tol


def test_diff_odometry_origin_start_keeps_the_plain_recurrence_bit_for_bit() -> None:
    rng = np.random.default_rng(7)
    left = np.cumsum(rng.integers(-5, 30, 400))
    right = np.cumsum(rng.integers(-5, 30, 400))
    odo = DiffOdometry(DRIVE, ticks_per_rev=4096)
    scale = 2.0 * math.pi * 0.1 / 4096.0
    x = y = th = 0.0
    last = None
    for a, b in zip(left.tolist(), right.tolist(), strict=True):
        pose = odo.update(a, b)
        if last is not None:
            d_left = scale * float(a - last[0])
            d_right = scale * float(b - last[1])
            dc = 0.5 * d_right + 0.5 * d_left
            dth = (d_right - d_left) / 0.5
            h = 0.5 * dth
            sa = 1.0 - dth * dth / 6.0 + dth**4 / 120.0 if abs(dth) < 1e-4 else math.sin(dth) / dth
            sh = 1.0 - h * h / 6.0 + h**4 / 120.0 if abs(h) < 1e-4 else math.sin(h) / h
            dx, dy = dc * sa, dc * (math.sin(h) * sh)
            c, s = math.cos(th), math.sin(th)
            x = x + (c * dx - s * dy)
            y = y + (s * dx + c * dy)
            th = math.remainder(th + math.remainder(dth, 2 * math.pi), 2 * math.pi)
        last = (a, b)
        assert (pose.x, pose.y) == (x, y)


def test_diff_odometry_reset_pose_starts_a_new_sum() -> None:
    odo = DiffOdometry(DRIVE, ticks_per_rev=4096, pose=(512345.25, 5123456.5, 0.0))
    odo.update(0, 0)
    odo.update(1000, 1000)
    odo.reset((612345.75, 6123456.25, 0.0))
    assert odo.pose == Pose2D(612345.75, 6123456.25, 0.0)
    odo.update(0, 0)
    p = odo.update(4096, 4096)  # one wheel turn: 0.2 pi m along x
    assert p.x == 612345.75 + 2.0 * math.pi * 0.1 / 4096 * 4096.0
    assert p.y == 6123456.25
    odo.reset()  # counters only: the sum goes on
    odo.update(0, 0)
    q = odo.update(4096, 4096)
    assert q.x == 612345.75 + (2.0 * (2.0 * math.pi * 0.1 / 4096 * 4096.0))


@pytest.mark.parametrize("copier", [copy.copy, copy.deepcopy,
                                     lambda o: pickle.loads(pickle.dumps(o))])
def test_diff_odometry_copies_carry_on_alike(copier: object) -> None:
    odo = DiffOdometry(DRIVE, ticks_per_rev=4096, pose=(512345.25, 5123456.5, 0.3))
    for i in range(100):
        odo.update(7 * i, 9 * i)
    twin = copier(odo)  # type: ignore[operator]
    for i in range(100, 300):
        assert odo.update(7 * i, 9 * i) == twin.update(7 * i, 9 * i)


def test_odometry_pickled_before_the_change_loads_with_its_absolute_pose() -> None:
    # A pickle of the former slots (no sum since the last set pose) holds the pose
    # only: it restores as that pose, and carries on from it.
    odo = DiffOdometry(DRIVE, ticks_per_rev=4096)
    odo.update(0, 0)
    state = {slot: getattr(odo, slot) for slot in (
        "_bits", "_drive", "_high", "_last", "_low", "_method", "_modulus", "_pose",
        "_scale_left", "_scale_right", "_ticks_per_rev")}
    state["_pose"] = Pose2D(512345.25, 5123456.5, 0.0)
    old = DiffOdometry.__new__(DiffOdometry)
    old.__setstate__((None, state))
    assert old.pose == Pose2D(512345.25, 5123456.5, 0.0)
    p = old.update(4096, 4096)
    assert p.x == 512345.25 + 2.0 * math.pi * 0.1 / 4096 * 4096.0
    omni = OmniOdometry.__new__(OmniOdometry)
    omni.__setstate__((None, {"_drive": OMNI, "_pose": Pose2D(1e6, 2e6, 0.0)}))
    q = omni.update(OMNI.inverse([1.0, 0.0, 0.0]) * 0.1, 0.0)
    assert abs(q.x - (1e6 + 0.1)) <= 1e-9 and q.y == 2e6


def _omni_run(start: tuple[float, float, float], inc: np.ndarray, yaws: np.ndarray,
              splits: list[int]) -> np.ndarray:
    odo = OmniOdometry(OMNI, pose=start)
    rows: list[np.ndarray] = []
    i = 0
    k = 0
    while i < inc.shape[0]:
        size = splits[k % len(splits)]
        k += 1
        if size == 0:
            p = odo.update(np.array(inc[i]), float(yaws[i]))
            rows.append(np.array([p.x, p.y, p.theta]))
            i += 1
        else:
            rows.extend(odo.update_batch(inc[i : i + size], yaws[i : i + size])[1:])
            i += size
    return np.array(rows)


@settings(max_examples=30, deadline=None)
@given(
    x0=EASTINGS,
    y0=NORTHINGS,
    speed=st.floats(0.1, 2.0),
    yaw=st.floats(-math.pi, math.pi),
    splits=st.lists(st.integers(0, 120), min_size=1, max_size=4),
)
def test_omni_odometry_far_start_is_the_origin_run_shifted(
    x0: float, y0: float, speed: float, yaw: float, splits: list[int]
) -> None:
    n = 1000
    step = OMNI.inverse([speed, 0.3 * speed, 0.0]) * 0.001  # 1 kHz
    inc = np.tile(step, (n, 1))
    yaws = np.full(n, yaw)
    near = _omni_run((0.0, 0.0, yaw), inc, yaws, splits)
    far = _omni_run((x0, y0, yaw), inc, yaws, splits)
    tol = _tolerance(x0 + 1e3, y0 + 1e3)
    assert np.abs(far[:, 0] - (x0 + near[:, 0])).max() <= tol
    assert np.abs(far[:, 1] - (y0 + near[:, 1])).max() <= tol
    np.testing.assert_array_equal(far[:, 2], near[:, 2])


def test_omni_odometry_update_and_batch_agree_far_from_origin() -> None:
    rng = np.random.default_rng(11)
    inc = rng.normal(0.0, 0.05, (400, 3))
    yaws = np.cumsum(rng.normal(0.0, 0.01, 400))
    one_by_one = _omni_run((512345.25, 5123456.5, 0.0), inc, yaws, [0])
    batch = _omni_run((512345.25, 5123456.5, 0.0), inc, yaws, [400])
    np.testing.assert_array_equal(one_by_one, batch)
