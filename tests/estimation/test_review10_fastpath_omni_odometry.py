"""``OmniOdometry.update``: the one-step fast path equals the general (batch) path.

The fast path takes a float64 ndarray of the drive's shape and a finite Python
float yaw; anything else (here the same values as a list and a NumPy float64
yaw) goes through ``update_batch``. Both must give the same poses bit for bit,
leave the increments unchanged, and raise the same errors for the same bad
values, leaving the odometry unchanged.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import OmniOdometry
from navkit.geometry import Pose2D
from navkit.kinematics import OmniDrive

_DRIVES = (
    OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2),
    OmniDrive([0.3, 1.9, 3.5, 5.0], wheel_radius=0.04, base_radius=0.25),
)


def _bits(pose: Pose2D) -> tuple[float, float, float]:
    return (pose.x, pose.y, pose.theta)


@settings(max_examples=40, deadline=None)
@given(
    drive=st.sampled_from(_DRIVES),
    start=st.tuples(
        st.floats(-1e3, 1e3), st.floats(-1e3, 1e3), st.floats(-math.pi, math.pi)
    ),
    steps=st.lists(
        st.tuples(
            st.lists(st.floats(-50.0, 50.0), min_size=4, max_size=4),
            st.floats(-100.0, 100.0),
        ),
        min_size=1,
        max_size=10,
    ),
)
def test_fast_path_equals_general_path(
    drive: OmniDrive,
    start: tuple[float, float, float],
    steps: list[tuple[list[float], float]],
) -> None:
    fast = OmniOdometry(drive, pose=start)
    slow = OmniOdometry(drive, pose=start)
    for values, yaw in steps:
        inc = np.array(values[: drive.n_wheels])
        kept = inc.copy()
        a = fast.update(inc, yaw)
        b = slow.update(inc.tolist(), np.float64(yaw))  # not an ndarray: the batch path
        assert type(a) is Pose2D
        assert _bits(a) == _bits(b) == _bits(fast.pose) == _bits(slow.pose)
        assert inc.tobytes() == kept.tobytes()


def test_strided_and_read_only_increments_take_the_same_values() -> None:
    drive = _DRIVES[0]
    inc = np.array([[0.3, 9.0], [-0.2, 9.0], [0.05, 9.0]])[:, 0]  # a strided view
    frozen = inc.copy()
    frozen.setflags(write=False)
    poses = [OmniOdometry(drive).update(arg, 0.7) for arg in (inc, frozen, inc.tolist())]
    assert len({_bits(p) for p in poses}) == 1


@pytest.mark.parametrize(
    ("inc", "yaw", "name"),
    [
        ([0.1, math.nan, 0.2], 0.0, "wheel_increments"),
        ([0.1, math.inf, 0.2], 0.0, "wheel_increments"),
        ([0.1, 0.2, 0.3], math.nan, "yaw"),
        ([0.1, 0.2, 0.3], -math.inf, "yaw"),
        ([0.1, 0.2], 0.0, "wheel_increments"),  # wrong length
    ],
)
def test_bad_values_get_the_general_paths_error(
    inc: list[float], yaw: float, name: str
) -> None:
    errors = []
    for args in ((np.array(inc), yaw), (inc, np.float64(yaw))):
        odo = OmniOdometry(_DRIVES[0], pose=(1.0, 2.0, 0.5))
        with pytest.raises((TypeError, ValueError)) as info:
            odo.update(*args)
        assert _bits(odo.pose) == (1.0, 2.0, 0.5)
        errors.append((type(info.value), str(info.value)))
    assert errors[0] == errors[1]
    assert name in errors[0][1]


def test_an_overflowing_step_gets_the_general_paths_error() -> None:
    drive = OmniDrive.three_wheel(wheel_radius=1.0, base_radius=0.2)
    inc = [1.7e308, -1.7e308, 1.7e308]
    errors = []
    for args in ((np.array(inc), 0.0), (inc, np.float64(0.0))):
        odo = OmniOdometry(drive, pose=(1e308, 0.0, 0.0))
        with pytest.raises(ValueError, match="overflows") as info:
            odo.update(*args)
        assert _bits(odo.pose) == (1e308, 0.0, 0.0)
        errors.append(str(info.value))
    assert errors[0] == errors[1]


@pytest.mark.parametrize(
    "inc",
    [
        np.array([1, 2, 3]),  # integers
        np.array([0.1, 0.2, 0.3], dtype=np.float32),
        np.array([0.1, 0.2, 0.3], dtype=">f8"),  # float64, not native byte order
    ],
)
def test_other_arrays_give_the_float64_results(inc: np.ndarray) -> None:
    a = OmniOdometry(_DRIVES[0]).update(inc, 0.4)
    b = OmniOdometry(_DRIVES[0]).update(inc.astype(np.float64), 0.4)
    assert _bits(a) == _bits(b)
