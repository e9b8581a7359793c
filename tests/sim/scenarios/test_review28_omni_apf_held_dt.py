"""The omni-APF scenario's controller rate-limits by the time its command is held (review 28).

Last release's ``Observation.dt`` reached ``TrackerController`` and the soccer
players; the omni-APF controller still used the nominal ``1 / control_rate``.
Its rates divide (20 of 100 Hz), so no figure changes, but a control rate that
does not divide would have been limited by a period up to a physics step off.
"""

from __future__ import annotations

import numpy as np

from navkit.control import limit_velocity_change
from navkit.geometry import Pose2D
from navkit.sim import Observation
from navkit.sim.scenarios._omni_apf_setup import MAX_ACCEL, MAX_DECEL, ApfController

FAR = Pose2D(0.0, 0.0, 0.0)


def _first_speed(dt: float | None) -> float:
    controller = ApfController((3.0, 0.0), control_rate=20.0)
    twist = controller(Observation(0.0, None, None, None, None, (), FAR, FAR, dt=dt))
    return float(np.hypot(twist.vx, twist.vy))


def test_the_command_is_limited_by_the_held_time() -> None:
    want = np.array([10.0, 0.0])  # beyond any step's limit: the limit decides
    for dt in (0.03, 0.04):
        expected = limit_velocity_change(
            np.zeros(2), want, max_accel=MAX_ACCEL, max_decel=MAX_DECEL, dt=dt
        )
        assert _first_speed(dt) == float(np.hypot(*expected))


def test_without_dt_the_nominal_period_is_used() -> None:
    assert _first_speed(None) == _first_speed(1.0 / 20.0)
    assert _first_speed(None) != _first_speed(0.03)
