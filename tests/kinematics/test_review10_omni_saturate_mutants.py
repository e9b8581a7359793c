"""OmniDrive.saturate refuses wheel speeds for another number of wheels.

Found by mutation testing (session 14): dropping the check of the last axis
(``w.shape[-1] != n_wheels``) survived every other kinematics test.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.kinematics import OmniDrive


@pytest.mark.parametrize("shape", [(2,), (4,), (5, 2), (5, 4), (1, 1)])
def test_saturate_refuses_speeds_of_another_wheel_count(shape: tuple[int, ...]) -> None:
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    speeds = np.full(shape, 20.0)
    with pytest.raises(ValueError, match="wheel_speeds"):
        drive.saturate(speeds, max_wheel_speed=10.0)


def test_saturate_accepts_single_and_batched_commands_of_its_wheel_count() -> None:
    drive = OmniDrive(np.radians([0.0, 90.0, 180.0, 270.0]), wheel_radius=0.05, base_radius=0.2)
    one = drive.saturate([20.0, -10.0, 5.0, 0.0], max_wheel_speed=10.0)
    np.testing.assert_allclose(one, [10.0, -5.0, 2.5, 0.0])
    batch = drive.saturate([[20.0, -10.0, 5.0, 0.0], [1.0, 2.0, 3.0, 4.0]], max_wheel_speed=10.0)
    np.testing.assert_allclose(batch, [[10.0, -5.0, 2.5, 0.0], [1.0, 2.0, 3.0, 4.0]])
