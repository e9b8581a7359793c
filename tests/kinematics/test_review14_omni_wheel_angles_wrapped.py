"""``OmniDrive.wheel_angles`` reads the mounting angles wrapped to (-π, π].

navkit's angles are in (-π, π]; a drive built from ``radians([30, 150, 270])`` kept
270° as 4.712 rad. The property now wraps; the drive's matrices and repr still
come from the angles as given, so every result is unchanged bit for bit.
"""

from __future__ import annotations

import copy
import math
import pickle

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from numpy import radians  # noqa: F401  (eval of the repr)

from hypothesis_twins import slow_twin
from navkit.geometry import wrap_angle
from navkit.kinematics import OmniDrive


def test_three_wheel_reads_270_degrees_as_minus_90() -> None:
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    assert drive.wheel_angles[2] == -math.pi / 2
    assert not drive.wheel_angles.flags.writeable
    # The repr still names the layout as built.
    assert "radians([30, 150, 270])" in repr(drive)


def test_minus_pi_reads_plus_pi() -> None:
    drive = OmniDrive([-math.pi, -math.pi / 3, math.pi / 3], wheel_radius=0.05, base_radius=0.2)
    assert drive.wheel_angles.tolist() == [math.pi, -math.pi / 3, math.pi / 3]


_ANGLES = st.lists(st.floats(-50.0, 50.0), min_size=3, max_size=6)


@settings(max_examples=60, deadline=None)
@given(_ANGLES)
def test_wheel_angles_are_wrapped_and_results_unchanged(angles: list[float]) -> None:
    given_angles = np.array(angles)
    layout = np.column_stack((-np.sin(given_angles), np.cos(given_angles), np.ones(len(angles))))
    assume(np.linalg.cond(layout) < 1e8)  # a singular layout is refused: not this subject
    # Whole numbers beyond a full turn look like degrees and warn: not this subject
    # (found by the thorough twin in review 31: [0.0, 1.0, 7.0]).
    assume(not (np.max(np.abs(given_angles)) > 2 * np.pi and np.all(given_angles % 1.0 == 0.0)))
    r, big_l = 0.05, 0.2
    drive = OmniDrive(given_angles, wheel_radius=r, base_radius=big_l)
    wrapped = drive.wheel_angles
    assert np.all((wrapped > -math.pi) & (wrapped <= math.pi))
    np.testing.assert_array_equal(wrapped, wrap_angle(given_angles))
    # Same wheels: the angle moved by whole turns only.
    np.testing.assert_allclose(np.cos(wrapped), np.cos(given_angles), atol=1e-13)
    np.testing.assert_allclose(np.sin(wrapped), np.sin(given_angles), atol=1e-13)
    # The matrices are the given angles' (bit for bit), whatever the property reads.
    np.testing.assert_array_equal(drive.jacobian[:, 0], -np.sin(given_angles) / r)
    np.testing.assert_array_equal(drive.jacobian[:, 1], np.cos(given_angles) / r)
    # Built from its own (wrapped) reading, the drive is the same layout.
    twin = OmniDrive(wrapped, wheel_radius=r, base_radius=big_l)
    np.testing.assert_allclose(twin.jacobian, drive.jacobian, atol=1e-11)
    np.testing.assert_array_equal(twin.wheel_angles, wrapped)


test_wheel_angles_are_wrapped_and_results_unchanged_thoroughly = slow_twin(
    test_wheel_angles_are_wrapped_and_results_unchanged, max_examples=400
)


def test_copies_pickles_and_repr_agree() -> None:
    drive = OmniDrive(np.radians([0.0, 100.0, 200.0, 300.0]), wheel_radius=0.05, base_radius=0.2)
    speeds = [1.0, -2.0, 3.0, 0.5]
    for twin in (copy.copy(drive), copy.deepcopy(drive), pickle.loads(pickle.dumps(drive))):
        np.testing.assert_array_equal(twin.wheel_angles, drive.wheel_angles)
        assert not twin.wheel_angles.flags.writeable
        assert repr(twin) == repr(drive)
        assert twin.forward(speeds) == drive.forward(speeds)
    rebuilt = eval(repr(drive))  # the repr names the angles as given, to 6 digits
    np.testing.assert_allclose(rebuilt.wheel_angles, drive.wheel_angles, atol=1e-12)
    np.testing.assert_allclose(np.degrees(drive.wheel_angles), [0.0, 100.0, -160.0, -60.0])
