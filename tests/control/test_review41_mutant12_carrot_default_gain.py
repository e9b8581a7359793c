"""FollowTheCarrot's default heading gain is the documented 3.0 (MUTANT12).

Mutation review 41: the default ``heading_gain`` at 6.0 survived; the defaults
test read the signature's other defaults and no test commanded a turn with the
default gain. The docstring's claim is checked from the commands: a small heading
error ``e`` to the carrot turns at ``3.0 e`` while driving at ``max_speed``, so the
lateral error's poles, the roots of ``s² + k s + k v / d``, are the documented
−0.8 and −2.2 s⁻¹ (overdamped).
"""

from __future__ import annotations

import inspect

import numpy as np
import pytest

from navkit.control import FollowTheCarrot
from navkit.geometry import Pose2D


@pytest.mark.parametrize("error", [0.01, -0.05, 0.1])
def test_a_small_heading_error_turns_at_three_times_it(error: float) -> None:
    assert inspect.signature(FollowTheCarrot).parameters["heading_gain"].default == 3.0
    tracker = FollowTheCarrot()
    tracker.set_path([[0.0, 0.0], [2.0, 0.0]])
    # The carrot 0.3 m ahead on the x axis: the heading error is -theta, within the
    # default align_tolerance 0.1 rad, so the robot drives at once.
    cmd = tracker.step(Pose2D(0.0, 0.0, -error), 0.01)
    assert cmd.vx == 0.18
    assert cmd.omega == pytest.approx(3.0 * error, rel=1e-12)
    k, v, d = cmd.omega / error, cmd.vx, tracker.carrot_distance
    poles = np.sort(np.roots([1.0, k, k * v / d]).real)
    assert np.round(poles, 1).tolist() == [-2.2, -0.8]


def test_a_heading_error_beyond_the_align_tolerance_turns_in_place() -> None:
    tracker = FollowTheCarrot()
    tracker.set_path([[0.0, 0.0], [2.0, 0.0]])
    cmd = tracker.step(Pose2D(0.0, 0.0, -0.2), 0.01)
    assert cmd.vx == 0.0
    assert cmd.omega == pytest.approx(0.6, rel=1e-12)  # 3.0 x 0.2, below max_omega 1.5
