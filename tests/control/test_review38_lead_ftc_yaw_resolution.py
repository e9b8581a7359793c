"""``FollowTheCarrot`` finishes with a yaw tolerance near float64's heading resolution (review 38).

Its final turn is proportional (``heading_gain`` × error). Once that step's turn
fell below the spacing of float64 headings (4.4e-16 rad near ±π), adding it to
the heading changed nothing: with a ``yaw_tolerance`` of 1e-300 (or 1e-15) the
robot stopped a few float steps short of the goal yaw and ``done`` never came
(20 of 20 random goals at 1e-300, 6-11 of 20 at 1e-15; found by TRACK2). The
last bit of the error is now turned at once. Fails on the code before.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.control import FollowTheCarrot
from navkit.geometry import Pose2D, integrate


def _finish(drive: str, tolerance: float, seed: int) -> tuple[bool, float, float]:
    rng = np.random.default_rng(seed)
    tracker = FollowTheCarrot(drive=drive, yaw_tolerance=tolerance)  # type: ignore[arg-type]
    goal = rng.uniform(-2.0, 2.0, size=2)
    goal_yaw = float(rng.uniform(-math.pi, math.pi))
    tracker.set_path(np.array([[0.0, 0.0], goal]), goal_yaw=goal_yaw)
    pose = Pose2D(0.0, 0.0, float(rng.uniform(-3.0, 3.0)))
    for _ in range(3000):  # 150 s; well under half is needed
        if tracker.done:
            break
        pose = integrate(pose, tracker.step(pose, 0.05), 0.05)
    error = abs(math.remainder(goal_yaw - pose.theta, 2.0 * math.pi))
    return tracker.done, error, goal_yaw


@pytest.mark.parametrize("drive", ["diff", "omni"])
@pytest.mark.parametrize("tolerance", [1e-300, 1e-15])
@pytest.mark.parametrize("seed", range(8))
def test_a_tolerance_at_the_heading_resolution_is_met(
    drive: str, tolerance: float, seed: int
) -> None:
    done, error, _ = _finish(drive, tolerance, seed)
    assert done
    assert error <= tolerance  # on the goal yaw itself, not merely stopped


@pytest.mark.parametrize("seed", range(4))
def test_an_ordinary_tolerance_ends_as_the_proportional_turn_leaves_it(seed: int) -> None:
    # The last-bit turn never acts above the resolution: the default tolerance is met
    # by the proportional law, with an error neither zero nor above the tolerance.
    done, error, _ = _finish("diff", 0.01, seed)
    assert done
    assert 0.0 < error <= 0.01
