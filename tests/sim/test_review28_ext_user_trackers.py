"""Trackers and estimators a user writes, from the user's side (review 28, extension points).

``TrackerController.tracker`` was typed as a private protocol with only ``step``
and ``done``, so a user's ``follow.tracker.set_path(...)`` failed their type check
and a tracker of their own had no public type to be written against. An
estimator whose ``observe`` is not callable was taken and failed at the first
reading with "'int' object is not callable"; a tracker ``done`` without a truth
value escaped as NumPy's bare ``ValueError``.
"""

from __future__ import annotations

import importlib.util
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from shapely.geometry import box

import navkit.sim
from navkit.control import FollowTheCarrot
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, TrackerController, World

ROOT = Path(__file__).resolve().parents[2]

USER_CODE = '''
from navkit.control import FollowTheCarrot
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Robot, Simulation, Tracker, TrackerController, World


class Stop:
    """A user's tracker: typed against the public protocol."""

    def __init__(self) -> None:
        self.done = False
        self.calls = 0

    def step(self, pose: Pose2D, dt: float) -> Twist2D:
        self.calls += 1
        return Twist2D(0.0, 0.0, 0.0)


mine: Tracker = Stop()
follow = TrackerController(FollowTheCarrot(max_speed=0.5), control_rate=20.0)
follow.tracker.set_path([[0.0, 0.0], [1.0, 0.0]])  # the tracker keeps its own type
own = TrackerController(Stop(), control_rate=20.0)
count: int = own.tracker.calls
robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
trace = Simulation(World(), robot, follow, start=(0.0, 0.0, 0.0), control_rate=20.0).run()
'''


@pytest.mark.slow
@pytest.mark.skipif(importlib.util.find_spec("mypy") is None, reason="mypy is not installed")
def test_a_users_tracker_code_type_checks_under_mypy_strict(tmp_path: Path) -> None:
    script = tmp_path / "user_tracker.py"
    script.write_text(textwrap.dedent(USER_CODE))
    proc = subprocess.run(
        [
            sys.executable, "-m", "mypy", "--strict", "--cache-dir",
            str(tmp_path / "mypy_cache"), str(script),
        ],
        cwd=ROOT, capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_the_tracker_protocol_is_public_and_the_adapter_generic_in_it() -> None:
    assert "Tracker" in navkit.sim.__all__
    assert navkit.sim.Tracker.__module__.startswith("navkit.sim")
    # Subscriptable at run time too, as the annotations a user writes are.
    alias = TrackerController[FollowTheCarrot]
    assert alias.__origin__ is TrackerController  # type: ignore[attr-defined]
    tracker = FollowTheCarrot()
    assert TrackerController(tracker, control_rate=10.0).tracker is tracker


class _Flags:
    """A tracker whose ``done`` is an array of flags, not one."""

    def __init__(self) -> None:
        self.done = np.array([True, False])

    def step(self, pose: Pose2D, dt: float) -> Twist2D:
        return Twist2D(0.1, 0.0, 0.0)


def test_a_done_without_a_truth_value_is_named() -> None:
    follow = TrackerController(_Flags(), control_rate=10.0, use_estimate=False)
    with pytest.raises(TypeError, match=r"tracker\.done must be true or false, got ndarray"):
        _ = follow.done
    # And in a run, where the simulation reads it after every control step.
    world = World(box(-1.0, -1.0, 3.0, 3.0).exterior)
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    sim = Simulation(world, robot, follow, start=(0.0, 0.0, 0.0), duration=0.2)
    with pytest.raises(TypeError, match=r"tracker\.done"):
        sim.run()


class _NotCallable:
    """An estimator with the names of the protocol but an ``observe`` that is not a method."""

    observe = 3
    pose: Pose2D | None = None


def test_an_estimator_whose_observe_is_not_callable_is_refused_when_built() -> None:
    world = World(box(-1.0, -1.0, 3.0, 3.0).exterior)
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)

    def stop(obs: Observation) -> Twist2D:
        return Twist2D(0.0, 0.0, 0.0)

    with pytest.raises(TypeError, match=r"estimator\.observe must be a method"):
        Simulation(world, robot, stop, start=(0.0, 0.0, 0.0), estimator=_NotCallable())


class _TypoDone:
    """A controller whose ``done`` property has a typo: it raises AttributeError."""

    def __init__(self) -> None:
        self.calls = 0
        self.finished = False

    @property
    def done(self) -> bool:
        return bool(self.finsihed)  # type: ignore[attr-defined]

    def __call__(self, obs: Observation) -> Twist2D:
        self.calls += 1
        self.finished = self.calls >= 3
        return Twist2D(0.0, 0.0, 0.0)


class _TypoTracker:
    """The same typo in a tracker's ``done``, behind a TrackerController."""

    @property
    def done(self) -> bool:
        return bool(self.finsihed)  # type: ignore[attr-defined]

    def step(self, pose: Pose2D, dt: float) -> Twist2D:
        return Twist2D(0.0, 0.0, 0.0)


class _SlotDone:
    """``done`` a slot set only once finished: unset, it is no done yet (as before)."""

    __slots__ = ("calls", "done")

    def __init__(self) -> None:
        self.calls = 0

    def __call__(self, obs: Observation) -> Twist2D:
        self.calls += 1
        if self.calls >= 3:
            self.done = True
        return Twist2D(0.0, 0.0, 0.0)


def _run(controller: object) -> str:
    world = World(box(-1.0, -1.0, 3.0, 3.0).exterior)
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    sim = Simulation(world, robot, controller, start=(0.0, 0.0, 0.0), duration=1.0)  # type: ignore[arg-type]
    return sim.run().metrics.reason


def test_an_attribute_error_inside_a_done_property_is_not_taken_for_no_done() -> None:
    # It used to be swallowed as "no done attribute": the run went on to its timeout.
    with pytest.raises(AttributeError, match="finsihed"):
        _run(_TypoDone())
    follow = TrackerController(_TypoTracker(), control_rate=20.0, use_estimate=False)
    with pytest.raises(AttributeError, match="finsihed"):
        _run(follow)
    assert _run(_SlotDone()) == "controller done"
    assert _run(lambda obs: Twist2D(0.0, 0.0, 0.0)) == "timeout"
