"""Tenth review, exception safety: what a run that fails part-way leaves behind.

A controller or an estimator that raises (a ``KeyboardInterrupt`` too) ends
the run with its exception, unchanged; the Simulation then counts as run, the
shared world and robot are untouched, and a new Simulation with the same seed
gives the run an untouched one would have given (``Simulation.run``'s Notes).
A ``progress`` callback that raises ends a sweep the same way (``sweep``'s
Raises).
"""

from __future__ import annotations

import copy
import pickle
from typing import Any

import numpy as np
import pytest
from shapely.geometry import box

from navkit.estimation import PlanarFusion
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import (
    Compass,
    Observation,
    Robot,
    Scenario,
    ScenarioResult,
    Simulation,
    Table,
    Trial,
    TrialResult,
    WheelEncoders,
    World,
    sweep,
)
from navkit.sim._sensors import Reading


class Boom(Exception):
    """The failure raised by the test callbacks."""


def _world() -> World:
    return World(box(-1.0, -1.0, 4.0, 2.0).exterior)


def _robot() -> Robot:
    return Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05),
        footprint=0.2,
        encoders=WheelEncoders(ticks_per_rev=1024.0, rate=50.0),
        compass=Compass(noise=0.01, rate=10.0),
        wheel_slip=0.01,
    )


class FailingController:
    """Drives forward; raises ``error`` at its ``fail_at``-th call (never when 0)."""

    def __init__(self, fail_at: int, error: BaseException) -> None:
        self.calls = 0
        self.fail_at = fail_at
        self.error = error

    def __call__(self, obs: Observation) -> Twist2D:
        self.calls += 1
        if self.calls == self.fail_at:
            raise self.error
        return Twist2D(0.4, 0.0, 0.3)


def _sim(world: World, robot: Robot, controller: FailingController, **options: Any) -> Simulation:
    return Simulation(world, robot, controller, start=(0.0, 0.0, 0.0), duration=2.0, seed=11,
                      **options)  # fmt: skip


@pytest.mark.parametrize("error", [Boom("controller failed"), KeyboardInterrupt()])
def test_a_failing_controller_ends_the_run_and_leaves_world_and_robot(
    error: BaseException,
) -> None:
    world, robot = _world(), _robot()
    world_bytes, robot_bytes = pickle.dumps(world), pickle.dumps(robot)
    controller = FailingController(7, error)
    sim = _sim(world, robot, controller)
    with pytest.raises(type(error)) as caught:
        sim.run()
    assert caught.value is error  # unchanged, not wrapped
    assert controller.calls == 7  # the run stopped at the failure
    assert pickle.dumps(world) == world_bytes
    assert pickle.dumps(robot) == robot_bytes
    # The Simulation counts as run, and so does a copy of it.
    with pytest.raises(RuntimeError, match="runs once"):
        sim.run()
    with pytest.raises(RuntimeError, match="runs once"):
        copy.copy(sim).run()


def test_a_new_simulation_after_a_failure_runs_as_an_untouched_one() -> None:
    world, robot = _world(), _robot()
    with pytest.raises(Boom):
        _sim(world, robot, FailingController(5, Boom("x"))).run()
    again = _sim(world, robot, FailingController(0, Boom("never"))).run()
    fresh = _sim(_world(), _robot(), FailingController(0, Boom("never"))).run()
    assert again.metrics.reason == fresh.metrics.reason == "timeout"
    np.testing.assert_array_equal(again.poses, fresh.poses)
    np.testing.assert_array_equal(again.estimates, fresh.estimates)


class FailingEstimator:
    """An estimator that raises at its ``fail_at``-th reading, counting what it took."""

    def __init__(self, fail_at: int) -> None:
        self.taken: list[float] = []
        self.fail_at = fail_at

    def observe(self, t: float, reading: Reading) -> None:
        if len(self.taken) + 1 == self.fail_at:
            raise Boom("estimator failed")
        self.taken.append(t)

    @property
    def pose(self) -> Pose2D | None:
        return None


def test_a_failing_estimator_ends_the_run_keeping_the_readings_it_took() -> None:
    estimator = FailingEstimator(12)
    controller = FailingController(0, Boom("never"))
    with pytest.raises(Boom, match="estimator failed"):
        _sim(_world(), _robot(), controller, estimator=estimator).run()
    assert len(estimator.taken) == 11
    assert estimator.taken == sorted(estimator.taken)
    # The run ended at the delivery that failed: well before the duration.
    assert estimator.taken[-1] < 2.0


def test_a_fusion_estimator_keeps_the_time_of_the_last_reading_before_the_failure() -> None:
    fusion = PlanarFusion(t0=0.0)
    controller = FailingController(10, Boom("x"))  # the 10th call, at t = 9 / 20 s
    with pytest.raises(Boom):
        _sim(_world(), _robot(), controller, estimator=fusion).run()
    assert fusion.t is not None and 0.0 < fusion.t <= 9.0 / 20.0 + 1e-9


# --------------------------------------------------------------------------- sweeps


class Counting(Scenario):
    """A scenario of instant trials (no simulation)."""

    name = "counting"
    default_trials = 3

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        return (("only", trials),)

    def run_trial(self, trial: Trial) -> TrialResult:
        return TrialResult(trial, {"index": float(trial.index)})

    def summarize(self, results: object, *, seed: int) -> ScenarioResult:
        results_, _, base = self._results_by_case(results, seed)
        table = Table("counting", ("index",), tuple((r.values["index"],) for r in results_))
        return ScenarioResult(self.name, base, results_, (table,), {})


@pytest.mark.parametrize("error", [Boom("progress failed"), KeyboardInterrupt()])
def test_a_failing_progress_callback_ends_the_sweep_without_a_trial_note(
    error: BaseException,
) -> None:
    calls: list[tuple[int, int]] = []

    def progress(done: int, total: int) -> None:
        calls.append((done, total))
        if done == 2:
            raise error

    with pytest.raises(type(error)) as caught:
        sweep(Counting(), trials=3, workers=1, progress=progress)
    assert caught.value is error
    assert calls == [(1, 3), (2, 3)]
    assert not getattr(caught.value, "__notes__", [])
    # The scenario is untouched: the same sweep without the callback runs whole.
    assert [r.values["index"] for r in sweep(Counting(), trials=3, workers=1).trials] == [
        0.0,
        1.0,
        2.0,
    ]
