"""World: obstacle kinds, clearance against shapely, collisions, moving obstacles, bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import example, given, settings
from hypothesis import strategies as st
from shapely.geometry import LineString, MultiPolygon, Point, Polygon, box

from hypothesis_twins import slow_twin
from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.sim import Circle, MovingObstacle, World
from navkit.sim._edge_grid_kernels import build_cell_lists, chebyshev_distance
from navkit.sim._latency import DelayLine
from navkit.sim._trace import cross_track

SQUARE = np.array([[-0.3, -0.2], [0.3, -0.2], [0.3, 0.2], [-0.3, 0.2]])


def test_obstacle_kinds() -> None:
    walls = box(0, 0, 10, 10).exterior
    holey = box(2, 2, 5, 5).difference(box(3, 3, 4, 4))
    world = World([walls, holey, LineString([(6, 1), (9, 1)]), Circle((8.0, 8.0), 0.5),
                   MultiPolygon([box(6, 5, 7, 6), box(8, 5, 9, 6)])])  # fmt: skip
    assert world.segments.shape == (4 + 8 + 1 + 8, 4)
    assert world.circles.tolist() == [[8.0, 8.0, 0.5]]
    assert world.bounds == (0.0, 0.0, 10.0, 10.0)
    assert not world.segments.flags.writeable
    # Inside the hole of a polygon is free space.
    assert not world.collides(0.2, (3.5, 3.5, 0.0))
    assert world.collides(0.2, (2.5, 2.5, 0.0))
    assert world.collides(0.2, (8.0, 8.0, 0.0))  # inside the solid circle
    assert not World(Circle((8.0, 8.0), 3.0, solid=False)).collides(0.2, (8.0, 8.0, 0.0))
    assert "<21 edges, 1 circle>" in repr(world)


def test_empty_world() -> None:
    world = World()
    assert world.bounds is None
    assert world.raycast((0, 0, 0), [0.0, 1.0], range_max=5.0).tolist() == [math.inf, math.inf]
    assert world.clearance(0.2, (0, 0, 0)) == math.inf
    assert not world.collides(SQUARE, (0, 0, 0))


footprint = st.sampled_from([0.25, SQUARE, np.array([[0.0, -0.3], [0.4, 0.0], [0.0, 0.3]])])


@settings(max_examples=30, deadline=None)
@given(
    fp=footprint,
    x=st.floats(-6.0, 6.0),
    y=st.floats(-6.0, 6.0),
    theta=st.floats(-math.pi, math.pi),
)
# A wall's end vertex exactly on the footprint's edge: touching, though rounding
# puts the computed distance a few 1e-17 m above zero.
@example(fp=np.array([[0.0, -0.3], [0.4, 0.0], [0.0, 0.3]]), x=0.0, y=4.625, theta=0.0)
def test_clearance_equals_shapely_distance(fp: object, x: float, y: float, theta: float) -> None:
    obstacles = [box(1.0, 1.0, 2.5, 1.6), Polygon([(-4, -4), (-2, -5), (-3, -2)]),
                 LineString([(-5, 3), (0, 4.5)])]  # fmt: skip
    circle = Point(4.0, -3.0).buffer(1.0, quad_segs=512)
    world = World([*obstacles, Circle((4.0, -3.0), 1.0)])
    pose = Pose2D(x, y, theta)
    if isinstance(fp, float):
        shape = Point(x, y).buffer(fp, quad_segs=512)
    else:
        shape = Polygon(pose.transform_points(fp))
    bounds = [shapely.boundary(o) if isinstance(o, Polygon) else o for o in obstacles]
    bounds.append(circle.exterior)
    expected = min(shape.distance(b) for b in bounds)
    # Inside a solid obstacle the clearance is to its boundary; collides() says so.
    inside_solid = any(shape.within(o) for o in [*obstacles[:2], circle])
    got = world.clearance(fp, pose)
    assert got == pytest.approx(expected, abs=2e-4)  # the buffered disc's own error
    if expected > 2e-4:
        assert world.collides(fp, pose) == inside_solid
    elif expected == 0.0:
        assert world.collides(fp, pose)


test_clearance_equals_shapely_distance_thoroughly = slow_twin(
    test_clearance_equals_shapely_distance, max_examples=80
)


def test_clearance_on_an_occupancy_grid() -> None:
    occupied = np.zeros((20, 20), dtype=bool)
    occupied[10, 15] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, origin=(1.0, 2.0, 0.5))
    world = World(grid=grid)
    cell = Polygon(grid.origin.transform_points([[1.5, 1.0], [1.6, 1.0], [1.6, 1.1],
                                                 [1.5, 1.1]]))  # fmt: skip
    pose = Pose2D(*grid.cell_to_world([10, 5]), 0.3)
    expected = Polygon(pose.transform_points(SQUARE)).distance(cell)
    assert world.clearance(SQUARE, pose) == pytest.approx(expected, abs=1e-12)
    disc = Point(pose.x, pose.y).buffer(0.2, quad_segs=1024).distance(cell)
    assert world.clearance(0.2, pose) == pytest.approx(disc, abs=1e-5)
    assert world.collides(0.2, [*grid.cell_to_world([10, 15]).tolist(), 0.0])


def test_moving_obstacles() -> None:
    ball = MovingObstacle.constant_velocity(0.2, start_xy=(0.0, 0.0), velocity_xy=(1.0, 0.0))
    sq = box(-0.25, -0.25, 0.25, 0.25)
    guard = MovingObstacle.scripted(sq, [(5.0, 0.0), (5.0, 2.0)], speed=1.0, after="loop")
    timed = MovingObstacle.scripted(0.1, [(0, 0), (1, 0), (1, 1)], times=[0.0, 1.0, 3.0])
    world = World(moving=[ball, guard, timed])
    assert world.moving == (ball, guard, timed)
    np.testing.assert_allclose(ball.position_at(3.0), [3.0, 0.0])
    np.testing.assert_allclose(guard.position_at(2.5), [5.0, 0.5])
    np.testing.assert_allclose(timed.position_at(-1.0), [0.0, 0.0])
    np.testing.assert_allclose(timed.position_at(9.0), [1.0, 1.0])
    # The ball reaches x = 2 at t = 2: a ray from (2, -3) up meets it then.
    r = world.raycast((2.0, -3.0, math.pi / 2), [0.0], range_max=10.0, t=2.0)[0]
    assert r == pytest.approx(2.8)
    assert world.raycast((2.0, -3.0, math.pi / 2), [0.0], range_max=10.0, t=0.0)[0] == math.inf
    assert world.collides(0.1, (5.0, 0.5, 0.0), t=2.5)
    assert not world.collides(0.1, (5.0, 0.5, 0.0), t=1.0)
    assert world.collides(0.05, (5.0, 1.0, 0.0), t=1.0)  # inside the moving square
    assert guard.geometry_at(1.0).equals(shapely.affinity.translate(sq, 5.0, 1.0))


def test_moving_obstacle_shapes_given_as_vertices_or_with_z() -> None:
    """Vertices (as a footprint takes them) and a polygon with z move like the 2-D polygon."""
    tri = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]
    plain = MovingObstacle.constant_velocity(Polygon(tri), start_xy=(0, 0), velocity_xy=(1, 0))
    expected = World(moving=[plain]).clearance(0.1, (1.5, 1.5, 0.0), t=1.0)
    assert expected == pytest.approx(math.sqrt(0.5) - 0.1)
    for shape in (tri, np.array(tri), Polygon([(x, y, 7.0) for x, y in tri])):
        ob = MovingObstacle.constant_velocity(shape, start_xy=(0, 0), velocity_xy=(1, 0))
        assert isinstance(ob.shape, Polygon)
        assert ob.geometry_at(1.0).equals(plain.geometry_at(1.0))
        assert World(moving=[ob]).clearance(0.1, (1.5, 1.5, 0.0), t=1.0) == expected
    with pytest.raises(ValueError, match="after"):
        MovingObstacle(0.2, [(0.0, 0.0)], [0.0], after=["loop"])  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("obstacles", "error"),
    [
        (Point(0, 0), ValueError),
        ([box(0, 0, 1, 1), "wall"], TypeError),
        (5, TypeError),
        ([LineString([(0, 0), (2e6, 0)])], ValueError),
    ],
)
def test_bad_obstacles(obstacles: object, error: type[Exception]) -> None:
    with pytest.raises(error):
        World(obstacles)  # type: ignore[arg-type]


def test_bad_world_arguments() -> None:
    with pytest.raises(TypeError, match="grid"):
        World(grid=np.zeros((3, 3)))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="moving"):
        World(moving=[box(0, 0, 1, 1)])  # type: ignore[list-item]
    with pytest.raises(ValueError, match="radius"):
        Circle((0, 0), -1.0)
    with pytest.raises(ValueError, match="strictly increasing"):
        MovingObstacle(0.2, [[0, 0], [1, 1]], [1.0, 1.0])
    with pytest.raises(ValueError, match="exactly one"):
        MovingObstacle.scripted(0.2, [[0, 0], [1, 1]])
    with pytest.raises(ValueError, match="after"):
        MovingObstacle(0.2, [[0, 0]], [0.0], after="bounce")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="range_max"):
        World().raycast((0, 0, 0), [0.0], range_max=0.0)
    with pytest.raises(ValueError, match="holes"):
        World().clearance(box(-1, -1, 1, 1).difference(box(0, 0, 0.5, 0.5)), (0, 0, 0))
    with pytest.raises(ValueError, match="simple"):
        World().clearance([[0, 0], [1, 1], [1, 0], [0, 1]], (0, 0, 0))
    with pytest.raises(TypeError):
        World().clearance(True, (0, 0, 0))  # type: ignore[arg-type]


def test_edge_index_size_is_checked(monkeypatch: pytest.MonkeyPatch) -> None:
    import navkit.sim._world as world_module

    monkeypatch.setattr(world_module, "MAX_INDEX_ENTRIES", 10)
    walls = [LineString([(0.0, float(k) * 0.01), (10.0, 5.0)]) for k in range(20)]
    with pytest.raises(ValueError, match="edge index would need"):
        World(walls)


def test_cell_lists_are_conservative() -> None:
    """Every cell a segment passes through lists it (segments on cell lines included)."""
    segs = np.array([[0.0, 0.0, 4.0, 4.0], [1.0, 0.0, 1.0, 4.0], [0.5, 2.0, 3.5, 2.0]])
    start, items = build_cell_lists(segs, np.empty((0, 3)), 0.0, 0.0, 1.0, 4, 4, 1000)
    cells = {k: set(items[start[k]:start[k + 1]].tolist()) for k in range(16)}
    for k in (0, 5, 10, 15):  # the diagonal
        assert 0 in cells[k]
    for row in range(4):  # x = 1 lies on the line between columns 0 and 1
        assert 1 in cells[row * 4] and 1 in cells[row * 4 + 1]
    for col in range(4):
        assert 2 in cells[2 * 4 + col] and 2 in cells[1 * 4 + col]


def test_chebyshev_distance() -> None:
    occ = np.zeros((5, 6), dtype=np.uint8)
    occ[1, 2] = 1
    d = chebyshev_distance(occ)
    rows, cols = np.indices(occ.shape)
    np.testing.assert_array_equal(d, np.maximum(abs(rows - 1), abs(cols - 2)))
    assert chebyshev_distance(np.zeros((2, 3), np.uint8)).min() == 5


def test_delay_line_keeps_order_and_delay() -> None:
    line: DelayLine[str] = DelayLine(0.08)
    for k in range(5):
        line.push_at(0.02 * k + 0.08, f"r{k}")
    assert line.pop_due(0.079) == []
    assert [item for _, item in line.pop_due(0.12)] == ["r0", "r1", "r2"]
    assert len(line) == 2


def test_cross_track_distance() -> None:
    path = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]])
    pts = np.array([[1.0, 0.5], [3.0, 1.0], [-1.0, 0.0], [2.0, 3.0]])
    np.testing.assert_allclose(cross_track(pts, path), [0.5, 1.0, 1.0, 1.0])
