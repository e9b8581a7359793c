"""``FieldDStar.plan_world`` / ``replan_world(..., start_tolerance=...)`` (session 25).

A robot tracking a Field D* path a few centimetres off is often inside the
inflated band, and the world methods refused that start; ``MapPlanner.plan``
escaped it to the nearest passable cell within ``start_tolerance``. The world
methods now take the same keyword, with ``FieldDStar(obstacles=)`` telling
the walls from the inflation (a cost array cannot). Checked here: the escape
cell against a brute force (every cell, shapely's closed-set segment test on
the squares grown by the documented 1e-9-cell margin),
the path against a fresh ``plan_world`` from the escape cell's centre, the
escape segment's cost against a numerical integral, bit-identical results
wherever no escape happens, the refusals and their messages, bad tolerances
and masks, and replanning while the robot drifts into the band (each replan
equal to a fresh plan on the current costs).
"""

from __future__ import annotations

import copy
import math
import pickle
from typing import Any

import numpy as np
import pytest
from hypothesis import assume, event, given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray
from shapely.geometry import LineString, box

from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import FieldDStar, MapPlanner
from navkit.planning.grid import Path2D

BAND_COST = 5.0  # 1 + cost_weight: what an inflation cell costs along an escape segment
# Powers of two: world points and node coordinates convert both ways exactly, so a
# fresh plan_world from the escape cell's centre starts from the very same point.
RESOLUTIONS = (0.25, 0.125, 0.0625)
ORIGIN = (-1.0, 2.0, 0.0)
# The documented margin: a segment within 1e-9 cell sides of an obstacle's square
# touches it. Without it the oracle took segments that miss a corner by 1e-16 cells
# (a start on a cell diagonal, u == v below), which navkit refuses as documented.
GRAZE = 1e-9


def scene(
    occupied: NDArray[np.bool_], res: float, radius_cells: float
) -> tuple[OccupancyGrid, NDArray[np.float64]]:
    grid = OccupancyGrid.from_occupancy(occupied, resolution=res, origin=ORIGIN)
    return grid, grid.traversal_costs(robot_radius=radius_cells * res)


def planner_for(grid: OccupancyGrid, costs: Any, obstacles: Any = None) -> FieldDStar:
    return FieldDStar(
        costs, resolution=grid.resolution, origin=grid.origin, obstacles=obstacles
    )


def cell_q(planner: FieldDStar, xy: Any) -> NDArray[np.float64]:
    """Continuous cell coordinates (integers at centres) of a world point."""
    return np.asarray(planner.world_to_node(xy, continuous=True), dtype=np.float64) - 0.5


def reference_escape(
    costs: NDArray[np.float64],
    hard: NDArray[np.bool_],
    q: NDArray[np.float64],
    res: float,
    tolerance: float,
    graze: float = GRAZE,
) -> tuple[int, int] | None:
    """The documented escape cell, brute force: every cell, shapely segment tests."""
    g = 0.5 + graze
    blocked = [box(r - g, c - g, r + g, c + g) for r, c in np.argwhere(hard)]
    candidates = []
    for r, c in np.argwhere(np.isfinite(costs)):
        d2 = (r - q[0]) ** 2 + (c - q[1]) ** 2
        if math.sqrt(d2) * res <= tolerance:
            candidates.append((d2, int(r), int(c)))
    for _, r, c in sorted(candidates):
        segment = LineString([tuple(q), (r, c)])
        if not any(segment.intersects(b) for b in blocked):
            return r, c
    return None


def escape_cost(
    costs: NDArray[np.float64], q: NDArray[np.float64], cell: tuple[int, int], res: float
) -> float:
    """Midpoint-rule integral of the costs along the escape segment, cost units × m."""
    n = 100_000
    t = (np.arange(n) + 0.5) / n
    pts = q[None, :] + t[:, None] * (np.array(cell) - q)[None, :]
    idx = np.floor(pts + 0.5).astype(int)
    c = costs[idx[:, 0], idx[:, 1]]
    c = np.where(np.isfinite(c), c, BAND_COST)
    return float(c.mean()) * float(np.hypot(*(np.array(cell) - q))) * res


def same(a: Path2D, b: Path2D, expanded: bool = True) -> None:
    np.testing.assert_array_equal(a.points, b.points)
    assert a.frame == b.frame
    assert a.cost == b.cost
    assert a.length == b.length
    if expanded:
        assert a.expanded == b.expanded


def check_escape(
    planner: FieldDStar,
    costs: NDArray[np.float64],
    hard: NDArray[np.bool_],
    start: NDArray[np.float64],
    goal: NDArray[np.float64],
    tolerance: float,
    path: Path2D,
) -> tuple[int, int]:
    """Every documented field of an escaped world path; returns the escape cell."""
    res = planner.resolution
    q = cell_q(planner, start)
    expected = reference_escape(costs, hard, q, res, tolerance)
    assert expected is not None
    # The start as every world path's: the point given, exactly.
    assert path.points[0].tolist() == np.asarray(start, dtype=np.float64).tolist()
    centre = planner.node_to_world((expected[0] + 0.5, expected[1] + 0.5))
    np.testing.assert_array_equal(path.points[1], centre)
    rest = planner_for_costs(planner, costs, hard).plan_world(centre, goal)
    np.testing.assert_array_equal(path.points[1:], rest.points)
    segment = float(np.hypot(*(centre - start)))
    assert segment <= tolerance + 1e-12
    assert path.length == pytest.approx(rest.length + segment, rel=1e-12, abs=1e-12)
    assert path.cost == pytest.approx(
        rest.cost + escape_cost(costs, q, expected, res), rel=1e-4, abs=1e-9
    )
    return expected


def planner_for_costs(
    like: FieldDStar, costs: NDArray[np.float64], hard: NDArray[np.bool_]
) -> FieldDStar:
    return FieldDStar(costs, resolution=like.resolution, origin=like.origin, obstacles=hard)


def wall_scene() -> tuple[OccupancyGrid, NDArray[np.float64]]:
    """A wall at column 10, rows 0-5; 0.125 m cells, radius 0.25 m (2 cells).

    Cell (r, c) spans x in [c, c + 1] / 8, y in [r, r + 1] / 8 m; the inflation
    closes columns 8-12 beside the wall.
    """
    occupied = np.zeros((10, 20), dtype=bool)
    occupied[:6, 10] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.125)
    return grid, grid.traversal_costs(robot_radius=0.25)


BAND = (1.0625, 0.3125)  # the centre of cell (2, 8), in the inflation
WALL = (1.3125, 0.3125)  # cell (2, 10), the wall
GOAL = (1.9375, 0.3125)  # cell (2, 15)
ESCAPE = [0.9375, 0.3125]  # the centre of cell (2, 7), 0.125 m from BAND


# --------------------------------------------------------------------------- maps


@st.composite
def maps(draw: st.DrawFn) -> tuple[NDArray[np.bool_], float, float]:
    rows = draw(st.integers(6, 14))
    cols = draw(st.integers(6, 14))
    density = draw(st.sampled_from([0.05, 0.1, 0.2]))
    seed = draw(st.integers(0, 2**32 - 1))
    occupied = np.random.default_rng(seed).random((rows, cols)) < density
    res = draw(st.sampled_from(RESOLUTIONS))
    radius_cells = draw(st.sampled_from([1.0, 1.5, 2.2]))
    return occupied, res, radius_cells


def point_in(planner: FieldDStar, cell: tuple[int, int], u: float, v: float) -> NDArray[Any]:
    return planner.node_to_world((cell[0] + u, cell[1] + v))


FRACTION = st.floats(0.02, 0.98)


# --------------------------------------------------------------------------- properties


@settings(max_examples=100)
@given(maps(), st.data())
def test_the_escape_is_the_nearest_reachable_passable_centre(
    drawn: tuple[NDArray[np.bool_], float, float], data: st.DataObject
) -> None:
    occupied, res, radius_cells = drawn
    grid, costs = scene(occupied, res, radius_cells)
    band = np.argwhere(~np.isfinite(costs) & ~occupied)
    free = np.argwhere(np.isfinite(costs))
    assume(band.shape[0] > 0 and free.shape[0] > 0)
    planner = planner_for(grid, costs, grid.occupied())
    cell = tuple(int(v) for v in band[data.draw(st.integers(0, band.shape[0] - 1))])
    start = point_in(planner, cell, data.draw(FRACTION), data.draw(FRACTION))
    assume(tuple(int(v) for v in np.floor(cell_q(planner, start) + 0.5)) == cell)
    goal_cell = tuple(int(v) for v in free[data.draw(st.integers(0, free.shape[0] - 1))])
    goal = point_in(planner, goal_cell, data.draw(FRACTION), data.draw(FRACTION))
    tolerance = data.draw(st.floats(0.5, 8.0)) * res
    q = cell_q(planner, start)
    expected = reference_escape(costs, occupied, q, res, tolerance)
    # A segment at about the margin's distance from a square is rounding's to decide.
    margins = {reference_escape(costs, occupied, q, res, tolerance, g) for g in (5e-10, 2e-9)}
    assume(margins == {expected})
    if expected is None:
        event("no escape within the tolerance")
        with pytest.raises(ValueError, match=r"no passable cell centre within start_tolerance"):
            planner.plan_world(start, goal, start_tolerance=tolerance)
        return
    centre = planner.node_to_world((expected[0] + 0.5, expected[1] + 0.5))
    try:
        planner_for_costs(planner, costs, occupied).plan_world(centre, goal)
    except NoPathError:
        event("escaped, no path on")
        with pytest.raises(NoPathError, match=r"\(escaped to cell"):
            planner.plan_world(start, goal, start_tolerance=tolerance)
        return
    event("escaped")
    path = planner.plan_world(start, goal, start_tolerance=tolerance)
    assert check_escape(planner, costs, occupied, start, goal, tolerance, path) == expected


@settings(max_examples=40)
@given(maps(), st.data())
def test_without_an_escape_every_result_is_bit_identical(
    drawn: tuple[NDArray[np.bool_], float, float], data: st.DataObject
) -> None:
    # A planner built as before (no obstacles), called as before (no keyword), against
    # one with obstacles called with a tolerance: passable starts never escape, and a
    # replan sequence (moves, cost updates) gives the same paths bit for bit.
    occupied, res, radius_cells = drawn
    grid, costs = scene(occupied, res, radius_cells)
    free = np.argwhere(np.isfinite(costs))
    assume(free.shape[0] > 1)
    before = planner_for(grid, costs)
    after = planner_for(grid, costs, grid.occupied())
    tolerance = data.draw(st.sampled_from([0.0, 0.0, 1.0, 1e9]))

    def free_point() -> NDArray[Any]:
        cell = tuple(int(v) for v in free[data.draw(st.integers(0, free.shape[0] - 1))])
        return point_in(before, cell, data.draw(FRACTION), data.draw(FRACTION))

    def both(call: Any) -> None:
        try:
            want = call(before, {})
        except (ValueError, NoPathError) as exc:
            with pytest.raises(type(exc)) as got:
                call(after, {"start_tolerance": tolerance})
            if tolerance == 0.0 or "no passable" in str(exc):
                assert str(got.value).startswith(str(exc))
            return
        same(call(after, {"start_tolerance": tolerance}), want)

    start, goal = free_point(), free_point()
    both(lambda p, kw: p.plan_world(start, goal, **kw))
    for _ in range(data.draw(st.integers(1, 4))):
        if data.draw(st.booleans()):
            cells = free[data.draw(st.lists(st.integers(0, free.shape[0] - 1), max_size=3))]
            value = data.draw(st.sampled_from([np.inf, 1.0, 3.0]))
            before.update_costs(cells.reshape(-1, 2), value)
            after.update_costs(cells.reshape(-1, 2), value)
        moved = free_point() if data.draw(st.booleans()) else None
        both(lambda p, kw, moved=moved: p.replan_world(moved, **kw))


def test_the_docstring_case_matches_map_planner() -> None:
    occupied = np.zeros((10, 20), dtype=bool)
    occupied[:6, 10] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    costs = grid.traversal_costs(robot_radius=0.2)
    planner = FieldDStar(costs, resolution=0.1, obstacles=grid.occupied())
    path = planner.plan_world((0.85, 0.25), (1.55, 0.25), start_tolerance=0.2)
    mp = MapPlanner(grid, robot_radius=0.2, planner="field_dstar")
    reference = mp.plan((0.85, 0.25), (1.55, 0.25), start_tolerance=0.2)
    # The same escape cell (2, 7) and segment; the rest differs only by how each links
    # a cell centre (plan_world: its nearest node; MapPlanner: all four corners).
    np.testing.assert_allclose(path.points[:2], reference.points[:2], rtol=0, atol=1e-15)
    check_escape(
        planner, costs, grid.occupied(), np.array([0.85, 0.25]), np.array([1.55, 0.25]), 0.2,
        path,
    )


# --------------------------------------------------------------------------- refusals


def test_refusals_say_why_and_what_to_pass() -> None:
    grid, costs = wall_scene()
    planner = FieldDStar(costs, resolution=0.125, obstacles=grid.occupied())
    with pytest.raises(
        ValueError,
        match=r"^start_xy \(1\.0625, 0\.3125\) is in an impassable cell \(2, 8\) \(cost inf\), "
        r"within the inflation around an obstacle; pass start_tolerance > 0 to escape",
    ):
        planner.plan_world(BAND, GOAL)
    # Never from an obstacle, whatever the tolerance.
    with pytest.raises(ValueError, match=r"impassable cell \(2, 10\) \(cost inf\), an obstacle$"):
        planner.plan_world(WALL, GOAL, start_tolerance=5.0)
    # Nothing within reach: MapPlanner's wording.
    with pytest.raises(
        ValueError,
        match=r"within the inflation around an obstacle, and no passable cell centre within "
        r"start_tolerance \(0\.0625 m\) can be reached in a straight line without crossing an "
        r"obstacle$",
    ):
        planner.plan_world(BAND, GOAL, start_tolerance=0.0625)
    # Without obstacles the planner cannot tell: refused, and the message says why.
    bare = FieldDStar(costs, resolution=0.125)
    with pytest.raises(ValueError, match=r"\(cost inf\)$"):
        bare.plan_world(BAND, GOAL)
    with pytest.raises(
        ValueError, match=r"start_tolerance escapes only a FieldDStar given obstacles="
    ):
        bare.plan_world(BAND, GOAL, start_tolerance=0.25)
    # Outside the grid, and the goal: as before, whatever the tolerance.
    with pytest.raises(ValueError, match=r"start_xy \(-0\.5, 0\.25\) is outside the grid"):
        planner.plan_world((-0.5, 0.25), GOAL, start_tolerance=1.0)
    with pytest.raises(ValueError, match=r"goal_xy \(1\.0625, 0\.3125\) is in an impassable cell"):
        planner.plan_world(GOAL, BAND, start_tolerance=1.0)


def test_an_unreachable_goal_after_an_escape_names_the_escape() -> None:
    grid, costs = wall_scene()
    costs = costs.copy()
    obstacles = grid.occupied()
    costs[:, 14] = np.inf  # a full-height wall between the start and the goal
    obstacles[:, 14] = True
    planner = FieldDStar(costs, resolution=0.125, obstacles=obstacles)
    with pytest.raises(
        NoPathError,
        match=r"no path from start_xy \(1\.0625, 0\.3125\) \(escaped to cell \(2, 7\)\) "
        r"to goal_xy \(1\.9375, 0\.3125\) \(expanded \d+ nodes\)",
    ):
        planner.plan_world(BAND, GOAL, start_tolerance=0.25)


BAD_TOLERANCES = [
    (-0.1, ValueError),
    (math.nan, ValueError),
    (math.inf, ValueError),
    (2e9, ValueError),
    (True, TypeError),
    ("0.2", TypeError),
    (None, TypeError),
]


@pytest.mark.parametrize(("value", "error"), BAD_TOLERANCES)
def test_bad_tolerances_are_named_and_change_nothing(value: Any, error: type) -> None:
    grid, costs = wall_scene()
    planner = FieldDStar(costs, resolution=0.125, obstacles=grid.occupied())
    with pytest.raises(error, match="start_tolerance"):
        planner.plan_world(BAND, GOAL, start_tolerance=value)
    first = planner.plan_world(BAND, GOAL, start_tolerance=0.25)
    with pytest.raises(error, match="start_tolerance"):
        planner.replan_world((0.3125, 0.3125), start_tolerance=value)
    with pytest.raises(error, match="start_tolerance"):
        planner.replan_world(start_tolerance=value)
    same(planner.replan_world(start_tolerance=0.25), first, expanded=False)


@pytest.mark.parametrize(
    ("obstacles", "error", "match"),
    [
        (np.zeros((10, 20)), TypeError, r"obstacles must be a boolean array, got dtype float64"),
        (np.zeros((20, 10), dtype=bool), ValueError, r"obstacles must have the shape of costs"),
        ("mask", TypeError, r"obstacles must be a boolean array"),
        (np.ones((10, 20), dtype=bool), ValueError,
         r"obstacles marks cell \(0, 0\), whose cost is finite \(1\.0\)"),
    ],
)
def test_bad_obstacle_masks_are_named(obstacles: Any, error: type, match: str) -> None:
    _, costs = wall_scene()
    with pytest.raises(error, match=match):
        FieldDStar(costs, resolution=0.125, obstacles=obstacles)


def test_the_mask_is_copied() -> None:
    grid, costs = wall_scene()
    obstacles = grid.occupied()
    kept = obstacles.copy()
    planner = FieldDStar(costs, resolution=0.125, obstacles=obstacles)
    planner.update_costs([(2, 7)], np.inf)
    np.testing.assert_array_equal(obstacles, kept)
    obstacles[2, 8] = True  # the caller's later changes do not reach the planner
    assert planner.plan_world(BAND, GOAL, start_tolerance=0.5).points[0].tolist() == [*BAND]


# --------------------------------------------------------------------------- replanning


def drift_scene() -> tuple[OccupancyGrid, NDArray[np.float64]]:
    """A room with pillars and a wall with a door: the path bends round their bands."""
    occupied = np.zeros((40, 60), dtype=bool)
    occupied[0, :] = occupied[-1, :] = occupied[:, 0] = occupied[:, -1] = True
    occupied[:28, 30] = True  # a wall with a door at the top
    occupied[8:26, 12:15] = True  # pillars
    occupied[14:38, 20:23] = True
    occupied[12:30, 42:45] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.125, origin=ORIGIN)
    # No cost band beyond the inscribed zone: shortest paths bend round its edge.
    return grid, grid.traversal_costs(robot_radius=0.25)


def test_a_robot_drifting_into_the_band_keeps_replanning() -> None:
    grid, costs = drift_scene()
    obstacles = grid.occupied()
    planner = planner_for(grid, costs, obstacles)
    goal = grid.cell_to_world((5, 55))
    tolerance = 0.25
    path = planner.plan_world(grid.cell_to_world((5, 5)), goal, start_tolerance=tolerance)
    current = costs.copy()
    hard = obstacles.copy()
    rng = np.random.default_rng(21)
    escapes = replans = 0
    for step in range(60):
        if step == 8:
            # Something appears on the way: its cells count as obstacles from now on.
            block = [(r, c) for r in range(18, 23) for c in range(35, 40)]
            planner.update_costs(block, np.inf)
            for r, c in block:
                current[r, c] = np.inf
                hard[r, c] = True
        # The robot cuts the path's next corner by a few cm (or overshoots it): often
        # into the band the corner bends round.
        target = path.points[1] if len(path.points) > 2 else goal
        pose = target + rng.normal(0.0, 0.06, 2)
        row, col = (int(v) for v in grid.world_to_cell(pose))
        if hard[row, col]:
            continue
        escaped = not math.isfinite(current[row, col])
        try:
            got = planner.replan_world(pose, start_tolerance=tolerance)
        except ValueError as exc:
            assert escaped and "no passable cell centre" in str(exc)
            continue
        replans += 1
        # Equal to a fresh plan on the current costs and obstacles.
        fresh = FieldDStar(current, resolution=grid.resolution, origin=grid.origin,
                           obstacles=hard).plan_world(pose, goal, start_tolerance=tolerance)
        same(got, fresh, expanded=False)
        np.testing.assert_allclose(got.points[[0, -1]], [pose, goal], rtol=0, atol=1e-12)
        if escaped:
            escapes += 1
            check_escape(planner, current, hard, pose, goal, tolerance, got)
            # No move, no change: the kept start escapes again, to the same path.
            same(planner.replan_world(start_tolerance=tolerance), got, expanded=False)
        path = got
        if len(path.points) <= 2 and float(np.hypot(*(pose - goal))) < 0.3:
            break
    assert escapes >= 2
    assert replans >= 10


def test_the_kept_start_is_the_point_given() -> None:
    grid, costs = wall_scene()
    planner = FieldDStar(costs, resolution=0.125, obstacles=grid.occupied())
    escaped = planner.plan_world(BAND, GOAL, start_tolerance=0.25)
    assert escaped.points[1].tolist() == ESCAPE
    # replan_world() escapes again from BAND, with its own tolerance.
    same(planner.replan_world(start_tolerance=0.25), escaped, expanded=False)
    with pytest.raises(ValueError, match=r"\(kept from the last plan\) is in an impassable cell "
                       r"\(2, 8\) \(cost inf\), within the inflation.*pass start_tolerance > 0"):
        planner.replan_world()
    # Refused, nothing changed: the same path again.
    same(planner.replan_world(start_tolerance=0.25), escaped, expanded=False)
    # Once the band cell opens, the point itself is the start: no escape segment.
    planner.update_costs([(2, 8)], 1.0)
    direct = planner.replan_world()
    fresh = FieldDStar(planner.costs, resolution=0.125)
    same(direct, fresh.plan_world(BAND, GOAL), expanded=False)
    # A node start kept from replan() is never escaped: replan_world() starts at that node.
    planner.plan_world((1.0625, 0.4375), GOAL, start_tolerance=0.25)
    planner.replan((2, 2))
    assert planner.replan_world(start_tolerance=0.25).points[0].tolist() == [0.25, 0.25]


def test_a_kept_world_start_closed_by_update_costs_is_an_obstacle() -> None:
    grid, costs = wall_scene()
    planner = FieldDStar(costs, resolution=0.125, obstacles=grid.occupied())
    planner.plan_world((0.4375, 0.5625), GOAL)  # cell (4, 3)
    planner.update_costs([(4, 3)], np.inf)
    for tolerance in (0.0, 0.5):
        with pytest.raises(
            ValueError, match=r"\(kept from the last plan\) .*\(4, 3\).* since update_costs\(\)"
        ):
            planner.replan_world(start_tolerance=tolerance)


def test_cells_closed_by_update_costs_are_obstacles_to_the_escape() -> None:
    grid, costs = wall_scene()
    planner = FieldDStar(costs, resolution=0.125, obstacles=grid.occupied())
    start = np.array([1.05, 0.2875])  # continuous cell (1.8, 7.9), in cell (2, 8)
    goal = np.array(GOAL)
    assert planner.plan_world(start, goal, start_tolerance=0.25).points[1].tolist() == ESCAPE
    # A new obstacle in cell (2, 7): the escape goes round it, to (1, 7).
    planner.update_costs([(2, 7)], np.inf)
    hard = grid.occupied()
    hard[2, 7] = True
    path = planner.plan_world(start, goal, start_tolerance=0.25)
    assert check_escape(planner, planner.costs, hard, start, goal, 0.25, path) == (1, 7)
    # Opened again, it is no obstacle any more: the nearest again.
    planner.update_costs([(2, 7)], 1.0)
    assert planner.plan_world(start, goal, start_tolerance=0.25).points[1].tolist() == ESCAPE
    # A band cell closed again keeps its kind: still escaped from.
    planner.update_costs([(2, 8)], np.inf)
    assert planner.plan_world(start, goal, start_tolerance=0.25).points[1].tolist() == ESCAPE


def test_copies_and_pickles_keep_the_mask_and_the_escape() -> None:
    grid, costs = wall_scene()
    planner = FieldDStar(costs, resolution=0.125, obstacles=grid.occupied())
    escaped = planner.plan_world(BAND, GOAL, start_tolerance=0.25)
    for twin in (copy.copy(planner), copy.deepcopy(planner), pickle.loads(pickle.dumps(planner))):
        same(twin.replan_world(start_tolerance=0.25), escaped, expanded=False)
        # A new obstacle at the escape cell: from BAND, (1, 7) and (3, 7) are behind
        # its corners and (2, 6) behind it.
        twin.update_costs([(2, 7)], np.inf)
        with pytest.raises(ValueError, match="no passable cell centre"):
            twin.replan_world(start_tolerance=0.25)
    # The copies' updates did not reach the original's costs or mask.
    same(planner.replan_world(start_tolerance=0.25), escaped, expanded=False)


def test_a_pickle_without_the_new_slots_loads_without_a_mask() -> None:
    _, costs = wall_scene()
    planner = FieldDStar(costs, resolution=0.125)
    planner.plan_world((0.3125, 0.3125), GOAL)
    instance, slots = planner.__reduce_ex__(4)[2]
    slots = {k: v for k, v in slots.items() if k not in ("_obstacles", "_escape")}
    old = FieldDStar.__new__(FieldDStar)
    old.__setstate__(copy.deepcopy((instance, slots)))
    same(old.replan_world((0.4375, 0.3125)), planner.replan_world((0.4375, 0.3125)),
         expanded=False)
    with pytest.raises(ValueError, match="given obstacles="):
        old.replan_world(BAND, start_tolerance=0.25)


# --------------------------------------------------------------------------- update_costs


def ring_planner(obstacles: Any) -> FieldDStar:
    """Uniform 0.125 m cells; a new obstacle at cell (4, 4) grown by 2 cells."""
    planner = FieldDStar(np.ones((10, 10)), resolution=0.125, obstacles=obstacles)
    planner.plan_world((0.0625, 0.0625), (1.1875, 1.1875))
    grown = [(r, c) for r in range(2, 7) for c in range(2, 7) if abs(r - 4) + abs(c - 4) <= 3]
    planner.update_costs(grown, np.inf, obstacles=False)
    planner.update_costs([(4, 4)], np.inf, obstacles=True)
    return planner


RING = np.array([0.3125, 0.5625])  # cell (4, 2), in the ring, west of the obstacle
HIT = np.array([0.5625, 0.5625])  # cell (4, 4), the obstacle


@pytest.mark.parametrize("built", ["mask", "none"])
def test_a_ring_marked_as_inflation_is_escaped_from(built: str) -> None:
    planner = ring_planner(np.zeros((10, 10), dtype=bool) if built == "mask" else None)
    got = planner.replan_world(RING, start_tolerance=0.25)
    hard = np.zeros((10, 10), dtype=bool)
    hard[4, 4] = True
    assert check_escape(planner, planner.costs, hard, RING, np.array([1.1875, 1.1875]), 0.25,
                        got) == (4, 1)
    fresh = FieldDStar(planner.costs, resolution=0.125, obstacles=hard)
    same(got, fresh.plan_world(RING, (1.1875, 1.1875), start_tolerance=0.25), expanded=False)
    with pytest.raises(ValueError, match=r"\(4, 4\) \(cost inf\), an obstacle$"):
        planner.replan_world(HIT, start_tolerance=1.0)


def test_the_escape_never_crosses_a_cell_marked_as_an_obstacle() -> None:
    planner = ring_planner(np.zeros((10, 10), dtype=bool))
    east = np.array([0.8125, 0.5625])  # cell (4, 6): its nearest way out is east, (4, 7)
    assert planner.replan_world(east, start_tolerance=0.2).points[1].tolist() == [0.9375, 0.5625]
    # Cell (4, 7) becomes part of the obstacle: (3, 7) and (5, 7) lie behind its corners,
    # nothing else within 0.2 m.
    planner.update_costs([(4, 7)], np.inf, obstacles=True)
    with pytest.raises(ValueError, match="no passable cell centre within"):
        planner.replan_world(east, start_tolerance=0.2)
    # Marked as inflation instead, its corner may be touched: (3, 7), the lower of two ties.
    planner.update_costs([(4, 7)], np.inf, obstacles=False)
    assert planner.replan_world(east, start_tolerance=0.2).points[1].tolist() == [0.9375, 0.4375]


def test_update_costs_obstacles_per_cell_the_last_wins() -> None:
    planner = FieldDStar(np.ones((4, 4)), obstacles=np.zeros((4, 4), dtype=bool))
    planner.update_costs([(1, 1), (1, 2), (1, 1)], np.inf, obstacles=[True, False, False])
    # (1, 1) is inflation (its last flag), (1, 2) too: a start in either may escape.
    for start in ((1.5, 1.5), (2.5, 1.5)):
        assert planner.plan_world(start, (3.5, 3.5), start_tolerance=1.0).points[0].tolist() == [
            *start
        ]
    # Only the kind changes: the costs and the search stay.
    first = planner.plan_world((0.5, 0.5), (3.5, 3.5))
    planner.update_costs([(1, 1)], np.inf, obstacles=True)
    assert planner.replan_world().expanded == 0  # the cached path: no repair
    with pytest.raises(ValueError, match=r"\(1, 1\) \(cost inf\), an obstacle$"):
        planner.plan_world((1.5, 1.5), (3.5, 3.5), start_tolerance=1.0)
    same(planner.plan_world((0.5, 0.5), (3.5, 3.5)), first)


@pytest.mark.parametrize(
    ("obstacles", "error", "match"),
    [
        (np.array([1.0, 0.0]), TypeError, r"obstacles must be a bool or a boolean array"),
        (1, TypeError, r"obstacles must be a bool or a boolean array, got dtype int"),
        ("yes", TypeError, r"obstacles must be a bool or a boolean array"),
        ([True, False, True], ValueError, r"obstacles must be a bool or have shape \(2,\)"),
        ([True, True], ValueError,
         r"obstacles marks cell \(1, 2\), whose new cost is finite \(3\.0\)"),
    ],
)
def test_bad_update_flags_are_named_and_change_nothing(
    obstacles: Any, error: type, match: str
) -> None:
    planner = FieldDStar(np.ones((4, 4)), obstacles=np.zeros((4, 4), dtype=bool))
    first = planner.plan_world((0.5, 0.5), (3.5, 3.5))
    with pytest.raises(error, match=match):
        planner.update_costs([(1, 1), (1, 2)], [np.inf, 3.0], obstacles=obstacles)
    np.testing.assert_array_equal(planner.costs, np.ones((4, 4)))
    same(planner.replan_world(), first, expanded=False)
