"""Fuzz specs of navkit.sim's controller adapters (registered on import by ``fuzz_specs.py``)."""

from __future__ import annotations

from fuzz_engine import Anything, Call, Obj, call, method, spec

from navkit.control import FollowTheCarrot
from navkit.geometry import Pose2D
from navkit.sim import Observation, Tracker, TrackerController

P = "navkit.sim."


def _tracker() -> FollowTheCarrot:
    tracker = FollowTheCarrot(max_speed=0.5)
    tracker.set_path([[0.0, 0.0], [2.0, 0.0]])
    return tracker


def _follow() -> Call:
    return call(TrackerController, _tracker(), control_rate=20.0)


def _observation() -> Call:
    pose = call(Pose2D, 0.5, 0.1, 0.2)
    return call(Observation, 0.1, None, None, None, None, (), pose, call(Pose2D, 0.5, 0.0, 0.1))


spec(P + "TrackerController", lambda c: _follow(), kinds={"tracker": Anything()})
spec(
    P + "TrackerController.__call__",
    lambda c: method(_follow(), "__call__", _observation()),
    kinds={"obs": Obj(Observation)},
    mutates=("self",),
)
spec(P + "Tracker", lambda c: call(Tracker), expect_error=TypeError)
