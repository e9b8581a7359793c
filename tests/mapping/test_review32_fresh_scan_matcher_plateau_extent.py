"""A plateau the scan could slide on is "degenerate", not "converged" (review 32, FRESH).

Review 31 made a match whose points all lie on a plateau of occupied cells
(zero Hessian, mean ``(1 - M)²`` <= ``PLATEAU_COST``) ``"converged"`` at the
last iterate with a one-cell covariance: right for walls drawn on cell edges
(two cells thick, the plateau one cell wide), but the rule never asked how far
the plateau reaches. A scan inside a solid occupied block (a map's
out-of-bounds area drawn occupied) was "converged" at *any* guess with a
1.4 cm standard deviation, and a corridor drawn on cell edges was "converged"
at a guess 20 cm off along it (x = 0.5 for the truth 0.3), where the same
corridor a quarter cell off the lattice is "degenerate". The plateau must now
end within a cell in every direction: the Hessians a cell either side (and a
rotation moving the RMS range a cell) must pass the degeneracy test a match's
own Hessian passes. Checked against the source before the fix: the solid-block
and corridor tests failed there (reason "converged"); the room plateau of
review 31 stays "converged".
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.geometry import LineString, box

from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid, ScanMatcher
from navkit.sim import Lidar, World

RES = 0.05
TRUE = Pose2D(0.3, -0.2, 0.4)


def _scan(obstacles: list[object], range_max: float) -> object:
    lidar = Lidar(n_beams=180, noise=None, range_min=0.05, range_max=range_max)
    return lidar.scan(World(obstacles), TRUE)


@pytest.mark.parametrize("guess", [Pose2D(0.0, 0.0, 0.0), Pose2D(5.0, 3.0, 1.0)])
def test_a_scan_inside_a_solid_block_is_degenerate(guess: Pose2D) -> None:
    room = [box(-4.0, -4.0, 4.0, 4.0).exterior, box(1.0, 1.0, 2.0, 1.5)]
    scan = _scan(room, 10.0)
    block = [box(-20.0, -20.0, 20.0, 20.0)]
    solid = OccupancyGrid.from_polygons(block, bounds=(-25.0, -25.0, 25.0, 25.0), resolution=RES)
    found = ScanMatcher().match(solid, scan, guess)
    assert found.reason == "degenerate" and not found.converged
    assert found.pose == guess and np.isinf(np.diag(found.covariance)).all()


@pytest.mark.parametrize("guess", [TRUE, Pose2D(0.5, -0.2, 0.4)])
def test_a_corridor_on_cell_edges_is_degenerate_as_off_them(guess: Pose2D) -> None:
    walls = [LineString([(-20.0, -1.0), (20.0, -1.0)]), LineString([(-20.0, 1.0), (20.0, 1.0)])]
    scan = _scan(walls, 4.0)  # the corridor's ends out of reach
    for shift in (0.0, RES / 4):
        bounds = (-22.0, -3.0 + shift, 22.0, 3.0 + shift)
        grid = OccupancyGrid.from_polygons(walls, bounds=bounds, resolution=RES)
        found = ScanMatcher().match(grid, scan, guess)
        assert found.reason == "degenerate" and not found.converged, (shift, found)


def test_a_room_on_cell_edges_stays_converged_from_near_guesses() -> None:
    room = [box(-4.0, -4.0, 4.0, 4.0).exterior, box(1.0, 1.0, 2.0, 1.5)]
    scan = _scan(room, 10.0)
    grid = OccupancyGrid.from_polygons(room, bounds=(-4.5, -4.5, 4.5, 4.5), resolution=RES)
    for guess in (TRUE, Pose2D(0.31, -0.19, 0.401), Pose2D(0.28, -0.21, 0.398)):
        found = ScanMatcher().match(grid, scan, guess)
        assert found.reason == "converged", (guess, found)
        assert math.hypot(found.pose.x - TRUE.x, found.pose.y - TRUE.y) < RES
        assert found.covariance[0, 0] == pytest.approx(RES**2 / 12.0, rel=1e-12)


@pytest.mark.parametrize(
    "weights",
    [
        {"translation_weight": 1.0, "rotation_weight": 1.0},
        {"translation_weight": 1.0},
        {"rotation_weight": 1.0},
    ],
)
def test_a_plateau_match_is_converged_with_a_prior_too(weights: dict[str, float]) -> None:
    # The prior's Hessian kept the solve regular (or singular but not zero), so the
    # plateau rule never ran: "degenerate" at the guess, where without a prior the
    # same match was "converged" (ScanMapper's default matcher has both weights).
    room = [box(-4.0, -4.0, 4.0, 4.0).exterior, box(1.0, 1.0, 2.0, 1.5)]
    scan = _scan(room, 10.0)
    grid = OccupancyGrid.from_polygons(room, bounds=(-4.5, -4.5, 4.5, 4.5), resolution=RES)
    guess = Pose2D(0.31, -0.19, 0.401)
    found = ScanMatcher(**weights).match(grid, scan, guess)  # type: ignore[arg-type]
    assert found.reason == "converged" and found.converged, found
    assert math.hypot(found.pose.x - TRUE.x, found.pose.y - TRUE.y) < RES
    assert found.covariance[0, 0] == pytest.approx(RES**2 / 12.0, rel=1e-12)
    # And inside a solid block a prior does not make a lost match converged.
    block = [box(-20.0, -20.0, 20.0, 20.0)]
    solid = OccupancyGrid.from_polygons(block, bounds=(-25.0, -25.0, 25.0, 25.0), resolution=RES)
    lost = ScanMatcher(**weights).match(solid, scan, Pose2D(5.0, 3.0, 1.0))  # type: ignore[arg-type]
    assert lost.reason == "degenerate" and not lost.converged
