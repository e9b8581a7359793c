"""0-d integer ticks take ``DiffOdometry.update``'s fast path (review 32, latency).

A counter reading picked out of an array with ``arr[i, ...]`` (or
``np.asarray`` of a message field) is a 0-d array, not a NumPy scalar: it went
:meth:`DiffOdometry.update_batch`'s way, about 0.13 ms a call instead of 2 us,
and the first such call compiled ``exp_forward_array`` (0.2 s; 7 ms from the
disk cache) if no batch had run yet. It is now read as the integer it holds.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.estimation import DiffOdometry
from navkit.kinematics import DiffDrive

_READINGS = [(0, 0), (500, 700), (1200, 900), (65530, 3)]


def _odometry(bits: int | None) -> Any:
    # Any: update is typed for ints, and these tests pass it 0-d arrays.
    return DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=1000, bits=bits)


@pytest.mark.parametrize("dtype", [np.int64, np.int32, np.uint16])
def test_0d_ticks_do_not_go_the_batch_way(dtype: Any, monkeypatch: pytest.MonkeyPatch) -> None:
    odo = _odometry(16)

    def batch(*args: object) -> None:
        raise AssertionError("update_batch called for one 0-d reading")

    monkeypatch.setattr(DiffOdometry, "update_batch", batch)
    for left, right in _READINGS:
        odo.update(np.array(left, dtype=dtype), np.array(right, dtype=dtype))


@pytest.mark.parametrize("bits", [None, 16])
def test_0d_ticks_give_the_int_poses_bit_for_bit(bits: int | None) -> None:
    plain, zero_d = _odometry(bits), _odometry(bits)
    for left, right in _READINGS:
        want = plain.update(left, right)
        got = zero_d.update(np.array(left), np.array(right))
        assert (got.x, got.y, got.theta) == (want.x, want.y, want.theta)


@pytest.mark.parametrize("value", [np.array(1.0), np.array(True), np.array(3, dtype=object)])
def test_0d_non_integers_are_still_refused(value: np.ndarray) -> None:
    odo = _odometry(None)
    odo.update(0, 0)
    with pytest.raises(TypeError, match="left_ticks"):
        odo.update(value, 2)
