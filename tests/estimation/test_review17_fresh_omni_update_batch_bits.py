"""``OmniOdometry``: ``update`` and ``update_batch`` agree bit for bit, however the log is split.

The last review documented this ("``update`` and ``update_batch`` agree bit for
bit however the readings are split") and tested it only far from the origin,
where adding the start (spacing 9.3e-10 m at 5e6 m) hid the disagreement: the
robot-frame steps were ``inc @ forward_matrix.T``, a matrix product whose BLAS
sums a (T, N) batch in another order than the (1, N) row of ``update``
(OpenBLAS: the last bit of most rows). From the origin, 187 of 200 random runs
of 8 steps disagreed. Both now add the wheels' products in the same order
(``_body_steps``; Python floats in ``update``'s fast path).
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import OmniOdometry
from navkit.estimation._odometry import _body_steps
from navkit.kinematics import OmniDrive

_DRIVES = (
    OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2),
    OmniDrive([0.3, 1.9, 3.5, 5.0], wheel_radius=0.04, base_radius=0.25),
    OmniDrive([0.0, 1.0, 2.0, 3.0, 4.0, 5.5], wheel_radius=0.07, base_radius=0.3),
)
_STARTS = st.one_of(
    st.tuples(st.just(0.0), st.just(0.0), st.floats(-math.pi, math.pi)),
    st.tuples(st.floats(-1e3, 1e3), st.floats(-1e3, 1e3), st.floats(-math.pi, math.pi)),
    st.tuples(st.floats(4e5, 8e5), st.floats(0.0, 1e7), st.floats(-math.pi, math.pi)),
)


def _run(
    drive: OmniDrive,
    start: tuple[float, float, float],
    inc: np.ndarray,
    yaws: np.ndarray,
    splits: list[int],
) -> np.ndarray:
    """Poses after every step; split sizes 0 mean one ``update`` call."""
    odo = OmniOdometry(drive, pose=start)
    rows: list[np.ndarray] = []
    i = k = 0
    while i < inc.shape[0]:
        size = splits[k % len(splits)]
        k += 1
        if size == 0:
            pose = odo.update(np.array(inc[i]), float(yaws[i]))
            rows.append(pose.as_array())
            i += 1
        else:
            rows.extend(odo.update_batch(inc[i : i + size], yaws[i : i + size])[1:])
            i += size
    assert np.array_equal(rows[-1], odo.pose.as_array())
    return np.array(rows)


@settings(max_examples=60, deadline=None)
@given(
    drive=st.sampled_from(_DRIVES),
    start=_STARTS,
    seed=st.integers(0, 2**32 - 1),
    steps=st.integers(1, 60),
    scale=st.sampled_from([1e-3, 0.3, 50.0]),
    splits=st.lists(st.integers(0, 25), min_size=1, max_size=4),
)
def test_update_and_batches_agree_bit_for_bit(
    drive: OmniDrive,
    start: tuple[float, float, float],
    seed: int,
    steps: int,
    scale: float,
    splits: list[int],
) -> None:
    rng = np.random.default_rng(seed)
    inc = rng.normal(0.0, scale, (steps, drive.n_wheels))
    yaws = start[2] + np.cumsum(rng.normal(0.0, 0.5, steps))
    one_by_one = _run(drive, start, inc, yaws, [0])
    one_batch = _run(drive, start, inc, yaws, [steps])
    mixed = _run(drive, start, inc, yaws, splits)
    np.testing.assert_array_equal(one_by_one, one_batch)
    np.testing.assert_array_equal(one_by_one, mixed)


def test_from_the_origin_many_short_runs_agree() -> None:
    # The case the review found: 187 of 200 such runs disagreed in the last bits.
    drive = _DRIVES[0]
    rng = np.random.default_rng(0)
    for _ in range(200):
        inc = rng.normal(0.0, 0.3, (8, 3))
        yaws = np.cumsum(rng.normal(0.0, 0.2, 8))
        odo = OmniOdometry(drive)
        rows = [odo.update(inc[i], float(yaws[i])).as_array() for i in range(8)]
        batch = OmniOdometry(drive).update_batch(inc, yaws)[1:]
        np.testing.assert_array_equal(np.array(rows), batch)


@settings(max_examples=100, deadline=None)
@given(
    drive=st.sampled_from(_DRIVES),
    seed=st.integers(0, 2**32 - 1),
    steps=st.integers(0, 40),
)
def test_body_steps_is_the_forward_product(drive: OmniDrive, seed: int, steps: int) -> None:
    inc = np.random.default_rng(seed).normal(0.0, 10.0, (steps, drive.n_wheels))
    kept = inc.copy()
    bx, by = _body_steps(inc, drive.forward_matrix)
    exact = inc @ drive.forward_matrix.T
    # Each sum of N products is within N roundings of the sum of their magnitudes.
    bound = drive.n_wheels * np.finfo(float).eps * (np.abs(inc) @ np.abs(drive.forward_matrix.T))
    assert bx.shape == by.shape == (steps,)
    assert np.all(np.abs(bx - exact[:, 0]) <= bound[:, 0])
    assert np.all(np.abs(by - exact[:, 1]) <= bound[:, 1])
    np.testing.assert_array_equal(inc, kept)


def test_fast_path_and_general_path_take_the_same_sums() -> None:
    # The fast path (float64 ndarray, float yaw) and the general one (a list: update_batch
    # on one row) add the products in the same order: equal bits, for any stride.
    drive = _DRIVES[1]
    rng = np.random.default_rng(5)
    for _ in range(100):
        wide = rng.normal(0.0, 2.0, (drive.n_wheels, 2))
        inc = wide[:, 0]  # a strided view
        yaw = float(rng.uniform(-4.0, 4.0))
        start = (float(rng.normal(0, 100)), float(rng.normal(0, 100)), 0.5)
        fast = OmniOdometry(drive, pose=start).update(inc, yaw)
        general = OmniOdometry(drive, pose=start).update(inc.tolist(), np.float64(yaw))
        assert fast.as_array().tobytes() == general.as_array().tobytes()
