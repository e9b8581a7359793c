"""One vocabulary for the controllers (session 15's audit, rows 5 and 6).

* ``PotentialFieldController.step(pose, target_pose, dt)``: ``dt`` may be passed
  positionally, as to every path tracker's ``step(pose, dt)``.
* The trackers' shared options: ``max_speed`` (``OnOffTracker(speed=)``),
  ``rotate_angle`` (``OnOffTracker(heading_tolerance=)``,
  ``FollowTheCarrot(align_angle=)``, ``RegulatedPurePursuit(rotate_to_heading_angle=)``)
  and ``rotate_omega`` (``OnOffTracker(turn_rate=)``). The old keywords and
  ``OnOffTracker``'s old properties still work, with a ``DeprecationWarning``.
"""

from __future__ import annotations

import inspect
import math
import warnings
from collections.abc import Callable
from typing import Any

import pytest

from navkit.control import (
    FollowTheCarrot,
    OnOffTracker,
    PotentialFieldController,
    RegulatedPurePursuit,
)
from navkit.control._path_following import PathTracker
from navkit.geometry import Pose2D, Twist2D, integrate

PATH = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]
DT = 0.05


def _loop(tracker: PathTracker, steps: int) -> list[Twist2D]:
    """The commands of a closed loop on the tracker's path, starting askew."""
    pose = Pose2D(0.0, 0.05, 0.6)
    out = []
    for _ in range(steps):
        cmd = tracker.step(pose, DT)
        out.append(cmd)
        pose = integrate(pose, cmd, DT)
    return out


def _commands(tracker: PathTracker, steps: int = 120) -> list[Twist2D]:
    """The commands of a closed loop on a right angle, starting askew."""
    tracker.set_path(PATH, goal_yaw=math.pi / 2)
    return _loop(tracker, steps)


def test_pfc_step_takes_dt_positionally_like_the_trackers() -> None:
    a, b = PotentialFieldController(), PotentialFieldController()
    pose, target = Pose2D(0.0, 0.0, 0.3), Pose2D(2.0, 1.0, 0.0)
    for _ in range(5):
        by_position = a.step(pose, target, 0.1, obstacles=[[1.0, 0.4]])
        by_name = b.step(pose, target, dt=0.1, obstacles=[[1.0, 0.4]])
        assert by_position == by_name
        pose = integrate(pose, by_position, 0.1)
    kinds = inspect.signature(PotentialFieldController.step).parameters
    assert kinds["dt"].kind is inspect.Parameter.POSITIONAL_OR_KEYWORD
    assert kinds["obstacles"].kind is inspect.Parameter.KEYWORD_ONLY
    assert kinds["velocity"].kind is inspect.Parameter.KEYWORD_ONLY


def test_every_tracker_has_the_shared_option_names() -> None:
    for cls in (FollowTheCarrot, OnOffTracker, RegulatedPurePursuit):
        params = inspect.signature(cls).parameters
        assert {"max_speed", "rotate_angle", "goal_tolerance", "yaw_tolerance"} <= set(params)
    assert "rotate_omega" in inspect.signature(OnOffTracker).parameters
    assert "rotate_omega" in inspect.signature(RegulatedPurePursuit).parameters


NEW_AND_OLD: list[tuple[Callable[..., PathTracker], dict[str, Any], dict[str, Any]]] = [
    (OnOffTracker, {"max_speed": 0.3}, {"speed": 0.3}),
    (OnOffTracker, {"rotate_omega": 1.2}, {"turn_rate": 1.2}),
    (OnOffTracker, {"rotate_angle": 0.3}, {"heading_tolerance": 0.3}),
    (FollowTheCarrot, {"rotate_angle": 0.15}, {"align_angle": 0.15}),
    (RegulatedPurePursuit, {"rotate_angle": 0.3}, {"rotate_to_heading_angle": 0.3}),
]
IDS = [f"{cls.__name__}.{next(iter(old))}" for cls, _, old in NEW_AND_OLD]


@pytest.mark.parametrize(("cls", "new", "old"), NEW_AND_OLD, ids=IDS)
def test_new_names_do_not_warn_and_change_the_behaviour(
    cls: Callable[..., PathTracker], new: dict[str, Any], old: dict[str, Any]
) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        commands = _commands(cls(**new))
    # The option is used: the default gives other commands.
    assert commands != _commands(cls())


@pytest.mark.parametrize(("cls", "new", "old"), NEW_AND_OLD, ids=IDS)
def test_old_names_warn_and_give_the_same_commands(
    cls: Callable[..., PathTracker], new: dict[str, Any], old: dict[str, Any]
) -> None:
    (old_name,) = old
    (new_name,) = new
    with pytest.warns(DeprecationWarning, match=f"{old_name} is deprecated.*use {new_name}") as rec:
        tracker = cls(**old)
    assert rec[0].filename == __file__
    assert _commands(tracker) == _commands(cls(**new))


@pytest.mark.parametrize(("cls", "new", "old"), NEW_AND_OLD, ids=IDS)
def test_old_and_new_name_together_are_a_type_error(
    cls: Callable[..., PathTracker], new: dict[str, Any], old: dict[str, Any]
) -> None:
    (new_name,) = new
    with pytest.raises(TypeError, match=f"both {new_name} and its old name"):
        cls(**new, **old)


@pytest.mark.parametrize(("cls", "new", "old"), NEW_AND_OLD, ids=IDS)
def test_errors_name_the_keyword_the_caller_wrote(
    cls: Callable[..., PathTracker], new: dict[str, Any], old: dict[str, Any]
) -> None:
    (old_name,) = old
    (new_name,) = new
    with pytest.raises(ValueError, match=rf"^{new_name} must"):
        cls(**{new_name: math.nan})
    with pytest.warns(DeprecationWarning), pytest.raises(ValueError, match=rf"^{old_name} must"):
        cls(**{old_name: math.nan})
    with pytest.warns(DeprecationWarning), pytest.raises(TypeError, match=rf"^{old_name} must"):
        cls(**{old_name: "fast"})


@pytest.mark.parametrize(
    ("old", "new"),
    [("speed", "max_speed"), ("turn_rate", "rotate_omega"), ("heading_tolerance", "rotate_angle")],
)
def test_on_off_old_properties_warn_and_read_the_new_ones(old: str, new: str) -> None:
    tracker = OnOffTracker(max_speed=0.3, rotate_omega=1.2, rotate_angle=0.3)
    with pytest.warns(DeprecationWarning, match=f"OnOffTracker.{old} is deprecated.*{new}") as rec:
        value = getattr(tracker, old)
    assert rec[0].filename == __file__
    assert value == getattr(tracker, new) == {"max_speed": 0.3, "rotate_omega": 1.2,
                                              "rotate_angle": 0.3}[new]  # fmt: skip


# ``PathTracker.set_path(goal_heading=)`` is now ``goal_yaw=`` (row 25): "yaw" as
# ``Pose2D.theta`` and ``yaw_tolerance``; "heading" stays the compass's clockwise-from-north word.
TRACKERS: list[Callable[[], PathTracker]] = [FollowTheCarrot, OnOffTracker, RegulatedPurePursuit]


@pytest.mark.parametrize("make", TRACKERS)
def test_goal_yaw_is_reached_and_wrapped(make: Callable[[], PathTracker]) -> None:
    tracker = make()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tracker.set_path(PATH, goal_yaw=5 * math.pi / 2)
        assert tracker.goal_yaw == pytest.approx(math.pi / 2)
        pose = Pose2D(0.0, 0.05, 0.6)
        for _ in range(600):
            pose = integrate(pose, tracker.step(pose, DT), DT)
            if tracker.done:
                break
    assert tracker.done
    assert abs(math.remainder(pose.theta - math.pi / 2, 2 * math.pi)) <= tracker.yaw_tolerance
    tracker.set_path(PATH)
    assert tracker.goal_yaw is None


@pytest.mark.parametrize("make", TRACKERS)
def test_goal_heading_still_works_with_a_warning(make: Callable[[], PathTracker]) -> None:
    new, old = make(), make()
    new.set_path(PATH, goal_yaw=-1.0)
    with pytest.warns(DeprecationWarning, match="goal_heading is deprecated.*use goal_yaw") as rec:
        old.set_path(PATH, goal_heading=-1.0)
    assert rec[0].filename == __file__
    assert _loop(old, 600) == _loop(new, 600)
    assert old.done and new.done
    with pytest.warns(DeprecationWarning, match=r"\.goal_heading is deprecated.*goal_yaw") as rec:
        assert old.goal_heading == new.goal_yaw == -1.0
    assert rec[0].filename == __file__
    with pytest.raises(TypeError, match="both goal_yaw and its old name goal_heading"):
        make().set_path(PATH, goal_yaw=1.0, goal_heading=1.0)


@pytest.mark.parametrize("name", ["goal_yaw", "goal_heading"])
def test_bad_goal_yaw_names_what_the_caller_wrote(name: str) -> None:
    infinite: dict[str, Any] = {name: math.inf}
    text: dict[str, Any] = {name: "north"}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        with pytest.raises(ValueError, match=name):
            OnOffTracker().set_path(PATH, **infinite)
        with pytest.raises(TypeError, match=name):
            OnOffTracker().set_path(PATH, **text)
