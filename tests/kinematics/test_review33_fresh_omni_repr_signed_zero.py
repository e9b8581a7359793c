"""Review 33 (FRESH): a wheel at -0.0 rad keeps its sign through ``eval(repr(drive))``.

Review 32's repr prints the wheel angles in degrees where ``np.radians`` gives
them back bit for bit, testing ``float(text)``; but a wheel at -0.0 rad
printed ``-0``, which ``eval`` reads as the integer 0: ``radians([-0, 120,
240])`` is +0.0 rad, a different drive (its Jacobian's ``-sin`` entry +0.0
where the drive's is -0.0; ``eval(repr(drive)) == drive`` fails wherever the
drive is compared). Checked: against ``_omni.py`` of HEAD both tests fail.
"""

from __future__ import annotations

import numpy as np
from numpy import radians

from navkit.kinematics import OmniDrive


def _rebuilt(drive: OmniDrive) -> OmniDrive:
    rebuilt = eval(repr(drive), {"OmniDrive": OmniDrive, "radians": radians})
    assert isinstance(rebuilt, OmniDrive)
    return rebuilt


def test_a_wheel_at_negative_zero_round_trips_with_its_sign() -> None:
    drive = OmniDrive(np.radians([-0.0, 120.0, 240.0]), wheel_radius=0.05, base_radius=0.2)
    rebuilt = _rebuilt(drive)
    assert np.signbit(rebuilt.wheel_angles[0])
    np.testing.assert_array_equal(np.signbit(rebuilt.jacobian), np.signbit(drive.jacobian))
    assert repr(rebuilt) == repr(drive)


def test_the_layout_still_prints_in_degrees() -> None:
    drive = OmniDrive(np.radians([-0.0, 120.0, 240.0]), wheel_radius=0.05, base_radius=0.2)
    assert "wheel_angles=radians([-0.0, 120, 240])," in repr(drive)
    plain = OmniDrive(np.radians([0.0, 120.0, 240.0]), wheel_radius=0.05, base_radius=0.2)
    assert "wheel_angles=radians([0, 120, 240])," in repr(plain)
