"""Rays and clearances of random worlds against outside oracles (review 34, mutation testing).

Mutation testing of the simulator's kernels (``_lidar_kernels``,
``_clearance_kernels``, ``_edge_grid_kernels``) left mutants alive that the
hand-made scenes of the older tests never reach: the edge index's slab clip
of a ray starting outside the indexed box, the walk's steps across cells in
the negative directions, the occupancy walk's jumps across large free squares
of a rotated map, the solid test's crossing count toward the nearer side, the
moving obstacles' brute-force loops. Each test here builds random worlds and
checks every ray and every clearance against an oracle written in the test:

* rays against segments by solving the 2x2 system of the ray and the segment,
  against circles by the quadratic, against the cells of a map by the slab
  test of each blocked cell's square (in the map's frame), brute force;
* clearances by shapely's distances (``Polygon.distance``, ``Point.distance``)
  and, for circles, the interval of distances from the centre to the
  footprint ([nearest point, farthest vertex]).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.geometry import LineString, Point, Polygon, box

from navkit.mapping import OccupancyGrid
from navkit.sim import Circle, MovingObstacle, World

TOL = 1e-9


def _ray_segment(o: np.ndarray, d: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    """t >= 0 where o + t d meets segment ab (inf when it does not), by Cramer's rule."""
    e = b - a
    den = d[0] * e[1] - d[1] * e[0]
    w = a - o
    if den == 0.0:
        return math.inf  # parallel: random data never has collinear rays
    t = (w[0] * e[1] - w[1] * e[0]) / den
    u = (w[0] * d[1] - w[1] * d[0]) / den
    return t if t >= 0.0 and 0.0 <= u <= 1.0 else math.inf


def _ray_circle(o: np.ndarray, d: np.ndarray, c: np.ndarray, r: float) -> float:
    """First t >= 0 where o + t d is on the circle (|o + t d - c| = r)."""
    w = o - c
    b = float(w @ d)
    disc = b * b - (float(w @ w) - r * r)
    if disc < 0.0:
        return math.inf
    for t in (-b - math.sqrt(disc), -b + math.sqrt(disc)):
        if t >= 0.0:
            return t
    return math.inf


def _edges(poly: Polygon) -> list[tuple[np.ndarray, np.ndarray]]:
    xy = np.asarray(poly.exterior.coords)
    return [(xy[i], xy[i + 1]) for i in range(len(xy) - 1)]


def _random_edge_world(
    rng: np.random.Generator,
) -> tuple[World, list[tuple[np.ndarray, np.ndarray]], list[tuple[np.ndarray, float]],
           list[Polygon], list[tuple[np.ndarray, float]]]:  # fmt: skip
    """Walls, circular walls, solid triangles and solid discs scattered over 40 x 30 m."""
    walls = []
    for _ in range(25):
        a = rng.uniform([-20.0, -15.0], [20.0, 15.0])
        b = a + rng.uniform(-6.0, 6.0, 2)
        walls.append((a, b))
    rings = [(rng.uniform([-20.0, -15.0], [20.0, 15.0]), float(rng.uniform(0.5, 4.0)))
             for _ in range(5)]  # fmt: skip
    solids = []
    for _ in range(4):
        c = rng.uniform([-20.0, -15.0], [20.0, 15.0])
        tri = Polygon(c + rng.uniform(-3.0, 3.0, (3, 2)))
        if tri.area > 0.5 and all(not tri.intersects(s) for s in solids):
            solids.append(tri)
    discs = [(rng.uniform([-20.0, -15.0], [20.0, 15.0]), float(rng.uniform(0.3, 2.0)))
             for _ in range(4)]  # fmt: skip
    obstacles: list[object] = [LineString([a, b]) for a, b in walls]
    obstacles += [Circle(c, r, solid=False) for c, r in rings]
    obstacles += solids
    obstacles += [Circle(c, r) for c, r in discs]
    return World(obstacles), walls, rings, solids, discs


@pytest.mark.parametrize("seed", range(6))
def test_edge_world_rays_match_brute_force(seed: int) -> None:
    rng = np.random.default_rng(1000 + seed)
    world, walls, rings, solids, discs = _random_edge_world(rng)
    segs = walls + [e for s in solids for e in _edges(s)]
    circles = rings + discs
    angles = np.linspace(-math.pi, math.pi, 97)[:-1] + rng.uniform(-0.01, 0.01)
    # Origins inside and far outside the indexed box (rays clipped to it).
    origins = list(rng.uniform([-22.0, -17.0], [22.0, 17.0], (10, 2)))
    origins += list(rng.uniform([-60.0, -50.0], [60.0, 50.0], (4, 2)))
    origins += [s.representative_point().coords[0] for s in solids[:1]]
    origins += [discs[0][0] + 0.5 * discs[0][1]]
    for o in origins:
        o = np.asarray(o, dtype=float)
        heading = float(rng.uniform(-math.pi, math.pi))
        range_max = float(rng.choice([5.0, 15.0, 200.0]))
        got = world.raycast((o[0], o[1], heading), angles, range_max=range_max)
        inside = any(s.contains(Point(o)) for s in solids) or any(
            math.hypot(*(o - c)) < r for c, r in discs
        )
        for k, a in enumerate(angles):
            phi = heading + a
            d = np.array([math.cos(phi), math.sin(phi)])
            if inside:
                want = 0.0
            else:
                want = min(
                    min(_ray_segment(o, d, p, q) for p, q in segs),
                    min(_ray_circle(o, d, c, r) for c, r in circles),
                )
                if want >= range_max:
                    want = math.inf
            if math.isinf(want):
                assert got[k] == math.inf, (o, k, got[k])
            else:
                assert got[k] == pytest.approx(want, abs=TOL), (o, k)


def test_moving_obstacles_rays_match_brute_force() -> None:
    rng = np.random.default_rng(7)
    tri = np.array([[-1.0, -0.5], [1.2, -0.3], [0.1, 1.1]])
    moving = [
        MovingObstacle.constant_velocity(tri, start_xy=(3.0, 1.0), velocity_xy=(0.5, -0.2)),
        MovingObstacle.constant_velocity(0.7, start_xy=(-4.0, 2.0), velocity_xy=(0.0, 0.3)),
        MovingObstacle.constant_velocity(tri * 0.8, start_xy=(0.0, -4.0), velocity_xy=(-0.4, 0.0)),
    ]
    world = World([box(-10.0, -10.0, 10.0, 10.0).exterior], moving=moving)
    t = 2.0
    angles = np.linspace(-math.pi, math.pi, 181)[:-1]
    wall = _edges(box(-10.0, -10.0, 10.0, 10.0))
    for o in rng.uniform(-9.0, 9.0, (8, 2)):
        parts = [np.array([3.0 + 0.5 * t, 1.0 - 0.2 * t]) + tri,
                 np.array([0.0 - 0.4 * t, -4.0]) + tri * 0.8]  # fmt: skip
        disc_c = np.array([-4.0, 2.0 + 0.3 * t])
        polys = [Polygon(p) for p in parts]
        inside = any(p.contains(Point(o)) for p in polys) or math.hypot(*(o - disc_c)) < 0.7
        segs = wall + [e for p in polys for e in _edges(p)]
        got = world.raycast((o[0], o[1], 0.0), angles, range_max=50.0, t=t)
        for k, a in enumerate(angles):
            d = np.array([math.cos(a), math.sin(a)])
            want = (
                0.0
                if inside
                else min(
                    min(_ray_segment(o, d, p, q) for p, q in segs), _ray_circle(o, d, disc_c, 0.7)
                )
            )
            assert got[k] == pytest.approx(want, abs=TOL), (o, k)


def _cell_hit(o: np.ndarray, d: np.ndarray, x0: float, y0: float, x1: float, y1: float) -> float:
    """Where the ray o + t d (t >= 0) first touches the closed box, by slabs (0 from inside)."""
    lo, hi = 0.0, math.inf
    for p, v, a, b in ((o[0], d[0], x0, x1), (o[1], d[1], y0, y1)):
        if v == 0.0:
            if p < a or p > b:
                return math.inf
            continue
        ta, tb = (a - p) / v, (b - p) / v
        lo, hi = max(lo, min(ta, tb)), min(hi, max(ta, tb))
    return lo if lo <= hi else math.inf


@pytest.mark.parametrize("seed", range(4))
def test_map_rays_match_cell_boxes(seed: int) -> None:
    """A rotated map, sparse cells and wide free areas: the walk's jumps and steps."""
    rng = np.random.default_rng(2000 + seed)
    rows, cols = 70, 90
    occ = rng.random((rows, cols)) < 0.01
    occ[20:50, 30:70] = False  # a free square wide enough to jump across
    occ[rng.integers(0, rows, 6), rng.integers(0, cols, 6)] = True
    res = float(rng.uniform(0.05, 0.3))
    yaw = float(rng.uniform(-math.pi, math.pi))
    origin = np.array([rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0)])
    world = World(grid=OccupancyGrid.from_occupancy(occ, resolution=res, origin=(*origin, yaw)))
    c, s = math.cos(yaw), math.sin(yaw)
    cells = np.argwhere(occ)
    angles = np.linspace(-math.pi, math.pi, 61)[:-1] + 0.003
    w, h = cols * res, rows * res
    local = list(rng.uniform([0.0, 0.0], [w, h], (8, 2)))
    local += [np.array([-0.5 * w, 0.3 * h]), np.array([1.4 * w, 1.2 * h])]  # outside the map
    for p in local:
        o = origin + np.array([c * p[0] - s * p[1], s * p[0] + c * p[1]])
        range_max = float(rng.choice([2.0, 40.0]))
        got = world.raycast((o[0], o[1], 0.0), angles, range_max=range_max)
        for k, a in enumerate(angles):
            # The ray in the map's frame.
            dl = np.array([math.cos(a - yaw), math.sin(a - yaw)])
            want = min(
                _cell_hit(p, dl, col * res, row * res, (col + 1) * res, (row + 1) * res)
                for row, col in cells
            )
            if want >= range_max:
                want = math.inf
            if math.isinf(want):
                assert got[k] == math.inf, (p, k, got[k])
            else:
                assert got[k] == pytest.approx(want, abs=TOL), (p, k)


def _circle_gap(center: np.ndarray, r: float, footprint: Polygon) -> float:
    """Distance from a polygon footprint to a circle's boundary: the distances from the
    centre to the footprint's points fill [near, far], so 0 when r lies within it."""
    near = footprint.distance(Point(center))
    far = max(math.hypot(*(np.asarray(v) - center)) for v in footprint.exterior.coords)
    return near - r if near > r else (r - far if far < r else 0.0)


_FOOTPRINT = np.array([[-0.6, -0.4], [0.7, -0.3], [0.8, 0.35], [-0.5, 0.45]])


@pytest.mark.parametrize("seed", range(5))
def test_clearance_matches_shapely(seed: int) -> None:
    rng = np.random.default_rng(3000 + seed)
    world, walls, rings, solids, discs = _random_edge_world(rng)
    lines = [LineString([a, b]) for a, b in walls] + [s.exterior for s in solids]
    circles = rings + discs
    for _ in range(12):
        x, y, th = rng.uniform([-24.0, -18.0, -math.pi], [24.0, 18.0, math.pi])
        # Disc footprint: distance from the centre less the radius.
        r = float(rng.uniform(0.1, 1.0))
        want = min(
            min(g.distance(Point(x, y)) for g in lines) - r,
            min(abs(math.hypot(x - c[0], y - c[1]) - rc) - r for c, rc in circles),
        )
        assert world.clearance(r, (x, y, th)) == pytest.approx(max(want, 0.0), abs=TOL)
        # Polygon footprint, placed at the pose.
        cth, sth = math.cos(th), math.sin(th)
        placed = Polygon([(x + cth * u - sth * v, y + sth * u + cth * v) for u, v in _FOOTPRINT])
        want = min(
            min(placed.distance(g) for g in lines),
            min(_circle_gap(c, rc, placed) for c, rc in circles),
        )
        assert world.clearance(_FOOTPRINT, (x, y, th)) == pytest.approx(want, abs=TOL)


@pytest.mark.parametrize("seed", range(3))
def test_map_clearance_matches_shapely(seed: int) -> None:
    rng = np.random.default_rng(4000 + seed)
    occ = rng.random((40, 50)) < 0.02
    res = float(rng.uniform(0.1, 0.4))
    yaw = float(rng.uniform(-math.pi, math.pi))
    origin = rng.uniform(-3.0, 3.0, 2)
    world = World(grid=OccupancyGrid.from_occupancy(occ, resolution=res, origin=(*origin, yaw)))
    c, s = math.cos(yaw), math.sin(yaw)

    def to_world(u: float, v: float) -> tuple[float, float]:
        return (origin[0] + c * u - s * v, origin[1] + s * u + c * v)

    corners = ((0.0, 0.0), (res, 0.0), (res, res), (0.0, res))
    squares = [
        Polygon([to_world(col * res + du, row * res + dv) for du, dv in corners])
        for row, col in np.argwhere(occ)
    ]
    for _ in range(10):
        u, v = rng.uniform([-2.0, -2.0], [50 * res + 2.0, 40 * res + 2.0])
        x, y = to_world(u, v)
        th = float(rng.uniform(-math.pi, math.pi))
        r = float(rng.uniform(0.05, 0.5))
        want = max(min(q.distance(Point(x, y)) for q in squares) - r, 0.0)
        assert world.clearance(r, (x, y, th)) == pytest.approx(want, abs=TOL)
        cth, sth = math.cos(th), math.sin(th)
        placed = Polygon(
            [(x + cth * a - sth * b, y + sth * a + cth * b) for a, b in 0.5 * _FOOTPRINT]
        )
        want = min(q.distance(placed) for q in squares)
        assert world.clearance(0.5 * _FOOTPRINT, (x, y, th)) == pytest.approx(want, abs=TOL)


@pytest.mark.parametrize("seed", range(2))
def test_clearance_among_many_small_primitives_matches_brute_force(seed: int) -> None:
    """Hundreds of short walls and small pillars: the index's cells are small, and the
    nearest primitive often lies one ring of cells beyond a farther one already found
    (the ring search may stop only when a ring's cells are all farther than the best)."""
    rng = np.random.default_rng(5000 + seed)
    pillars = [(rng.uniform(0.0, 12.0, 2), float(rng.uniform(0.01, 0.05))) for _ in range(150)]
    walls = []
    for _ in range(150):
        a = rng.uniform(0.0, 12.0, 2)
        walls.append((a, a + rng.uniform(-0.15, 0.15, 2)))
    world = World([Circle(c, r) for c, r in pillars] + [LineString([a, b]) for a, b in walls])
    lines = [LineString([a, b]) for a, b in walls]
    for x, y, th in rng.uniform([-0.5, -0.5, -math.pi], [12.5, 12.5, math.pi], (150, 3)):
        r = 0.02
        p = Point(x, y)
        inside = any(math.hypot(x - c[0], y - c[1]) < rc for c, rc in pillars)
        want = min(
            min(g.distance(p) for g in lines) - r,
            min(abs(math.hypot(x - c[0], y - c[1]) - rc) - r for c, rc in pillars),
        )
        got = world.clearance(r, (x, y, th))
        if not inside:
            assert got == pytest.approx(max(want, 0.0), abs=TOL), (x, y)


@pytest.mark.parametrize("velocity", [(1.5e3, 0.0), (0.0, -2e3)])
def test_constant_velocity_refuses_speeds_beyond_1e3(velocity: tuple[float, float]) -> None:
    with pytest.raises(ValueError, match="velocity_xy"):
        MovingObstacle.constant_velocity(0.5, start_xy=(0.0, 0.0), velocity_xy=velocity)
    ob = MovingObstacle.constant_velocity(0.5, start_xy=(0.0, 0.0), velocity_xy=(1e3, -1e3))
    assert ob.position_at(1.0).tolist() == [1e3, -1e3]  # the ends are within


def test_bounds_hold_every_static_obstacle_circles_included() -> None:
    rng = np.random.default_rng(9)
    world, walls, rings, solids, discs = _random_edge_world(rng)
    shapes = [LineString([a, b]) for a, b in walls] + solids
    shapes += [Point(c).buffer(r, quad_segs=1024) for c, r in rings + discs]
    xs0, ys0, xs1, ys1 = zip(*(g.bounds for g in shapes), strict=True)
    want = (min(xs0), min(ys0), max(xs1), max(ys1))
    assert world.bounds == pytest.approx(want, abs=1e-6)
    assert World(Circle((3.0, -2.0), 0.5)).bounds == (2.5, -2.5, 3.5, -1.5)


@pytest.mark.parametrize("pose", [(2e12, 0.0, 0.0), (0.0, -1.5e12, 0.0)])
def test_query_poses_beyond_1e12_m_are_refused(pose: tuple[float, float, float]) -> None:
    world = World(Circle((0.0, 0.0), 1.0))
    with pytest.raises(ValueError, match="pose must lie within"):
        world.raycast(pose, [0.0], range_max=10.0)
    with pytest.raises(ValueError, match="pose must lie within"):
        world.clearance(0.1, pose)
