"""Review 46: the simulated LiDAR against references written from the geometry alone.

Every expected range here comes from code that shares nothing with navkit's
kernels: shapely's own ray/polygon intersection for polygon worlds, an exact
rational slab test (``fractions.Fraction``) for lattice worlds whose beams pass
exactly through corners and along faces, a float slab test per blocked cell for
occupancy grids, and the quadratic of a ray and a circle. The sensor pose is
composed by hand from the robot pose and the mount, and the beam angles are
those the :class:`~navkit.sim.Lidar` docstring states (``angle_min + k *
angle_increment``, counter-clockwise, in the sensor frame).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely import affinity
from shapely.geometry import LineString, Point, Polygon, box

from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.sim import Circle, Lidar, RangeNoise, Robot, Simulation, World

#: Relative agreement of two exact computations in floats (both round a few times).
TOL = 1e-9


def documented_angles(n_beams: int, fov: float) -> np.ndarray:
    """Beam angles in the sensor frame as the Lidar docstring states them (not wrapped)."""
    if fov >= 2.0 * math.pi:
        return -math.pi + (2.0 * math.pi / n_beams) * np.arange(n_beams)
    if n_beams == 1:
        return np.zeros(1)
    return -0.5 * fov + (fov / (n_beams - 1)) * np.arange(n_beams)


def sensor_pose(pose: tuple[float, float, float],
                mount: tuple[float, float, float]) -> tuple[float, float, float]:  # fmt: skip
    """``pose ⊕ mount`` written out: the mount's offset rotated by the robot's heading."""
    x, y, th = pose
    mx, my, mth = mount
    c, s = math.cos(th), math.sin(th)
    return x + c * mx - s * my, y + s * mx + c * my, th + mth


def shapely_range(geoms: list, solids: list, ox: float, oy: float, phi: float,
                  range_max: float) -> float:  # fmt: skip
    """First boundary point along the ray, by shapely; 0 from inside (or on) a solid."""
    origin = Point(ox, oy)
    if any(s.covers(origin) for s in solids):
        return 0.0
    ray = LineString([(ox, oy), (ox + range_max * math.cos(phi), oy + range_max * math.sin(phi))])
    best = math.inf
    for g in geoms:
        hit = ray.intersection(g.boundary if isinstance(g, Polygon) else g)
        if not hit.is_empty:
            best = min(best, origin.distance(hit))
    return best if best < range_max else math.inf


def close(expected: float, got: float) -> bool:
    return expected == got or abs(expected - got) <= TOL * max(1.0, abs(expected))


#: The LiDAR's on-line tolerance (``_lidar_kernels._ON_LINE``, documented on ``Lidar``):
#: a wall end within it of a beam's line is on the line, a sensor within it of a wall
#: on the wall.
ON_LINE = 1e-9


def agrees(geoms: list, solids: list, ox: float, oy: float, phi: float,
           range_max: float, got: float) -> bool:  # fmt: skip
    """``got`` is the shapely range, or one the on-line tolerance allows.

    Where a wall passes within ``ON_LINE`` of the beam (or of the sensor), the
    LiDAR may meet it there: ``got`` may then be as short as the first boundary
    point of the ray widened by the tolerance, and no longer than the exact one.
    """
    expected = shapely_range(geoms, solids, ox, oy, phi, range_max)
    if close(expected, got):
        return True
    origin = Point(ox, oy)
    ray = LineString([(ox, oy), (ox + range_max * math.cos(phi), oy + range_max * math.sin(phi))])
    wide = ray.buffer(2.0 * ON_LINE)
    near = min(
        (origin.distance(hit) for g in geoms
         if not (hit := wide.intersection(g.boundary if isinstance(g, Polygon) else g)).is_empty),
        default=math.inf,
    )  # fmt: skip
    return near < expected and near - TOL * max(1.0, near) <= got <= expected * (1.0 + TOL)


# ----------------------------------------------------------------- polygon worlds
_coord = st.floats(-4.0, 4.0, allow_nan=False)


@st.composite
def polygon_worlds(draw: st.DrawFn) -> tuple[list, list]:
    """Rotated boxes (some solid, some only their outline, one with a hole) and walls."""
    geoms: list = []
    solids: list = []
    for _ in range(draw(st.integers(1, 3))):
        cx, cy = draw(_coord), draw(_coord)
        w, h = draw(st.floats(0.3, 2.5)), draw(st.floats(0.3, 2.5))
        angle = draw(st.floats(-180.0, 180.0))
        outer = affinity.rotate(box(cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2), angle)
        kind = draw(st.sampled_from(["solid", "outline", "holed"]))
        if kind == "outline":
            geoms.append(outer.exterior)
            continue
        if kind == "holed":
            hole = affinity.scale(outer, 0.5, 0.5)
            outer = Polygon(outer.exterior.coords, [hole.exterior.coords])
        geoms.append(outer)
        solids.append(outer)
    for _ in range(draw(st.integers(0, 2))):
        geoms.append(LineString([(draw(_coord), draw(_coord)), (draw(_coord), draw(_coord))]))
    return geoms, solids


@settings(max_examples=30, deadline=None)
@given(
    world=polygon_worlds(),
    pose=st.tuples(st.floats(-5.0, 5.0), st.floats(-5.0, 5.0), st.floats(-math.pi, math.pi)),
    mount=st.tuples(st.floats(-0.4, 0.4), st.floats(-0.4, 0.4), st.floats(-math.pi, math.pi)),
    fov=st.one_of(st.just(2.0 * math.pi), st.floats(0.2, 6.0)),
    n_beams=st.integers(1, 40),
)
def test_polygon_worlds_match_shapely_from_a_rotated_off_centre_mount(
    world: tuple[list, list],
    pose: tuple[float, float, float],
    mount: tuple[float, float, float],
    fov: float,
    n_beams: int,
) -> None:
    geoms, solids = world
    lidar = Lidar(n_beams=n_beams, fov=fov, noise=None, range_min=0.0, range_max=9.0,
                  mount=mount)  # fmt: skip
    scan = lidar.scan(World(geoms), pose)
    angles = documented_angles(n_beams, fov)
    wrapped = np.angle(np.exp(1j * angles))
    wrapped[wrapped <= -math.pi] += 2.0 * math.pi
    np.testing.assert_allclose(scan.angles(), wrapped, rtol=0.0, atol=1e-12)
    np.testing.assert_allclose(lidar.angles(), wrapped, rtol=0.0, atol=1e-12)
    sx, sy, sth = sensor_pose(pose, mount)
    for k, a in enumerate(angles):
        got = float(scan.ranges[k])
        assert agrees(geoms, solids, sx, sy, sth + a, 9.0, got), (
            k, shapely_range(geoms, solids, sx, sy, sth + a, 9.0), got
        )


@pytest.mark.parametrize("gap", [2.121e-174, 1e-12, 0.5e-9, 2e-9])
def test_a_wall_end_beside_the_sensor_is_met_within_the_on_line_tolerance(gap: float) -> None:
    """Found by this file's shapely property: a wall whose end is ``gap`` beside the sensor.

    Far below the tolerance every beam's line passes through that end at the
    sensor: every beam reads 0, the sensor on the wall, as ``Lidar`` documents.
    Near it, beams crossing the wall within it of the sensor read 0; beyond it
    (2e-9 m) beams away from the wall see nothing. Every reading is one the
    tolerance allows.
    """
    lidar = Lidar(n_beams=5, noise=None, range_min=0.0, range_max=9.0)
    wall = LineString([(gap, 1.0), (gap, 0.0)])
    ranges = lidar.scan(World([wall]), (0.0, 1.0, 0.0)).ranges
    if gap < 1e-11:
        assert ranges.tolist() == [0.0] * 5
    if gap > ON_LINE:
        assert np.isinf(ranges[[0, 1, 4]]).all()
    for k in range(5):
        assert agrees([wall], [], 0.0, 1.0, float(lidar.angles()[k]), 9.0, float(ranges[k]))


def test_beams_are_counterclockwise_in_the_mounts_frame() -> None:
    """One thin post on beam k's line: only beam k (robot heading + mount + its angle) sees it."""
    pose, mount = (1.0, 1.0, 0.3), (0.2, -0.1, 0.9)
    sx, sy, sth = sensor_pose(pose, mount)
    n, k = 72, 17
    phi = sth + documented_angles(n, 2.0 * math.pi)[k]  # counter-clockwise from the sensor's x
    post = Circle((sx + 3.0 * math.cos(phi), sy + 3.0 * math.sin(phi)), 0.05)
    lidar = Lidar(n_beams=n, noise=None, range_min=0.0, range_max=20.0, mount=mount)
    ranges = lidar.scan(World([post]), pose).ranges
    assert np.flatnonzero(np.isfinite(ranges)).tolist() == [k]
    assert close(2.95, float(ranges[k]))
    # Mirrored (the post clockwise of the heading by the same bearing), the mirrored beam.
    mirror = Lidar(n_beams=n, noise=None, range_min=0.0, range_max=20.0)
    r = mirror.scan(World([Circle((2.0, -2.0), 0.05)]), (0.0, 0.0, 0.0)).ranges
    assert np.flatnonzero(np.isfinite(r)).tolist() == [n // 2 - n // 8]  # at -45°


# ---------------------------------------------------------------- lattice worlds
_DIRS = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1),
         (2, 1), (1, 2), (-2, 1), (1, -3), (-3, -2)]  # fmt: skip


def _slab(o: tuple[Fraction, Fraction], d: tuple[int, int], lo: tuple[int, int],
          hi: tuple[int, int]) -> tuple[Fraction, Fraction] | None:  # fmt: skip
    """Exact parameters where the ray ``o + t d`` (t >= 0) is in the closed box, or None."""
    t0, t1 = Fraction(0), Fraction(10**9)
    for p, dd, a, b in ((o[0], d[0], lo[0], hi[0]), (o[1], d[1], lo[1], hi[1])):
        if dd == 0:
            if p < a or p > b:
                return None
            continue
        ta, tb = (a - p) / dd, (b - p) / dd
        t0, t1 = max(t0, min(ta, tb)), min(t1, max(ta, tb))
    return (t0, t1) if t0 <= t1 else None


@pytest.mark.parametrize("seed", range(6))
def test_lattice_worlds_exactly_at_corners_faces_and_on_boundaries(seed: int) -> None:
    """Integer boxes, sensors on a half-integer lattice, beams along lattice directions.

    Beams run along faces, through corners (touching a box at one point), start
    on an outline (0), on or inside a solid (0 on every beam): the exact answer
    is rational, computed with Fractions.
    """
    rng = np.random.default_rng(seed)
    for _ in range(40):
        boxes = []
        for _ in range(int(rng.integers(1, 4))):
            x0, y0 = (int(v) for v in rng.integers(-4, 4, 2))
            w, h = (int(v) for v in rng.integers(1, 4, 2))
            boxes.append(((x0, y0), (x0 + w, y0 + h), bool(rng.random() < 0.5)))
        world = World([box(*lo, *hi) if solid else box(*lo, *hi).exterior
                       for lo, hi, solid in boxes])  # fmt: skip
        o = (Fraction(int(rng.integers(-10, 14)), 2), Fraction(int(rng.integers(-10, 14)), 2))
        got = world.raycast((float(o[0]), float(o[1]), 0.0),
                            [math.atan2(b, a) for a, b in _DIRS], range_max=100.0)  # fmt: skip
        in_solid = any(s and lo[0] <= o[0] <= hi[0] and lo[1] <= o[1] <= hi[1]
                       for lo, hi, s in boxes)  # fmt: skip
        for d, g in zip(_DIRS, got.tolist(), strict=True):
            best: Fraction | None = Fraction(0) if in_solid else None
            for lo, hi, solid in boxes:
                if in_solid:
                    break
                span = _slab(o, d, lo, hi)
                if span is None:
                    continue
                strictly_in = lo[0] < o[0] < hi[0] and lo[1] < o[1] < hi[1]
                # An outline seen from strictly inside is met where the ray leaves it.
                t = span[1] if (strictly_in and not solid) else span[0]
                best = t if best is None or t < best else best
            expected = math.inf if best is None else float(best) * math.hypot(*d)
            assert close(expected, g), (boxes, o, d, expected, g)


# -------------------------------------------------------------- occupancy grids
def cell_face_range(blocked: np.ndarray, res: float, origin: tuple[float, float, float],
                    ox: float, oy: float, phi: float, range_max: float) -> float:  # fmt: skip
    """Distance to the first closed blocked cell along the ray, by a slab test per cell."""
    gx, gy, gth = origin
    c, s = math.cos(gth), math.sin(gth)
    u = c * (ox - gx) + s * (oy - gy)
    v = -s * (ox - gx) + c * (oy - gy)
    du, dv = math.cos(phi - gth), math.sin(phi - gth)
    # An axis direction written as an angle is the axis (cos(pi/2) is 6e-17, not 0).
    du = 0.0 if abs(du) < 1e-12 else du
    dv = 0.0 if abs(dv) < 1e-12 else dv
    best = math.inf
    for row, col in zip(*np.nonzero(blocked), strict=True):
        t0, t1 = 0.0, math.inf
        hit = True
        for p, d, a in ((u, du, col * res), (v, dv, row * res)):
            b = a + res
            if d == 0.0:
                hit = hit and a - TOL <= p <= b + TOL
                continue
            ta, tb = sorted(((a - p) / d, (b - p) / d))
            t0, t1 = max(t0, ta), min(t1, tb)
        if hit and t0 <= t1 + TOL:
            best = min(best, t0)
    return best if best < range_max else math.inf


@pytest.mark.parametrize("seed", range(4))
def test_grid_worlds_match_cell_faces_on_lines_and_corners(seed: int) -> None:
    """Random maps (origins turned by multiples of 45° and at random), sensors on grid lines."""
    rng = np.random.default_rng(100 + seed)
    for _ in range(30):
        rows, cols = (int(v) for v in rng.integers(3, 9, 2))
        blocked = rng.random((rows, cols)) < 0.2
        res = float(rng.choice([0.05, 0.1, 0.25, 0.5]))
        yaw = float(rng.choice([0.0, math.pi / 2, math.pi, -math.pi / 2, math.pi / 4,
                                rng.uniform(-math.pi, math.pi)]))  # fmt: skip
        origin = (float(rng.uniform(-2, 2)), float(rng.uniform(-2, 2)), yaw)
        grid = OccupancyGrid(np.where(blocked, 10.0, -10.0), resolution=res, origin=origin)
        # On the half-cell lattice (grid lines, corners, centres), a little outside too.
        u = int(rng.integers(-1, 2 * cols + 2)) * res / 2
        v = int(rng.integers(-1, 2 * rows + 2)) * res / 2
        c, s = math.cos(yaw), math.sin(yaw)
        pose = (origin[0] + c * u - s * v, origin[1] + s * u + c * v,
                yaw + float(rng.choice([0.0, math.pi / 4, math.atan2(1, 2), 0.37])))  # fmt: skip
        lidar = Lidar(n_beams=16, noise=None, range_min=0.0, range_max=50.0)
        ranges = lidar.scan(World(grid=grid), pose).ranges
        for k, a in enumerate(documented_angles(16, 2.0 * math.pi)):
            expected = cell_face_range(blocked, res, origin, pose[0], pose[1], pose[2] + a, 50.0)
            assert close(expected, float(ranges[k])), (k, expected, ranges[k], u / res, v / res)


def test_grid_and_polygons_together_read_the_nearer() -> None:
    blocked = np.zeros((10, 10), dtype=bool)
    blocked[5, 8] = True  # x in [0.8, 0.9), y in [0.5, 0.6)
    grid = OccupancyGrid(np.where(blocked, 10.0, -10.0), resolution=0.1)
    wall = LineString([(0.6, -1.0), (0.6, 0.52)])
    world = World([wall], grid=grid)
    lidar = Lidar(n_beams=4, noise=None, range_min=0.0, range_max=5.0)
    # From (0.1, 0.55): ahead the wall ends below the beam (0.52), the cell at 0.8.
    assert lidar.scan(world, (0.1, 0.55, 0.0)).ranges[2] == pytest.approx(0.7, abs=1e-12)
    # From (0.1, 0.5): the beam runs along the cell's lower face and crosses the wall first.
    assert lidar.scan(world, (0.1, 0.5, 0.0)).ranges[2] == pytest.approx(0.5, abs=1e-12)


# ---------------------------------------------------------------------- circles
def circle_range(centre: tuple[float, float], radius: float, ox: float, oy: float,
                 phi: float) -> float:  # fmt: skip
    """First t >= 0 with |o + t u - c| = radius (u the unit direction): the quadratic's root."""
    wx, wy = ox - centre[0], oy - centre[1]
    b = wx * math.cos(phi) + wy * math.sin(phi)
    disc = b * b - (wx * wx + wy * wy - radius * radius)
    if disc < 0.0:
        return math.inf
    roots = [t for t in (-b - math.sqrt(disc), -b + math.sqrt(disc)) if t >= 0.0]
    return min(roots) if roots else math.inf


@pytest.mark.parametrize("offset", [0.0, 0.3, 0.999, 1.0, 1.0 + 1e-6])
def test_circle_secants_and_tangents(offset: float) -> None:
    """A beam at lateral offset ``e`` from the centre meets r = 1 at d - sqrt(1 - e²)."""
    d = 5.0
    world = World([Circle((d, offset), 1.0)])
    r = float(world.raycast((0.0, 0.0, 0.0), [0.0], range_max=20.0)[0])
    if offset > 1.0:
        assert r == math.inf
    else:
        assert close(d - math.sqrt(1.0 - offset * offset), r)
    # From inside a hollow circle (a ring): its far side.
    ring = World([Circle((0.0, 0.0), 2.0, solid=False)])
    far = ring.raycast((0.5, 0.0, 0.0), [math.pi, 0.0], range_max=9.0)
    assert close(2.5, float(far[0])) and close(1.5, float(far[1]))


# ------------------------------------------------------- inside, limits, no return
@pytest.mark.parametrize("obstacle", ["solid polygon", "solid circle", "blocked cell"])
@pytest.mark.parametrize("range_min", [0.0, 0.15])
def test_a_sensor_inside_an_obstacle_reads_zero_or_too_close(obstacle: str,
                                                             range_min: float) -> None:  # fmt: skip
    if obstacle == "blocked cell":
        world = World(grid=OccupancyGrid(np.full((4, 4), 10.0), resolution=1.0))
    elif obstacle == "solid circle":
        world = World([Circle((2.0, 2.0), 1.5)])
    else:
        world = World([box(0.0, 0.0, 4.0, 4.0)])
    lidar = Lidar(n_beams=9, noise=None, range_min=range_min, range_max=10.0)
    ranges = lidar.scan(world, (2.0, 2.0, 0.4)).ranges
    assert ranges.tolist() == [-math.inf if range_min > 0.0 else 0.0] * 9
    # The robot's centre free but the mount inside: the sensor decides.
    mounted = Lidar(n_beams=9, noise=None, range_min=range_min, range_max=10.0,
                    mount=(3.0, 0.0, 0.0))  # fmt: skip
    assert np.all(mounted.scan(world, (-1.0, 2.0, 0.0)).ranges == ranges)


def test_range_max_is_no_return_and_range_min_too_close() -> None:
    world = World([LineString([(2.0, -5.0), (2.0, 5.0)])])
    # A wall exactly at range_max is "no return" (REP 117: at or beyond); just inside it reads.
    at = Lidar(n_beams=1, fov=0.1, noise=None, range_min=0.0, range_max=2.0)
    assert at.scan(world, (0.0, 0.0, 0.0)).ranges.tolist() == [math.inf]
    inside = Lidar(n_beams=1, fov=0.1, noise=None, range_min=0.0, range_max=math.nextafter(2, 3))
    assert inside.scan(world, (0.0, 0.0, 0.0)).ranges.tolist() == [2.0]
    near = Lidar(n_beams=1, fov=0.1, noise=None, range_min=2.5, range_max=9.0)
    assert near.scan(world, (0.0, 0.0, 0.0)).ranges.tolist() == [-math.inf]
    # Nothing in range: +inf, the same with noise (no reading to noise).
    noisy = Lidar(n_beams=3, fov=0.1, range_min=0.0, range_max=1.0)
    assert noisy.scan(world, (0.0, 0.0, 0.0), seed=1).ranges.tolist() == [math.inf] * 3


# ------------------------------------------------------------------- in the loop
def test_simulated_scans_are_taken_from_the_step_pose_through_the_mount() -> None:
    """Every recorded scan equals a scan from the trace's pose at its stamp."""
    world = World([box(-3.0, -2.0, 4.0, 3.0).exterior, Circle((2.0, 1.0), 0.3)])
    lidar = Lidar(n_beams=30, noise=None, range_min=0.0, range_max=10.0, rate=10.0,
                  mount=(0.1, 0.05, -0.6))  # fmt: skip
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15, lidar=lidar)
    trace = Simulation(world, robot, lambda obs: (0.3, 0.0, 0.5), start=(-1.0, 0.0, 0.2),
                       duration=2.0, record_scans=True).run()  # fmt: skip
    assert len(trace.scans) == 21
    for reading in trace.scans:
        i = int(np.flatnonzero(trace.times == reading.stamp)[0])
        x, y, th = trace.poses[i]
        sx, sy, sth = sensor_pose((float(x), float(y), float(th)), (0.1, 0.05, -0.6))
        for k, a in enumerate(documented_angles(30, 2.0 * math.pi)):
            phi = sth + a
            room = shapely_range([box(-3.0, -2.0, 4.0, 3.0).exterior], [], sx, sy, phi, 10.0)
            post = circle_range((2.0, 1.0), 0.3, sx, sy, phi)
            assert close(min(room, post), float(reading.scan.ranges[k]))


# --------------------------------------------------------------------- statistics
def test_range_noise_by_band_has_the_stated_mean_and_spread() -> None:
    """``r (1 + bias_b + sigma_b z)``, band by the true range; dropouts at their rate.

    20,000 scans, fixed seed: the means are checked to 5 standard errors
    (sigma / sqrt(n)), the standard deviations to 5 standard errors of a sample
    standard deviation (sigma / sqrt(2 n)), the dropout rate to 5 binomial
    standard errors.
    """
    world = World(box(-2.0, -3.5, 4.0, 3.5).exterior)
    noise = RangeNoise(limits=(3.0, math.inf), sigma=(0.02, 0.05), bias=(0.01, -0.03))
    lidar = Lidar(n_beams=4, noise=noise, range_min=0.1, range_max=20.0, dropout=0.1)
    rng = np.random.default_rng(46)
    n = 20_000
    ranges = np.array([lidar.scan(world, (0.0, 0.0, 0.0), seed=rng).ranges for _ in range(n)])
    for k, (true, bias, sigma) in enumerate(
        [(2.0, 0.01, 0.02), (3.5, -0.03, 0.05), (4.0, -0.03, 0.05), (3.5, -0.03, 0.05)]
    ):
        col = ranges[:, k]
        kept = col[~np.isnan(col)]
        p = 1.0 - kept.size / n
        assert abs(p - 0.1) < 5.0 * math.sqrt(0.1 * 0.9 / n)
        rel = kept / true - 1.0
        m = kept.size
        assert abs(rel.mean() - bias) < 5.0 * sigma / math.sqrt(m)
        assert abs(rel.std(ddof=1) - sigma) < 5.0 * sigma / math.sqrt(2.0 * m)


def test_angle_jitter_casts_off_the_nominal_beam() -> None:
    """A wall at distance d ahead reads d / cos(e), e ~ N(0, s²): E[d / r] = exp(-s² / 2)."""
    world = World([LineString([(2.0, -50.0), (2.0, 50.0)])])
    s = 0.2
    lidar = Lidar(n_beams=1, fov=0.1, noise=None, range_min=0.0, range_max=100.0,
                  angle_jitter=s)  # fmt: skip
    rng = np.random.default_rng(7)
    n = 20_000
    ratio = np.array([2.0 / lidar.scan(world, (0.0, 0.0, 0.0), seed=rng).ranges[0]
                      for _ in range(n)])  # fmt: skip
    # cos(e) has variance (1 - e^{-s²})² / 2 ... below 1e-3 here: its mean within 5 SE.
    spread = float(ratio.std(ddof=1))
    assert abs(float(ratio.mean()) - math.exp(-s * s / 2.0)) < 5.0 * spread / math.sqrt(n)
    # Reported at the nominal angle, as a real scanner does.
    assert lidar.scan(world, (0.0, 0.0, 0.0), seed=rng).angles().tolist() == [0.0]


@pytest.mark.parametrize("seed", range(3))
def test_large_sparse_grids_jump_across_free_squares_exactly(seed: int) -> None:
    """Hundreds of cells between obstacles: the walk's jumps (free squares) miss nothing."""
    rng = np.random.default_rng(300 + seed)
    rows, cols = (int(v) for v in rng.integers(300, 500, 2))
    blocked = rng.random((rows, cols)) < 0.0005
    blocked[0, :] = True  # one long wall along the map's bottom row
    res = 0.1
    origin = (float(rng.uniform(-2, 2)), float(rng.uniform(-2, 2)),
              float(rng.choice([0.0, math.pi / 2, rng.uniform(-math.pi, math.pi)])))  # fmt: skip
    world = World(grid=OccupancyGrid(np.where(blocked, 10.0, -10.0), resolution=res,
                                     origin=origin))  # fmt: skip
    c, s = math.cos(origin[2]), math.sin(origin[2])
    for _ in range(4):
        u, v = float(rng.uniform(0.0, cols * res)), float(rng.uniform(0.0, rows * res))
        pose = (origin[0] + c * u - s * v, origin[1] + s * u + c * v,
                float(rng.uniform(-math.pi, math.pi)))  # fmt: skip
        range_max = float(rng.choice([60.0, rng.uniform(1.0, 20.0)]))
        lidar = Lidar(n_beams=48, noise=None, range_min=0.0, range_max=range_max)
        ranges = lidar.scan(world, pose).ranges
        for k, a in enumerate(documented_angles(48, 2.0 * math.pi)):
            expected = cell_face_range(blocked, res, origin, pose[0], pose[1], pose[2] + a,
                                       range_max)  # fmt: skip
            assert close(expected, float(ranges[k])), (k, expected, ranges[k])


def test_thousands_of_walls_and_rings_match_shapely_and_the_quadratic() -> None:
    """A cluttered world (the edge index's many cells): shapely for the walls, exact rings."""
    rng = np.random.default_rng(46)
    starts = rng.uniform(-50.0, 50.0, (1500, 2))
    ends = starts + rng.normal(scale=2.0, size=(1500, 2))
    walls = [LineString([tuple(a), tuple(b)]) for a, b in zip(starts, ends, strict=True)]
    rings = [(tuple(rng.uniform(-50.0, 50.0, 2)), float(rng.uniform(0.1, 2.0))) for _ in range(20)]
    world = World(walls + [Circle(cc, r, solid=False) for cc, r in rings])
    for _ in range(3):
        ox, oy = (float(v) for v in rng.uniform(-55.0, 55.0, 2))
        angles = rng.uniform(-math.pi, math.pi, 40)
        got = world.raycast((ox, oy, 0.0), angles, range_max=200.0)
        for a, g in zip(angles.tolist(), got.tolist(), strict=True):
            expected = min([shapely_range(walls, [], ox, oy, a, 200.0)]
                           + [circle_range(cc, r, ox, oy, a) for cc, r in rings])  # fmt: skip
            assert close(expected, g), (ox, oy, a, expected, g)
