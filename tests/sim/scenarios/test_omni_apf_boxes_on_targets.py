"""omni-apf: every obstacle box (all stand in the one world) clears every target."""

from __future__ import annotations

import pytest

from navkit.sim.scenarios import OmniApf
from navkit.sim.scenarios._omni_apf_setup import BODY_RADIUS, omni_world


@pytest.mark.parametrize("obstacles", [None, True])
def test_a_target_inside_another_routes_box_is_refused(obstacles: bool | None) -> None:
    # (1.5, 0.2) is the centre of the box on the route to (3, 0): the robot could
    # never stand at that target. Each route was checked against its own box only.
    targets = [(3.0, 0.0), (1.5, 0.2)]
    world = omni_world(tuple(targets), True)
    assert world.collides(BODY_RADIUS, (1.5, 0.2, 0.0))
    with pytest.raises(ValueError, match=r"targets\[1\].*targets\[0\]"):
        OmniApf(obstacles=obstacles, targets=targets)


def test_without_the_obstacle_series_such_targets_stay_allowed() -> None:
    assert OmniApf(obstacles=False, targets=[(3.0, 0.0), (1.5, 0.2)]).targets[1] == (1.5, 0.2)


@pytest.mark.parametrize("dx", [-0.45, -0.3, -0.15, 0.0, 0.15, 0.3, 0.45])
def test_accepted_targets_leave_the_body_clear_of_every_box(dx: float) -> None:
    # Targets around the box on the route to (3, 0), at (1.5, 0.2).
    for dy in (-0.45, -0.3, -0.15, 0.0, 0.15, 0.3, 0.45):
        targets = [(3.0, 0.0), (0.0, -3.0), (1.5 + dx, 0.2 + dy)]
        try:
            scenario = OmniApf(obstacles=True, targets=targets)
        except ValueError:
            continue
        world = omni_world(scenario.targets, True)
        for x, y in [(0.0, 0.0), *scenario.targets]:
            assert not world.collides(BODY_RADIUS, (x, y, 0.0)), (x, y)
