"""A ``done`` a user's ``__getattr__`` made up is refused, not taken for true (review 31, FNF).

The simulation reads a controller's optional ``done`` (and ``TrackerController`` a
tracker's) as Python does, ``__getattr__`` included, so forwarding proxies keep
working. A ``__getattr__`` returning a default for every name (an options object,
say) answered for ``done`` with an object of no truth value of its own, which
Python takes for true: the run ended at 0 s as "controller done", without a
word. ``done_flag`` now refuses an object whose class defines neither
``__bool__`` nor ``__len__`` (``TypeError`` naming the flag). Checked against
the source before the fix: the refusal tests failed there (the run ended at 0 s;
``done_flag`` returned True). An estimator's ``observe`` and ``pose`` found
through ``__getattr__`` were checked already (a ``pose`` that is no Pose2D is
refused): pinned.
"""

from __future__ import annotations

from typing import Any

import pytest
from shapely.geometry import box

from navkit.control import OnOffTracker
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, TrackerController, World
from navkit.sim._done import done_flag

ROBOT = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)


class Options:
    """A user's default: no __bool__, no __len__ (so every instance is true)."""


class Defaulting:
    """A controller answering every unknown name with a default Options()."""

    def __call__(self, obs: Observation) -> Twist2D:
        return Twist2D(0.1, 0.0, 0.0)

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        return Options()


def test_a_controller_whose_getattr_answers_done_is_refused() -> None:
    sim = Simulation(World(), ROBOT, Defaulting(), start=(0.0, 0.0, 0.0), duration=1.0)
    with pytest.raises(TypeError, match=r"^the controller's done must be true or false, got a "
                       r"Options, which has no truth value of its own"):  # fmt: skip
        sim.run()


class DefaultingTracker(OnOffTracker):
    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        return Options()


class NoDoneTracker:
    def step(self, pose: Pose2D, dt: float) -> Twist2D:
        return Twist2D(0.0, 0.0, 0.0)

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        return Options()


def test_a_tracker_done_made_up_by_getattr_is_refused() -> None:
    follow = TrackerController(NoDoneTracker(), control_rate=10.0)  # "done" is found
    with pytest.raises(TypeError, match=r"^tracker\.done must be true or false, got a Options"):
        _ = follow.done
    # A tracker's own done (a property of its class) is read as before.
    assert TrackerController(DefaultingTracker(), control_rate=10.0).done is False


@pytest.mark.parametrize("value", [object(), Options(), Ellipsis], ids=["object", "Options", "..."])
def test_objects_of_no_truth_value_of_their_own_are_refused(value: object) -> None:
    with pytest.raises(TypeError, match=r"has no truth value of its own"):
        done_flag(value, "tracker.done")


class Flag:
    def __init__(self, on: bool) -> None:
        self.on = on

    def __bool__(self) -> bool:
        return self.on


class Pending:
    def __init__(self, n: int) -> None:
        self.n = n

    def __len__(self) -> int:
        return self.n


@pytest.mark.parametrize(
    ("value", "want"),
    [
        (None, False),
        (Flag(True), True),
        (Flag(False), False),
        (Pending(0), False),
        (Pending(2), True),
    ],
)
def test_objects_defining_their_truth_keep_it(value: object, want: bool) -> None:
    assert done_flag(value, "tracker.done") is want


class Forwarding:
    """A logging proxy forwarding every other name to the controller it wraps."""

    def __init__(self, inner: TrackerController[Any]) -> None:
        self.inner = inner
        self.calls = 0

    def __call__(self, obs: Observation) -> Twist2D:
        self.calls += 1
        return self.inner(obs)

    def __getattr__(self, name: str) -> Any:
        return getattr(self.__dict__["inner"], name)


def test_a_forwarding_proxy_still_ends_the_run_when_its_tracker_is_done() -> None:
    tracker = OnOffTracker(max_speed=0.5)
    tracker.set_path([[1.0, 1.0], [2.0, 1.0]])
    proxy = Forwarding(TrackerController(tracker, control_rate=20.0, use_estimate=False))
    world = World([box(0.0, 0.0, 4.0, 2.0).exterior])
    trace = Simulation(world, ROBOT, proxy, start=(1.0, 1.0, 0.0), control_rate=20.0,
                       duration=30.0).run()  # fmt: skip
    assert tracker.done and trace.metrics.reason == "controller done"
    assert 0.0 < trace.metrics.duration < 30.0 and proxy.calls > 1


class DefaultingEstimator:
    def observe(self, t: float, reading: Any) -> None:
        pass

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        return Options()


def test_an_estimator_pose_made_up_by_getattr_is_refused() -> None:
    sim = Simulation(World(), ROBOT, lambda obs: Twist2D(0.0, 0.0, 0.0), start=(0.0, 0.0, 0.0),
                     duration=0.5, estimator=DefaultingEstimator())  # fmt: skip
    with pytest.raises(TypeError, match=r"estimator\.pose must be a Pose2D or None, got Options"):
        sim.run()
