"""Sensor faults flowing into the controllers: a spike in the measured velocity."""

from __future__ import annotations

import math

import pytest

from navkit.control import PotentialFieldController
from navkit.estimation import PlanarFusion
from navkit.geometry import Twist2D


# The norm of a change near 1e300 m/s overflows inside the limiter (documented: it may
# warn; the change is then measured scaled).
@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning")
@pytest.mark.parametrize("drive", ["omni", "diff"])
@pytest.mark.parametrize(
    "velocity", [(1e300, 0.0, 0.0), (-1e300, 0.0, 0.0), (0.0, 1e300, 0.0), (1e6, 0.0, 1e6)]
)
def test_potential_field_command_stays_within_max_speed_after_a_velocity_spike(
    drive: str, velocity: tuple[float, float, float]
) -> None:
    ctl = PotentialFieldController(drive=drive, max_speed=0.5)  # type: ignore[arg-type]
    ctl.step((0.0, 0.0, 0.0), (2.0, 0.0, 0.0), dt=0.05)
    cmd = ctl.step((0.0, 0.0, 0.3), (2.0, 0.0, 0.0), dt=0.05, velocity=velocity)
    assert math.hypot(cmd.vx, cmd.vy) <= 0.5 * (1.0 + 1e-12)
    # The controller keeps working with good measurements afterwards.
    cmd = ctl.step((0.0, 0.0, 0.3), (2.0, 0.0, 0.0), dt=0.05, velocity=Twist2D(0.4, 0.0, 0.0))
    assert math.hypot(cmd.vx, cmd.vy) <= 0.5 * (1.0 + 1e-12)
    assert math.hypot(float(ctl.previous_velocity[0]), float(ctl.previous_velocity[1])) <= 0.5 * (
        1.0 + 1e-12
    )


@pytest.mark.parametrize("drive", ["omni", "diff"])
def test_odometry_spike_through_fusion_does_not_reach_the_command(drive: str) -> None:
    # Wheel odometry -> PlanarFusion (no gate: the spike is applied, as documented)
    # -> the controller's measured velocity: the command must not follow the spike.
    fusion = PlanarFusion()
    for i in range(20):
        fusion.update_odometry(0.01 * i, 0.3, 0.0, v_variance=1e-4, omega_variance=1e-4)
    fusion.update_odometry(0.2, 1e6, 0.0, v_variance=1e-4, omega_variance=1e-4)
    v = float(fusion.x[3])
    assert v > 1e5  # the spike is in the estimate
    ctl = PotentialFieldController(drive=drive, max_speed=0.5)  # type: ignore[arg-type]
    cmd = ctl.step(fusion.pose, (2.0, 0.0, 0.0), dt=0.05, velocity=(v, 0.0, float(fusion.x[4])))
    assert math.hypot(cmd.vx, cmd.vy) <= 0.5 * (1.0 + 1e-12)
    # Slowing from a real overspeed below the spike's scale is still bounded by max_speed.
    cmd = ctl.step(fusion.pose, (2.0, 0.0, 0.0), dt=0.05, velocity=(0.6, 0.0, 0.0))
    assert math.hypot(cmd.vx, cmd.vy) <= 0.5 * (1.0 + 1e-12)
