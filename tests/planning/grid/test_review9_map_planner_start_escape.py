"""``MapPlanner.plan(..., start_tolerance=...)``: escaping from a start in the inflated band.

A state estimate drifting within ``robot_radius`` of a wall made every replan
fail (the start cell is impassable through the inflation only). With
``start_tolerance`` the planner goes straight from the start point to the
nearest passable cell centre within the tolerance whose segment touches no
occupied (or impassable unknown) cell, then plans from there. The escape cell
is checked against an independent reference: shapely's closed-set
intersection of the segment with every blocked cell's square, candidates in
the documented order; the cost against a numerical integral of the costs
along the segment.
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray
from scipy import ndimage
from shapely.geometry import LineString, box

from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner, plan_path

BAND_COST = 5.0  # 1 + cost_weight: what a band cell costs along an escape segment
#: The escape's documented margin, in cell sides (see navkit.planning.grid._escape).
GRAZE = 1e-9


def hard_cells(planner: MapPlanner, unknown_cost: float = math.inf) -> NDArray[np.bool_]:
    """Cells no escape segment may touch: occupied, or unknown when impassable."""
    grid = planner.grid
    hard = grid.occupied()
    if math.isinf(unknown_cost):
        hard |= grid.unknown()
    return hard


def continuous(planner: MapPlanner, point: Any) -> NDArray[np.float64]:
    return np.asarray(planner.grid.world_to_cell(point, continuous=True), dtype=np.float64)


def reference_escape(
    planner: MapPlanner, start: Any, tolerance: float, hard: NDArray[np.bool_]
) -> tuple[int, int] | None:
    """The documented escape cell, brute force: every cell, shapely segment tests."""
    q = continuous(planner, start)
    res = planner.grid.resolution
    # Grown by the documented margin: a segment within 1e-9 cell sides of a square
    # touches it (one missing a corner by 1e-16, from a start on a diagonal, does).
    g = 0.5 + GRAZE
    blocked = [box(r - g, c - g, r + g, c + g) for r, c in np.argwhere(hard)]
    candidates = []
    rows, cols = planner.costs.shape
    for r in range(rows):
        for c in range(cols):
            if not np.isfinite(planner.costs[r, c]):
                continue
            d2 = (r - q[0]) ** 2 + (c - q[1]) ** 2
            if math.sqrt(d2) * res <= tolerance:
                candidates.append((d2, r, c))
    for _, r, c in sorted(candidates):
        segment = LineString([tuple(q), (r, c)])
        if not any(segment.intersects(b) for b in blocked):
            return r, c
    return None


def escape_cost(planner: MapPlanner, start: Any, cell: tuple[int, int], n: int = 200_000) -> float:
    """Midpoint-rule integral of the costs along the escape segment, cost-weighted metres."""
    q = continuous(planner, start)
    t = (np.arange(n) + 0.5) / n
    pts = q[None, :] + t[:, None] * (np.array(cell) - q)[None, :]
    idx = np.floor(pts + 0.5).astype(int)
    c = planner.costs[idx[:, 0], idx[:, 1]]
    c = np.where(np.isfinite(c), c, BAND_COST)
    length = float(np.hypot(*(np.array(cell) - q))) * planner.grid.resolution
    return float(c.mean()) * length


def check_escape(planner: MapPlanner, start: Any, goal: Any, tolerance: float) -> tuple[int, int]:
    """Plan with an escape and check every documented field; returns the escape cell."""
    path = planner.plan(start, goal, start_tolerance=tolerance)
    start_xy = np.asarray(start, dtype=float)[:2]
    np.testing.assert_array_equal(path.points[0], start_xy)
    cell = tuple(int(v) for v in planner.grid.world_to_cell(path.points[1]))
    expected = reference_escape(planner, start, tolerance, hard_cells(planner))
    assert cell == expected
    centre = planner.grid.cell_to_world(cell)
    np.testing.assert_allclose(path.points[1], centre, rtol=0, atol=1e-12)
    rest = planner.plan(centre, goal)
    np.testing.assert_array_equal(path.points[1:], rest.points)
    segment = float(np.hypot(*(centre - start_xy)))
    assert segment <= tolerance + 1e-12
    assert path.length == pytest.approx(rest.length + segment, rel=1e-12, abs=1e-12)
    assert path.cost == pytest.approx(
        rest.cost + escape_cost(planner, start, cell), rel=1e-4, abs=1e-9
    )
    assert path.expanded == rest.expanded
    return cell


# --------------------------------------------------------------------------- synthetic


def wall_planner(**kw: Any) -> MapPlanner:
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:15, 14:16] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    return MapPlanner(grid, robot_radius=0.2, **kw)


def test_default_still_refuses_and_names_the_option() -> None:
    planner = wall_planner()
    start = (1.33, 0.55)  # cell (5, 13): 0.1 m from the wall's cells, inside the 0.2 m band
    assert not np.isfinite(planner.costs[5, 13])
    msg = r"start .* within robot_radius \(0.2 m\) of an obstacle; pass start_tolerance > 0"
    with pytest.raises(ValueError, match=msg):
        planner.plan(start, (2.55, 0.55))
    with pytest.raises(ValueError, match=msg):
        planner.plan(start, (2.55, 0.55), start_tolerance=0)
    # Too small a tolerance: refused, the message says why.
    with pytest.raises(ValueError, match=r"no passable cell centre within start_tolerance"):
        planner.plan(start, (2.55, 0.55), start_tolerance=0.05)


@pytest.mark.parametrize("name", ["astar", "field_dstar"])
def test_escape_from_the_band_on_a_synthetic_map(name: str) -> None:
    planner = wall_planner(planner=name)
    cell = check_escape(planner, (1.33, 0.55), (2.55, 0.55), 0.3)
    assert cell == (5, 11)


def test_a_passable_start_is_unchanged_by_the_tolerance() -> None:
    planner = wall_planner()
    plain = planner.plan((0.55, 0.55), (2.55, 0.55))
    tolerant = planner.plan((0.55, 0.55), (2.55, 0.55), start_tolerance=5.0)
    np.testing.assert_array_equal(plain.points, tolerant.points)
    assert (plain.cost, plain.length, plain.expanded) == (
        tolerant.cost, tolerant.length, tolerant.expanded
    )


def test_obstacle_unknown_and_outside_starts_are_never_escaped() -> None:
    occupied = np.zeros((12, 12), dtype=bool)
    occupied[5, 5] = True
    unknown = np.zeros((12, 12), dtype=bool)
    unknown[0, 11] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown)
    planner = MapPlanner(grid, robot_radius=0.1)
    goal = (0.25, 0.25)
    with pytest.raises(ValueError, match="is in an obstacle"):
        planner.plan((0.55, 0.55), goal, start_tolerance=10.0)
    with pytest.raises(ValueError, match="is in unknown space"):
        planner.plan((1.15, 0.05), goal, start_tolerance=10.0)
    with pytest.raises(ValueError, match="outside the map"):
        planner.plan((-0.5, 0.5), goal, start_tolerance=10.0)
    # Within robot_radius of unknown space (inflate_unknown): escaped.
    check_escape(planner, (1.05, 0.05), goal, 0.2)
    # The goal gets no tolerance.
    with pytest.raises(ValueError, match=r"goal .* within robot_radius"):
        planner.plan(goal, (0.45, 0.55), start_tolerance=10.0)


def test_never_escapes_through_a_thin_wall() -> None:
    # One-cell walls at cols 7 and 10 across the whole map, radius one cell:
    # cols 6, 8, 9 and 11 are band, the start's pocket between the walls has
    # no passable cell at all.
    occupied = np.zeros((15, 20), dtype=bool)
    occupied[:, 10] = True
    occupied[:, 7] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=1.0)
    planner = MapPlanner(grid, robot_radius=1.0)
    start = (9.1, 7.5)  # continuous (7, 8.6), cell (7, 9): band
    goal = (17.5, 7.5)
    free_cols = set(np.nonzero(np.isfinite(planner.costs[7]))[0].tolist())
    assert {5, 12} <= free_cols and not set(range(6, 12)) & free_cols
    # The nearest free centres, (7, 12) 3.4 m away and (7, 5) 3.6 m away, lie
    # across a wall: refused, however large the tolerance.
    for tolerance in (4.0, 50.0, 1e9):
        with pytest.raises(ValueError, match="no passable cell centre within start_tolerance"):
            planner.plan(start, goal, start_tolerance=tolerance)
    # The wall at col 10 ends at row 11: from (11, 8.6) the escape goes to the
    # free cell below its end, (12, 9), not across it to (11, 12).
    gapped = occupied.copy()
    gapped[12:, 10] = False
    planner = MapPlanner(OccupancyGrid.from_occupancy(gapped, resolution=1.0), robot_radius=1.0)
    assert check_escape(planner, (9.1, 11.5), goal, 6.0) == (12, 9)


def test_a_segment_grazing_a_wall_corner_is_refused() -> None:
    # Start continuous (2, 2), cell (2, 2) in the band of the obstacle at (3, 3).
    # Free cell (4, 4)'s segment passes exactly through the obstacle square's
    # corners: touching counts as crossing.
    occupied = np.zeros((7, 7), dtype=bool)
    occupied[3, 3] = True
    occupied[1, :] = True
    occupied[:, 1] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=1.0)
    planner = MapPlanner(grid, robot_radius=1.5)
    start = (2.5, 2.5)
    assert np.isfinite(planner.costs[5, 5])
    cell = check_escape(planner, start, (6.5, 6.5), 5.0)
    assert cell != (4, 4)


def test_ties_go_to_the_lowest_row_then_column() -> None:
    # Obstacle at (5, 5), radius one cell: its 4-neighbours are band, the
    # diagonals free. From the centre of (5, 6), (4, 6), (5, 7) and (6, 6) are
    # all exactly 1 away (resolution 1: exact arithmetic): (4, 6) wins.
    occupied = np.zeros((11, 11), dtype=bool)
    occupied[5, 5] = True
    planner = MapPlanner(OccupancyGrid.from_occupancy(occupied, resolution=1.0), robot_radius=1.0)
    assert np.isfinite(planner.costs[[4, 5, 6], [6, 7, 6]]).all()
    assert check_escape(planner, (6.5, 5.5), (9.5, 9.5), 1.0) == (4, 6)
    # From the centre of (4, 5): (3, 5) , (4, 4) and (4, 6) tie: (3, 5).
    assert check_escape(planner, (5.5, 4.5), (9.5, 9.5), 1.0) == (3, 5)


@pytest.mark.parametrize(
    ("bad", "error"),
    [
        (-0.1, ValueError),
        (float("nan"), ValueError),
        (float("inf"), ValueError),
        (2e9, ValueError),
        (-0.0 - 1e-300, ValueError),
        (True, TypeError),
        ("0.3", TypeError),
        (None, TypeError),
        (1j, TypeError),
        ([0.3], TypeError),
    ],
)
def test_bad_tolerances_are_refused(bad: Any, error: type[Exception]) -> None:
    planner = wall_planner()
    with pytest.raises(error, match="start_tolerance"):
        planner.plan((0.55, 0.55), (2.55, 0.55), start_tolerance=bad)
    with pytest.raises(error, match="start_tolerance"):
        planner.plan((1.33, 0.55), (2.55, 0.55), start_tolerance=bad)


def test_tolerance_accepts_numpy_and_integers_and_the_limit() -> None:
    planner = wall_planner()
    a = planner.plan((1.33, 0.55), (2.55, 0.55), start_tolerance=np.float32(0.3))
    b = planner.plan((1.33, 0.55), (2.55, 0.55), start_tolerance=1)
    c = planner.plan((1.33, 0.55), (2.55, 0.55), start_tolerance=1e9)
    np.testing.assert_array_equal(a.points, b.points)
    np.testing.assert_array_equal(a.points, c.points)


def test_the_escape_is_reported_in_no_path_errors() -> None:
    occupied = np.zeros((10, 20), dtype=bool)
    occupied[:, 10] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    planner = MapPlanner(grid, robot_radius=0.1)
    with pytest.raises(NoPathError, match=r"escaped to cell \(5, 8\)"):
        planner.plan((0.92, 0.55), (1.55, 0.55), start_tolerance=0.2)


# --------------------------------------------------------------------------- real map


def test_escape_on_the_turtlebot3_map(shared_data: Path) -> None:
    path = shared_data / "ros-map-server-maps" / "turtlebot3_world" / "map.yaml"
    if not path.is_file():
        pytest.skip(f"{path} is not available")
    grid = OccupancyGrid.load(path)
    planner = MapPlanner(grid, robot_radius=0.105, inflation_radius=0.3)
    finite = np.isfinite(planner.costs)
    band = ~finite & ~grid.occupied() & ~grid.unknown()
    # Band cells next to a passable one, and passable cells 4-connected to them.
    near_free = band & ndimage.binary_dilation(finite)
    labels, _ = ndimage.label(finite)
    rows, cols = np.nonzero(near_free)
    assert rows.size > 50
    rng = np.random.default_rng(7)
    hard = hard_cells(planner)
    for k in rng.choice(rows.size, size=6, replace=False):
        r, c = int(rows[k]), int(cols[k])
        start = grid.cell_to_world([r + rng.uniform(-0.4, 0.4), c + rng.uniform(-0.4, 0.4)])
        assert tuple(grid.world_to_cell(start)) == (r, c)
        with pytest.raises(ValueError, match="within robot_radius"):
            planner.plan(start, start)
        escape = reference_escape_window(planner, start, 0.1, hard)
        if escape is None:
            with pytest.raises(ValueError, match="start_tolerance"):
                planner.plan(start, start, start_tolerance=0.1)
            continue
        # A goal in the escape cell's component, far from it.
        comp = np.argwhere(labels == labels[escape])
        far = comp[np.argmax(np.hypot(*(comp - np.array(escape)).T))]
        goal = grid.cell_to_world(far)
        path = planner.plan(start, goal, start_tolerance=0.1)
        assert tuple(grid.world_to_cell(path.points[1])) == escape
        np.testing.assert_array_equal(path.points[0], start)
        rest = planner.plan(grid.cell_to_world(escape), goal)
        assert path.cost == pytest.approx(
            rest.cost + escape_cost(planner, start, escape), rel=1e-4
        )


def reference_escape_window(
    planner: MapPlanner, start: Any, tolerance: float, hard: NDArray[np.bool_]
) -> tuple[int, int] | None:
    """:func:`reference_escape` on the cells within a few cells of ``start`` (a big map)."""
    q = continuous(planner, start)
    reach = math.ceil(tolerance / planner.grid.resolution) + 2
    r0, c0 = max(0, int(q[0]) - reach), max(0, int(q[1]) - reach)
    r1, c1 = int(q[0]) + reach + 1, int(q[1]) + reach + 1
    g = 0.5 + GRAZE  # as in reference_escape
    blocked = [
        box(r + r0 - g, c + c0 - g, r + r0 + g, c + c0 + g)
        for r, c in np.argwhere(hard[r0:r1, c0:c1])
    ]
    candidates = []
    for r, c in np.argwhere(np.isfinite(planner.costs[r0:r1, c0:c1])):
        d2 = (r + r0 - q[0]) ** 2 + (c + c0 - q[1]) ** 2
        if math.sqrt(d2) * planner.grid.resolution <= tolerance:
            candidates.append((d2, int(r + r0), int(c + c0)))
    for _, r, c in sorted(candidates):
        segment = LineString([tuple(q), (r, c)])
        if not any(segment.intersects(b) for b in blocked):
            return r, c
    return None


# --------------------------------------------------------------------------- property


@st.composite
def scenes(
    draw: st.DrawFn,
) -> tuple[MapPlanner, tuple[float, float], tuple[float, float], float, float]:
    rows = draw(st.integers(4, 10))
    cols = draw(st.integers(4, 10))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    occupied = rng.random((rows, cols)) < draw(st.sampled_from([0.08, 0.15, 0.25]))
    unknown = np.zeros((rows, cols), dtype=bool)
    if draw(st.booleans()):
        unknown[draw(st.integers(0, rows - 1)), :] = True
        unknown &= ~occupied
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.5, unknown=unknown)
    radius = draw(st.sampled_from([0.3, 0.5, 0.75, 1.0, 1.2]))
    unknown_cost = draw(st.sampled_from([math.inf, 3.0]))
    planner = MapPlanner(
        grid, robot_radius=radius, unknown_cost=unknown_cost,
        planner=draw(st.sampled_from(["astar", "field_dstar"])),
    )
    # Mostly a start in the band (impassable, neither occupied nor impassable
    # unknown), on a sixteenth-cell lattice: exact, so grazing is decided exactly.
    band = ~np.isfinite(planner.costs) & ~hard_cells(planner, unknown_cost)
    cells = np.argwhere(band) if draw(st.integers(0, 4)) else np.argwhere(occupied | ~occupied)
    if len(cells) == 0:
        cells = np.argwhere(occupied | ~occupied)
    r, c = cells[draw(st.integers(0, len(cells) - 1))]
    start = (
        0.5 * (int(c) + draw(st.integers(0, 15)) / 16),
        0.5 * (int(r) + draw(st.integers(0, 15)) / 16),
    )
    free = np.argwhere(np.isfinite(planner.costs))
    if len(free) == 0:
        free = cells
    g_r, g_c = free[draw(st.integers(0, len(free) - 1))]
    goal = (0.5 * int(g_c) + 0.25, 0.5 * int(g_r) + 0.25)
    tolerance = draw(st.sampled_from([0.0, 0.3, 0.6, 1.2, 3.0, 100.0]))
    return planner, start, goal, tolerance, unknown_cost


@settings(max_examples=60)
@given(scenes())
def test_escaped_paths_never_touch_an_obstacle(
    scene: tuple[MapPlanner, tuple[float, float], tuple[float, float], float, float],
) -> None:
    planner, start, goal, tolerance, unknown_cost = scene
    grid = planner.grid
    cell = tuple(int(v) for v in grid.world_to_cell(start))
    hard = hard_cells(planner, unknown_cost)
    try:
        path = planner.plan(start, goal, start_tolerance=tolerance)
    except NoPathError:
        return
    except ValueError as exc:
        # Refused: the start is not passable and no documented escape exists.
        if "goal" in str(exc).split("(")[0]:
            return
        assert not np.isfinite(planner.costs[cell])
        if hard[cell] or tolerance == 0.0:
            return
        assert reference_escape(planner, start, tolerance, hard) is None
        return
    blocked = [
        box(r - 0.5, c - 0.5, r + 0.5, c + 0.5) for r, c in np.argwhere(hard)
    ]
    pts = np.asarray(grid.world_to_cell(path.points, continuous=True)).reshape(-1, 2)
    if np.isfinite(planner.costs[cell]):
        # No escape: the path starts at the start itself, then the start cell's
        # centre (unless the start is that centre), as without a tolerance.
        np.testing.assert_array_equal(path.points[0], start)
        first = 0 if np.allclose(pts[0], cell, rtol=0.0, atol=1e-9) else 1
        np.testing.assert_allclose(pts[first], cell, rtol=0.0, atol=1e-12)
        return
    # Escaped: the escape segment touches no blocked square at all...
    assert not hard[cell]
    escape = LineString(pts[:2]) if len(pts) > 1 else None
    assert escape is not None
    assert not any(escape.intersects(b) for b in blocked)
    # ... and no part of the path enters one (Field D* may run along edges).
    for a, b in itertools.pairwise(pts):
        seg = LineString([a, b]) if not np.array_equal(a, b) else None
        if seg is None:
            continue
        for square in blocked:
            assert seg.intersection(square).length < 1e-9 or not seg.relate_pattern(
                square, "T********"
            )
    assert tuple(int(v) for v in grid.world_to_cell(path.points[1])) == reference_escape(
        planner, start, tolerance, hard
    )


def test_plan_path_passes_the_tolerance_through() -> None:
    planner = wall_planner()
    with pytest.raises(ValueError, match="start_tolerance"):
        plan_path(planner.grid, (1.33, 0.55), (2.55, 0.55), robot_radius=0.2)
    one_shot = plan_path(
        planner.grid, (1.33, 0.55), (2.55, 0.55), robot_radius=0.2, start_tolerance=0.3
    )
    kept = planner.plan((1.33, 0.55), (2.55, 0.55), start_tolerance=0.3)
    np.testing.assert_array_equal(one_shot.points, kept.points)
    assert (one_shot.cost, one_shot.length) == (kept.cost, kept.length)
