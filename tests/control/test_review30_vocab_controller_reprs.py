"""The controllers print their options, as every other configured navkit object does.

``AStarPlanner``, ``FieldDStar``, ``MapPlanner``, ``ScanMatcher``, the odometry
classes, ``PlanarFusion``, the drives and the scenarios print their options;
the three path trackers and ``PotentialFieldController`` printed
``<navkit.control._follow_the_carrot.FollowTheCarrot object at 0x...>``, so two
differently tuned trackers in a log or a failing test read alike.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.control import (
    FollowTheCarrot,
    OnOffTracker,
    PotentialFieldController,
    RegulatedPurePursuit,
)
from navkit.mapping import OccupancyGrid
from navkit.planning import BlendedAttraction, PiecewiseAttraction

NAMESPACE = {
    "FollowTheCarrot": FollowTheCarrot,
    "OnOffTracker": OnOffTracker,
    "PotentialFieldController": PotentialFieldController,
    "RegulatedPurePursuit": RegulatedPurePursuit,
    "BlendedAttraction": BlendedAttraction,
    "PiecewiseAttraction": PiecewiseAttraction,
}


def _options(**options: Any) -> dict[str, Any]:
    return options


# Each controller with every option off its default: each must show in the repr.
TUNED: list[tuple[type[Any], dict[str, Any]]] = [
    (
        FollowTheCarrot,
        _options(carrot_distance=0.4, max_speed=0.25, max_omega=1.25, goal_tolerance=0.0625,
             yaw_tolerance=0.03, heading_gain=2.5, rotate_angle=0.5, align_tolerance=0.125,
             drive="omni"),
    ),
    (
        OnOffTracker,
        _options(max_speed=0.3, rotate_omega=0.75, rotate_angle=0.25, goal_tolerance=0.0625,
             yaw_tolerance=0.03, drive="omni"),
    ),
    (
        RegulatedPurePursuit,
        _options(max_speed=0.4, lookahead_time=1.25, min_lookahead=0.35, max_lookahead=0.8,
             rotate_to_heading=False, rotate_angle=0.5, rotate_omega=1.5, max_angular_accel=2.5,
             curvature_regulation=False, slowdown_radius=0.75, min_regulated_speed=0.125,
             clearance_distance=0.5, clearance_gain=2.0, approach_distance=0.5,
             min_approach_speed=0.0625, goal_tolerance=0.125, yaw_tolerance=0.2, max_omega=1.0,
             drive="omni"),
    ),
    (
        PotentialFieldController,
        _options(k_rep=0.0625, influence_radius=0.5, max_speed=0.4, max_accel=0.75, max_decel=1.5,
             max_omega=1.75, kp=2.5, ki=0.125, kd=0.25, integral_limit=0.5, drive="diff",
             goal_tolerance=0.0625, stall_radius=0.0625, stall_timeout=1.5),
    ),
]  # fmt: skip


@pytest.mark.parametrize(("cls", "options"), TUNED, ids=lambda v: getattr(v, "__name__", ""))
def test_repr_shows_every_option_and_evaluates_to_a_twin(
    cls: type[Any], options: dict[str, Any]
) -> None:
    controller = cls(**options)
    text = repr(controller)
    assert text.startswith(f"{cls.__name__}(") and " object at 0x" not in text, text
    for name, value in options.items():
        assert f"{name}={value!r}" in text, (name, text)
    twin = eval(text, NAMESPACE)
    assert type(twin) is cls and repr(twin) == text
    # The defaults print as themselves too, and differ from the tuned controller.
    assert repr(eval(repr(cls()), NAMESPACE)) == repr(cls()) != text


def test_the_field_controller_shows_its_attraction() -> None:
    attraction = PiecewiseAttraction(np.array([1.0, 2.0]), alpha=0.5, goal_radius=0.25)
    # A goal_tolerance beyond the field's goal_radius (the default 0.05 is refused).
    text = repr(PotentialFieldController(attraction, goal_tolerance=0.3))
    assert text.startswith(
        "PotentialFieldController(attraction=PiecewiseAttraction(goal_xy=(1.0, 2.0), alpha=0.5, "
        "goal_radius=0.25, spread=1.0), k_rep="
    ), text
    assert repr(eval(text, NAMESPACE)) == text


def test_a_clearance_map_shows_as_its_grid() -> None:
    grid = OccupancyGrid.from_occupancy(np.zeros((4, 5), dtype=bool), resolution=0.1)
    text = repr(RegulatedPurePursuit(clearance=grid))
    assert f"clearance={grid!r}, clearance_distance=0.6" in text, text
    assert "clearance=None" in repr(RegulatedPurePursuit())


@pytest.mark.parametrize("cls", [FollowTheCarrot, OnOffTracker, RegulatedPurePursuit])
def test_a_tracker_repr_does_not_change_as_it_tracks(cls: type[Any]) -> None:
    tracker = cls()
    before = repr(tracker)
    tracker.set_path(np.array([[0.0, 0.0], [1.0, 0.0]]), goal_yaw=0.5)
    tracker.step((0.0, 0.0, 0.0), 0.1)
    assert repr(tracker) == before
