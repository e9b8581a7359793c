"""Metrics refuses impossible figures, naming the field (session 30).

Negative durations, times and distances, a ``time_to_goal`` after the run's end
and a ``time_to_goal`` that disagrees with ``reached`` were accepted. NaN stays
where it means "does not apply"; every Metrics a Simulation builds still passes.
"""

from __future__ import annotations

import math
import pickle
from typing import Any

import pytest

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Metrics, Observation, Robot, Simulation, World

NAN = math.nan
FIELDS = ("reached", "reason", "duration", "time_to_goal", "final_error",
          "final_error_estimated", "estimate_error", "cross_track_mean", "cross_track_max",
          "min_clearance", "collisions", "distance")  # fmt: skip
GOOD: dict[str, Any] = dict(zip(FIELDS, (True, "goal reached", 10.0, 9.5, 0.04, 0.06, 0.02,
                                         0.01, 0.05, 0.3, 0, 4.2), strict=True))  # fmt: skip


def _metrics(**changes: Any) -> Metrics:
    return Metrics(**{**GOOD, **changes})


@pytest.mark.parametrize(
    "name",
    ["duration", "time_to_goal", "final_error", "final_error_estimated", "estimate_error",
     "cross_track_mean", "cross_track_max", "distance"],
)  # fmt: skip
@pytest.mark.parametrize("value", [-1e-300, -0.5, -math.inf])
def test_a_negative_time_or_distance_is_refused_naming_it(name: str, value: float) -> None:
    with pytest.raises(ValueError, match=rf"^{name} must be"):
        _metrics(**{name: value})


@pytest.mark.parametrize(
    "name",
    ["final_error", "final_error_estimated", "estimate_error", "cross_track_mean",
     "cross_track_max"],
)  # fmt: skip
def test_nan_stays_where_a_figure_does_not_apply(name: str) -> None:
    assert math.isnan(getattr(_metrics(**{name: NAN}), name))


def test_time_to_goal_is_nan_exactly_when_the_goal_was_not_reached() -> None:
    assert math.isnan(_metrics(reached=False, reason="timeout", time_to_goal=NAN).time_to_goal)
    with pytest.raises(ValueError, match=r"^time_to_goal must be NaN exactly when reached"):
        _metrics(reached=True, time_to_goal=NAN)
    with pytest.raises(ValueError, match=r"^time_to_goal must be NaN exactly when reached"):
        _metrics(reached=False, reason="timeout", time_to_goal=9.5)


def test_time_to_goal_lies_within_the_run() -> None:
    assert _metrics(time_to_goal=10.0).time_to_goal == 10.0  # reached at the last step
    assert _metrics(time_to_goal=0.0, duration=0.0).duration == 0.0  # at the goal at the start
    with pytest.raises(ValueError, match=r"^time_to_goal must be <= duration, got 10\.5 > 10\.0"):
        _metrics(time_to_goal=10.5)


def _forward(obs: Observation) -> Twist2D:
    return Twist2D(0.5, 0.0, 0.0)


@pytest.mark.parametrize(
    ("goal", "reference", "stop"),
    [(None, None, True), ((0.3, 0.0), [(0.0, 0.0), (1.0, 0.0)], True), ((0.3, 0.0), None, False),
     ((0.0, 0.0), None, True), ((9.0, 0.0), None, True)],
)  # fmt: skip
def test_every_run_still_builds_its_metrics(goal: Any, reference: Any, stop: bool) -> None:
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2)
    sim = Simulation(World(), robot, _forward, start=(0.0, 0.0, 0.0), duration=1.0, goal=goal,
                     reference_path=reference, stop_at_goal=stop)  # fmt: skip
    metrics = sim.run().metrics
    assert metrics.reached == (goal is not None and goal[0] < 1.0)
    assert metrics.duration == (1.0 if not metrics.reached or not stop else metrics.time_to_goal)
    # _forward drives straight at 0.5 m/s for the whole run (>= 0 held for any distance).
    assert metrics.distance == pytest.approx(0.5 * metrics.duration, rel=1e-12, abs=1e-15)
    assert pickle.loads(pickle.dumps(metrics)) == metrics
