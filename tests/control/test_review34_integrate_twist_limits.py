"""Review 34 (integrator lens): a Twist2D given to ``limit_velocity_change``.

A ROS node smooths its ``/cmd_vel`` between control steps: the natural call
passes the previous and the new ``Twist2D``. ``limit_velocity_change`` takes
velocity vectors in m/s, and a twist's ``(vx, vy, omega)`` mixes m/s with
rad/s, so one norm over the three would be wrong; the twist was refused with
"previous must hold real numbers, got an element of type Twist2D", which names
no element and does not say what to pass. The message now says it.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.control import limit_velocity_change
from navkit.geometry import Twist2D

LIMITS = {"max_accel": 0.5, "max_decel": 2.0, "dt": 0.1}


@pytest.mark.parametrize("which", ["previous", "desired", "both"])
def test_a_twist_is_refused_with_what_to_pass(which: str) -> None:
    twist = Twist2D(0.3, 0.0, 0.8)
    previous: object = twist if which in ("previous", "both") else [0.0, 0.0]
    desired: object = twist if which in ("desired", "both") else [0.5, 0.0]
    name = "desired" if which == "desired" else "previous"
    with pytest.raises(TypeError) as info:
        limit_velocity_change(previous, desired, **LIMITS)  # type: ignore[arg-type]
    message = str(info.value)
    assert message.startswith(f"{name} is a Twist2D")
    assert "rad/s" in message and "[twist.vx, twist.vy]" in message
    assert "element" not in message


def test_the_linear_part_the_message_names_is_limited() -> None:
    before, after = Twist2D(0.0, 0.0, 0.0), Twist2D(1.0, 0.0, 2.0)
    linear = limit_velocity_change(
        [before.vx, before.vy], [after.vx, after.vy], **LIMITS
    )
    assert np.allclose(linear, [0.05, 0.0], rtol=0, atol=1e-15)
    omega = limit_velocity_change([before.omega], [after.omega], **LIMITS)
    assert np.allclose(omega, [0.05], rtol=0, atol=1e-15)


def test_arrays_and_sequences_still_pass() -> None:
    out = limit_velocity_change(np.array([1.0, 0.0]), (0.0, 0.0), **LIMITS)
    assert np.allclose(out, [0.8, 0.0], rtol=0, atol=1e-15)
