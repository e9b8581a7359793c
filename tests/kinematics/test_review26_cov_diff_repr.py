"""``DiffDrive``'s repr, which no test read (coverage review, session 30).

It names each wheel's radius and evaluates to an equal drive (unequal wheels
included), as the omni drive's repr does.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.kinematics import DiffDrive


@pytest.mark.parametrize(
    ("drive", "text"),
    [
        (DiffDrive(track=0.5, wheel_radius=0.1),
         "DiffDrive(track=0.5, left_radius=0.1, right_radius=0.1)"),
        (DiffDrive(track=0.32, left_radius=0.033, right_radius=0.0335),
         "DiffDrive(track=0.32, left_radius=0.033, right_radius=0.0335)"),
    ],
)  # fmt: skip
def test_repr_names_the_wheels_and_rebuilds_the_drive(drive: DiffDrive, text: str) -> None:
    assert repr(drive) == text
    twin = eval(text, {"DiffDrive": DiffDrive})
    assert (twin.track, twin.left_radius, twin.right_radius) == (
        drive.track, drive.left_radius, drive.right_radius
    )  # fmt: skip
    np.testing.assert_array_equal(twin.inverse([0.3, 0.0, 0.7]), drive.inverse([0.3, 0.0, 0.7]))
