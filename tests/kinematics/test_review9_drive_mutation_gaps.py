"""Review 9 (mutation testing): documented promises of the drives that no test pinned down."""

from __future__ import annotations

import numpy as np
import pytest

from navkit.geometry import Twist2D, wrap_angle
from navkit.kinematics import DiffDrive, OmniDrive


def test_omni_drive_keeps_its_own_copy_of_the_wheel_angles() -> None:
    # Inputs are never modified (not even their writeable flag), and changing the
    # caller's array afterwards does not move the drive's wheels.
    angles = np.radians([30.0, 150.0, 270.0])
    expected = angles.copy()
    drive = OmniDrive(angles, wheel_radius=0.05, base_radius=0.2)
    assert angles.flags.writeable
    speeds = drive.inverse(Twist2D(1.0, 0.5, 0.25))
    angles[:] = 0.0
    np.testing.assert_array_equal(drive.wheel_angles, wrap_angle(expected))
    np.testing.assert_array_equal(drive.inverse(Twist2D(1.0, 0.5, 0.25)), speeds)
    assert not drive.wheel_angles.flags.writeable


def test_omni_saturate_returns_commands_at_the_limit_unchanged() -> None:
    # "commands already within the limit are returned unchanged": a command whose
    # fastest wheel is exactly at the limit is within it, so it comes back bit for
    # bit (scaling it by limit / peak = 1 as (w / peak) * limit would round).
    drive = OmniDrive(np.radians([0.0, 90.0, 180.0, 270.0]), wheel_radius=0.05, base_radius=0.2)
    rng = np.random.default_rng(9)
    commands = rng.uniform(-3.0, 3.0, size=(200, 4))
    limits = np.max(np.abs(commands), axis=1)
    for command, limit in zip(commands, limits, strict=True):
        out = drive.saturate(command, max_wheel_speed=float(limit))
        np.testing.assert_array_equal(out, command)
    # The batch form, each row at its own peak: the largest peak is the limit.
    top = float(limits.max())
    at_top = commands[limits == top]
    np.testing.assert_array_equal(drive.saturate(at_top, max_wheel_speed=top), at_top)


@pytest.mark.parametrize("vy", [-1e-300, -0.1, -5.0])
def test_diff_drive_refuses_any_lateral_velocity_not_only_positive(vy: float) -> None:
    drive = DiffDrive(track=0.4, wheel_radius=0.05)
    with pytest.raises(ValueError, match="vy"):
        drive.inverse(Twist2D(1.0, vy, 0.2))
    with pytest.raises(ValueError, match="vy"):
        drive.inverse_batch([[1.0, vy, 0.2], [0.5, 0.0, 0.0]])
    with pytest.raises(ValueError, match="vy"):
        drive.inverse_batch([[0.5, 0.0, 0.0], [1.0, vy, 0.2]])
    # Dropped on request: the speeds of the twist without vy.
    np.testing.assert_array_equal(
        drive.inverse(Twist2D(1.0, vy, 0.2), ignore_lateral=True), drive.inverse([1.0, 0.0, 0.2])
    )


@pytest.mark.parametrize("bits", [2, 16, 33, 63])
def test_tick_delta_refuses_readings_just_below_the_signed_range(bits: int) -> None:
    from navkit.kinematics import tick_delta

    lowest = -(2 ** (bits - 1))  # the smallest reading of a signed bits-bit counter
    highest = 2**bits - 1  # the largest of an unsigned one
    # The limits themselves are valid readings; one step past either is refused.
    assert tick_delta(lowest, lowest + 1, bits=bits) == 1
    assert tick_delta(highest, 0, bits=bits) == 1
    for name, args in (("previous", (lowest - 1, 0)), ("current", (0, lowest - 1))):
        with pytest.raises(ValueError, match=name):
            tick_delta(*args, bits=bits)
        with pytest.raises(ValueError, match=name):
            tick_delta(np.array([args[0], 0]), np.array([args[1], 0]), bits=bits)
    with pytest.raises(ValueError, match="current"):
        tick_delta(0, highest + 1, bits=bits)
