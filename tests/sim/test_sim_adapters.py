"""TrackerController: a path tracker stepped as a Simulation controller."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import box

from navkit.control import FollowTheCarrot, OnOffTracker, RegulatedPurePursuit
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, TrackerController, World

ROUTE = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0]]


def observation(estimate: Pose2D | None, true_pose: Pose2D) -> Observation:
    return Observation(0.5, None, None, None, None, (), estimate, true_pose)


def tracker(kind: type) -> FollowTheCarrot | OnOffTracker | RegulatedPurePursuit:
    t = kind()
    t.set_path(ROUTE)
    return t


@pytest.mark.parametrize("kind", [FollowTheCarrot, OnOffTracker, RegulatedPurePursuit])
@settings(deadline=None, max_examples=50)  # the first step loads the trackers' compiled kernels
@given(
    x=st.floats(-0.5, 2.5), y=st.floats(-0.5, 1.5), theta=st.floats(-3.0, 3.0),
    rate=st.floats(1.0, 100.0), use_estimate=st.booleans(),
)  # fmt: skip
def test_steps_the_tracker_on_the_chosen_pose_with_the_control_period(
    kind: type, x: float, y: float, theta: float, rate: float, use_estimate: bool
) -> None:
    pose, other = Pose2D(x, y, theta), Pose2D(x + 0.3, y - 0.2, -theta)
    obs = observation(pose, other) if use_estimate else observation(other, pose)
    reference = tracker(kind)
    follow = TrackerController(tracker(kind), control_rate=rate, use_estimate=use_estimate)
    for _ in range(3):
        assert follow(obs) == reference.step(pose, 1.0 / rate)
        assert follow.done == reference.done


def test_without_an_estimate_it_stops_and_leaves_the_tracker_alone() -> None:
    t = tracker(FollowTheCarrot)
    follow = TrackerController(t, control_rate=20.0)
    assert follow(observation(None, Pose2D(0.0, 0.0, 0.0))) == Twist2D(0.0, 0.0, 0.0)
    assert t.phase == tracker(FollowTheCarrot).phase  # not stepped
    oracle = TrackerController(t, control_rate=20.0, use_estimate=False)
    assert oracle(observation(None, Pose2D(0.0, 0.0, 0.0))).vx > 0.0


def test_the_run_ends_when_the_tracker_is_done() -> None:
    t = FollowTheCarrot(max_speed=0.5)
    t.set_path(ROUTE)
    follow = TrackerController(t, control_rate=20.0, use_estimate=False)
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    world = World([box(-1.0, -1.0, 3.0, 2.0).exterior])
    trace = Simulation(world, robot, follow, start=(0.0, 0.0, 0.0), goal=(2.0, 1.0),
                       control_rate=20.0, stop_at_goal=False, duration=60.0).run()  # fmt: skip
    assert follow.done and t.done
    assert trace.metrics.reached and trace.metrics.collisions == 0
    assert trace.metrics.duration < 59.0  # ended by the tracker, not the time limit


def test_a_tracker_whose_done_flag_is_an_instance_attribute() -> None:
    """``done`` set in ``__init__`` (not a property or class attribute) is a done flag too."""

    class Once:
        def __init__(self) -> None:
            self.done = False

        def step(self, pose: Pose2D, dt: float) -> Twist2D:
            self.done = True
            return Twist2D(0.1, 0.0, 0.0)

    follow = TrackerController(Once(), control_rate=20.0, use_estimate=False)
    assert not follow.done
    assert follow(observation(None, Pose2D(0.0, 0.0, 0.0))) == Twist2D(0.1, 0.0, 0.0)
    assert follow.done


@pytest.mark.parametrize(
    ("args", "kwargs", "error", "match"),
    [
        ((object(),), {"control_rate": 20.0}, TypeError, "tracker"),
        ((tracker(OnOffTracker),), {"control_rate": 0.0}, ValueError, "control_rate"),
        ((tracker(OnOffTracker),), {"control_rate": 1e7}, ValueError, "control_rate"),
        ((tracker(OnOffTracker),), {"control_rate": "20"}, TypeError, "control_rate"),
        ((tracker(OnOffTracker),), {"control_rate": 20.0, "use_estimate": 1}, TypeError,
         "use_estimate"),
    ],
)  # fmt: skip
def test_bad_arguments_are_refused(args: tuple, kwargs: dict, error: type, match: str) -> None:
    with pytest.raises(error, match=match):
        TrackerController(*args, **kwargs)


def test_a_bad_observation_or_tracker_answer_is_refused() -> None:
    follow = TrackerController(tracker(OnOffTracker), control_rate=20.0)
    with pytest.raises(TypeError, match="obs"):
        follow(Pose2D(0.0, 0.0, 0.0))  # type: ignore[arg-type]

    class Broken:
        done = False

        def step(self, pose: Pose2D, dt: float) -> Twist2D:
            return (1.0, 0.0, 0.0)  # type: ignore[return-value]

    with pytest.raises(TypeError, match="Twist2D"):
        origin = Pose2D(0.0, 0.0, 0.0)
        TrackerController(Broken(), control_rate=20.0)(observation(origin, origin))
