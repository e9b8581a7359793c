"""greedy_step's robot-frame goal and waypoint say their frame (session 15's audit, row 21).

Every other ``goal_xy`` of navkit is a world point; greedy_step's goal is in the
robot frame (the frame of the LocalGrid it plans on). It is now
``goal_robot_xy`` (positional calls unchanged; ``goal_xy=`` still works with a
DeprecationWarning), and ``GreedyStep.waypoint_robot_xy`` reads the
``waypoint_xy`` field under a name that says the frame.
"""

from __future__ import annotations

import inspect
import pickle
import warnings
from typing import Any

import numpy as np
import pytest

from navkit.mapping import LocalGrid
from navkit.planning import GreedyStep, greedy_step

GOAL = (2.0, 0.3)


def _grid() -> LocalGrid:
    return LocalGrid.from_points([[0.3, 0.0], [0.3, 0.1], [0.3, -0.1]])


def _same(a: GreedyStep, b: GreedyStep) -> bool:
    return (a.cell, a.g, a.h, a.candidates) == (b.cell, b.g, b.h, b.candidates) and bool(
        np.array_equal(a.waypoint_xy, b.waypoint_xy)
    )


def test_goal_robot_xy_positional_and_keyword_agree() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        positional = greedy_step(_grid(), GOAL)
        keyword = greedy_step(_grid(), goal_robot_xy=GOAL)
        progress = greedy_step(_grid(), goal_robot_xy=GOAL, require_progress=True)
    assert _same(positional, keyword)
    assert positional.cell != (10, 10) and progress.h < float(np.hypot(*GOAL))
    param = inspect.signature(greedy_step).parameters["goal_robot_xy"]
    assert param.kind is inspect.Parameter.POSITIONAL_OR_KEYWORD


def test_goal_xy_still_works_with_a_warning() -> None:
    with pytest.warns(DeprecationWarning, match="goal_xy is deprecated.*goal_robot_xy") as rec:
        old = greedy_step(_grid(), goal_xy=GOAL)
    assert rec[0].filename == __file__
    assert _same(old, greedy_step(_grid(), GOAL))
    with pytest.raises(TypeError, match="both goal_robot_xy and its old name goal_xy"):
        greedy_step(_grid(), GOAL, goal_xy=GOAL)


def test_a_missing_goal_is_a_type_error() -> None:
    with pytest.raises(TypeError, match="missing the argument goal_robot_xy"):
        greedy_step(_grid())


def _named(name: str, value: Any) -> dict[str, Any]:
    return {name: value}


@pytest.mark.parametrize("name", ["goal_robot_xy", "goal_xy"])
def test_bad_goals_name_what_the_caller_wrote(name: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        with pytest.raises(ValueError, match=f"^{name} "):
            greedy_step(_grid(), **_named(name, (np.nan, 0.0)))
        with pytest.raises(ValueError, match=f"^{name} "):
            greedy_step(_grid(), **_named(name, (1.0, 0.0, 0.0)))


def test_waypoint_robot_xy_is_the_field_read_only() -> None:
    step = greedy_step(_grid(), GOAL)
    assert step.waypoint_robot_xy is step.waypoint_xy
    np.testing.assert_array_equal(step.waypoint_robot_xy, _grid().cell_to_world(step.cell))
    assert not step.waypoint_robot_xy.flags.writeable
    with pytest.raises(AttributeError):
        step.waypoint_robot_xy = np.zeros(2)  # type: ignore[misc]
    built = GreedyStep((10, 12), [0.2, 0.0], g=0.2, h=1.8, candidates=440)
    assert built.waypoint_robot_xy.tolist() == [0.2, 0.0]
    # Not a field: fields, replace and pickles keep the field's name.
    assert "waypoint_robot_xy" not in {f.name for f in GreedyStep.__dataclass_fields__.values()}
    again = pickle.loads(pickle.dumps(step))
    np.testing.assert_array_equal(again.waypoint_robot_xy, step.waypoint_robot_xy)
    assert not again.waypoint_robot_xy.flags.writeable
