"""The indoor scenarios' end-point snap (``plan_between``) never steps through a wall.

A start or goal on an impassable cell is joined to a passable cell centre within
``SNAP_DISTANCE``. The nearest one as the crow flies may lie beyond a thin wall
(a start in a narrow corridor filled by the inflation): the path then began by
driving through the wall. The snap now takes the nearest centre whose straight
step touches no obstacle cell but those of the obstacle the point is in. Checked
against an independent reference: shapely's closed-set distance from every
step to every obstacle cell's square, all cells of the map tried.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray
from scipy import ndimage
from shapely.geometry import LineString, Point, box

from hypothesis_twins import slow_twin
from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner, Path2D
from navkit.sim.scenarios._indoor_nav_mapping import SNAP_DISTANCE, _passable, plan_between


def corridor() -> MapPlanner:
    """A 1-cell wall (column 10) and, left of it, a corridor the inflation fills.

    0.05 m cells, robot radius 0.1 m: columns 8-12 are impassable beside the
    wall, columns 3-7 beside the corridor's other wall (column 5, rows 6 up).
    """
    occupied = np.zeros((16, 16), dtype=bool)
    occupied[:, 10] = True
    occupied[6:, 5] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.05)
    return MapPlanner(grid, robot_radius=0.1)


WALL = box(0.5, 0.0, 0.55, 0.8)  # column 10 of corridor(), in the world frame
# In the corridor (cell (9, 9)): the passable centre nearest as the crow flies is
# (0.675, 0.475), 0.18 m away beyond the wall; the nearest on this side is
# (0.375, 0.275), 0.233 m away round the corridor's end.
IN_CORRIDOR = (0.495, 0.475)
FAR_SIDE_GOAL = (0.725, 0.075)
NEAR_SIDE_GOAL = (0.075, 0.075)


def test_a_start_beside_a_thin_wall_is_not_snapped_through_it() -> None:
    planner = corridor()
    snapped = _passable(planner, IN_CORRIDOR)
    assert snapped == pytest.approx((0.375, 0.275))
    # The planner's own escape (start_tolerance) agrees.
    escape = planner.plan(IN_CORRIDOR, NEAR_SIDE_GOAL, start_tolerance=SNAP_DISTANCE)
    assert escape.points[1].tolist() == pytest.approx(list(snapped))
    path = plan_between(planner, IN_CORRIDOR, NEAR_SIDE_GOAL)
    assert path.points[0].tolist() == list(IN_CORRIDOR)
    assert path.points[1].tolist() == pytest.approx(list(snapped))
    assert path.points[-1].tolist() == pytest.approx(list(NEAR_SIDE_GOAL), abs=0.03)
    assert not LineString(path.points).intersects(WALL)
    # The other side is reached only round the wall: there is no way round.
    with pytest.raises(NoPathError):
        plan_between(planner, IN_CORRIDOR, FAR_SIDE_GOAL)


def test_a_goal_beside_a_thin_wall_is_not_snapped_through_it() -> None:
    planner = corridor()
    path = plan_between(planner, NEAR_SIDE_GOAL, IN_CORRIDOR)
    assert path.points[-1].tolist() == list(IN_CORRIDOR)
    assert path.points[-2].tolist() == pytest.approx([0.375, 0.275])
    assert not LineString(path.points).intersects(WALL)


def test_a_point_in_the_wall_leaves_it_on_the_nearer_side() -> None:
    # A built map may draw a wall over the point: leaving that wall is allowed.
    planner = corridor()
    point = (0.54, 0.475)  # in the wall's cell (9, 10), near its right face
    assert _passable(planner, point) == pytest.approx((0.675, 0.475))


def obstacle_cells(planner: MapPlanner) -> NDArray[np.bool_]:
    """Impassable cells that are not free on the map: occupied or (impassable) unknown."""
    return ~np.isfinite(planner.costs) & ~planner.grid.free()


def reference_snap(
    planner: MapPlanner, point: tuple[float, float]
) -> tuple[list[tuple[float, tuple[float, float]]], bool]:
    """Every admissible snap ``(distance, centre)`` by brute force, and whether it is clear-cut.

    Continuous grid coordinates (cell ``(r, c)`` the square ``[r-1/2, r+1/2] x
    [c-1/2, c+1/2]``): a step crosses an obstacle cell when shapely's distance
    between them is 0 (closed sets), except a cell whose edge holds the point
    itself, which a step crosses only by entering its inside (leaving a wall's
    face is allowed). The point's own obstacle: the 8-connected
    blob of obstacle cells around its cell, among the cells within
    ``ceil(SNAP_DISTANCE / resolution) + 1`` rows and columns of it (those a step
    can touch). Not clear-cut: a step within 1e-7 cells of a foreign cell without
    touching it, the point within 1e-7 cells of one, or a centre within 1e-9 m
    of the snap distance.
    """
    grid, costs = planner.grid, planner.costs
    rows, cols = costs.shape
    q = np.asarray(grid.world_to_cell(np.array(point), continuous=True), dtype=float)
    r, c = (int(v) for v in grid.world_to_cell(np.array(point)))
    k = math.ceil(SNAP_DISTANCE / grid.resolution) + 1
    obstacle = obstacle_cells(planner)
    foreign = obstacle.copy()
    if obstacle[r, c]:
        near = np.zeros_like(obstacle)
        near[max(r - k, 0) : r + k + 1, max(c - k, 0) : c + k + 1] = True
        labels, _ = ndimage.label(obstacle & near, structure=np.ones((3, 3)))
        foreign &= labels != labels[r, c]
    squares = [box(fr - 0.5, fc - 0.5, fr + 0.5, fc + 0.5) for fr, fc in np.argwhere(foreign)]
    at_q = [s.distance(Point(q)) == 0.0 for s in squares]
    found: list[tuple[float, tuple[float, float]]] = []
    clear_cut = not any(0.0 < s.distance(Point(q)) < 1e-7 for s in squares)
    for rr in range(rows):
        for cc in range(cols):
            if not math.isfinite(costs[rr, cc]):
                continue
            x, y = (float(v) for v in grid.cell_to_world(np.array([rr, cc])))
            d = math.dist(point, (x, y))
            clear_cut &= abs(d - SNAP_DISTANCE) > 1e-9
            if d > SNAP_DISTANCE:
                continue
            step = LineString([q, (rr, cc)])  # q is in an impassable cell: never (rr, cc)
            gaps = [step.distance(s) for s in squares]
            clear_cut &= not any(0.0 < g < 1e-7 for g in gaps)
            crossed = (
                step.intersects(s) and not step.touches(s) if edge else g == 0.0
                for s, g, edge in zip(squares, gaps, at_q, strict=True)
            )
            if not any(crossed):
                found.append((d, (x, y)))
    return found, clear_cut


def _on_an_obstacle_square(planner: MapPlanner, point: tuple[float, float]) -> bool:
    """Whether ``point`` lies on the closed square of an obstacle cell (its edge, say)."""
    q = Point(planner.grid.world_to_cell(np.array(point), continuous=True))
    squares = (
        box(r - 0.5, c - 0.5, r + 0.5, c + 0.5) for r, c in np.argwhere(obstacle_cells(planner))
    )
    return any(s.distance(q) == 0.0 for s in squares)


def straight(costs: NDArray[np.float64], start: tuple[int, int], goal: tuple[int, int]) -> Path2D:
    """A CellPlanner that never searches: the step from ``start`` to ``goal``."""
    length = math.dist(start, goal)
    return Path2D(np.array([start, goal], dtype=float), "grid", cost=length, length=length,
                  expanded=0)  # fmt: skip


@st.composite
def maps_and_points(draw: st.DrawFn) -> tuple[MapPlanner, tuple[float, float]]:
    rows = draw(st.integers(4, 12))
    cols = draw(st.integers(4, 12))
    resolution = draw(st.sampled_from([0.05, 0.1]))
    cells = st.lists(st.booleans(), min_size=rows * cols, max_size=rows * cols)
    occupied = np.array(draw(cells)).reshape(rows, cols) & draw(st.booleans())
    if not occupied.any():  # walls, not noise: rows or columns of cells
        for _ in range(draw(st.integers(1, 3))):
            if draw(st.booleans()):
                occupied[draw(st.integers(0, rows - 1)), :] = True
            else:
                occupied[:, draw(st.integers(0, cols - 1))] = True
            gap = draw(st.integers(0, max(rows, cols)))
            occupied.ravel()[gap % occupied.size] = False
    unknown = np.array(draw(cells)).reshape(rows, cols) & ~occupied & draw(st.booleans())
    origin = (draw(st.floats(-3.0, 3.0)), draw(st.floats(-3.0, 3.0)), 0.0)
    grid = OccupancyGrid.from_occupancy(
        occupied, resolution=resolution, origin=origin, unknown=unknown
    )
    radius = draw(st.sampled_from([0.0, 0.05, 0.1, 0.15]))
    planner = MapPlanner(grid, robot_radius=radius)
    # Inside the map, never on its edge (where rounding may put the point outside).
    u, v = draw(st.floats(1e-6, 1.0 - 1e-6)), draw(st.floats(1e-6, 1.0 - 1e-6))
    point = (origin[0] + u * cols * resolution, origin[1] + v * rows * resolution)
    return planner, point


def _wall_band_case(point: tuple[float, float]) -> tuple[MapPlanner, tuple[float, float]]:
    """A point in the inflation band beside a wall column."""
    occupied = np.zeros((6, 6), dtype=bool)
    occupied[:, 3] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, origin=(0.0, 0.0, 0.0))
    return MapPlanner(grid, robot_radius=0.15), point


def _unknown_edge_case() -> tuple[MapPlanner, tuple[float, float]]:
    """A point on the top edge of an unknown cell, in the band its inflation makes."""
    unknown = np.zeros((10, 5), dtype=bool)
    unknown[4, 0] = True
    grid = OccupancyGrid.from_occupancy(
        np.zeros((10, 5), dtype=bool), resolution=0.05, origin=(0.0, 0.0, 0.0), unknown=unknown
    )
    return MapPlanner(grid, robot_radius=0.05), (0.03125, 0.25)


@settings(max_examples=25)
@given(maps_and_points())
# The draws reach the inflation-band escape check at the end 0 to 3 times a run (none in
# 2 of 8 seeds): these two, one each side of the wall, reach it every run.
@example(_wall_band_case((0.21, 0.27)))
@example(_wall_band_case((0.45, 0.33)))
@example(_unknown_edge_case())
def test_the_snap_is_the_nearest_centre_reached_without_crossing_another_obstacle(
    case: tuple[MapPlanner, tuple[float, float]],
) -> None:
    planner, point = case
    r, c = (int(v) for v in planner.grid.world_to_cell(np.array(point)))
    snapped = _passable(planner, point)
    if math.isfinite(planner.costs[r, c]):
        assert snapped == point
        return
    found, clear_cut = reference_snap(planner, point)
    assume(clear_cut)
    if not found:
        assert snapped == point
        return
    nearest = min(d for d, _ in found)
    assert math.dist(point, snapped) == pytest.approx(nearest, abs=1e-12)
    admissible = [centre for _, centre in found]
    assert any(math.dist(snapped, centre) < 1e-12 for centre in admissible)
    # Only in the inflation: the planner's own escape takes a centre as near (the
    # search itself replaced by a straight step: only the escape matters here).
    if not obstacle_cells(planner)[r, c]:
        escaping = MapPlanner(planner.grid, robot_radius=planner.robot_radius, planner=straight)
        if _on_an_obstacle_square(planner, point):
            # On an obstacle cell's edge (a thorough run drew (0.03125, 0.25) on 0.05 m
            # cells, on an unknown cell's top edge): the snap may leave its face, but the
            # planner's escape refuses any segment touching a hard square (a corner
            # included, as documented), and every segment from there touches this one.
            with pytest.raises(ValueError, match="no passable cell centre within"):
                escaping.plan(point, snapped, start_tolerance=SNAP_DISTANCE)
            return
        escape = escaping.plan(point, snapped, start_tolerance=SNAP_DISTANCE)
        assert math.dist(point, escape.points[1]) == pytest.approx(nearest, abs=1e-12)


test_the_snap_is_the_nearest_centre_reached_without_crossing_another_obstacle_thoroughly = (
    slow_twin(
        test_the_snap_is_the_nearest_centre_reached_without_crossing_another_obstacle,
        max_examples=60,
    )
)
