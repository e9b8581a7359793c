"""Ray casting of scans into the log-odds grid (integrate_scan and the grid's method)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid, integrate_scan

ROOM = (0.0, 0.0, 6.0, 4.0)  # xmin, ymin, xmax, ymax of the room's inner walls
HIT = math.log(0.7 / 0.3)
MISS = math.log(0.4 / 0.6)


def room_scan(pose: Pose2D, n_beams: int, range_max: float = 10.0) -> LaserScan:
    """Exact ranges from ``pose`` to the walls of ROOM for beams all around."""
    xmin, ymin, xmax, ymax = ROOM
    angles = -math.pi + 2 * math.pi * np.arange(n_beams) / n_beams
    phi = angles + pose.theta
    c, s = np.cos(phi), np.sin(phi)
    with np.errstate(divide="ignore"):
        tx = np.where(c > 0, (xmax - pose.x) / c, (xmin - pose.x) / c)
        ty = np.where(s > 0, (ymax - pose.y) / s, (ymin - pose.y) / s)
    ranges = np.minimum(np.abs(tx), np.abs(ty))
    return LaserScan(
        ranges,
        angle_min=-math.pi,
        angle_increment=2 * math.pi / n_beams,
        range_min=0.05,
        range_max=range_max,
    )


def wall_distance(points: np.ndarray) -> np.ndarray:
    xmin, ymin, xmax, ymax = ROOM
    x, y = points[:, 0], points[:, 1]
    inside = (x >= xmin) & (x <= xmax) & (y >= ymin) & (y <= ymax)
    d_in = np.minimum.reduce([x - xmin, xmax - x, y - ymin, ymax - y])
    dx = np.maximum.reduce([xmin - x, np.zeros_like(x), x - xmax])
    dy = np.maximum.reduce([ymin - y, np.zeros_like(y), y - ymax])
    return np.where(inside, d_in, np.hypot(dx, dy))


@pytest.mark.parametrize("exact", [False, True])
@pytest.mark.parametrize("grid_yaw", [0.0, math.radians(30.0)])
def test_room_scan_maps_walls_and_interior(grid_yaw: float, exact: bool) -> None:
    res = 0.05
    # The rotated grid's origin is placed so that it still covers the whole room.
    # Walls do not lie on cell boundaries, where rounding could pick either cell.
    origin = Pose2D(1.0, -3.2, grid_yaw) if grid_yaw else Pose2D(-1.013, -0.987, 0.0)
    grid = OccupancyGrid.empty(width=10.0, height=10.0, resolution=res, origin=origin)
    pose = Pose2D(2.2, 1.3, 0.4)
    scan = room_scan(pose, 720)
    assert grid.contains(scan.to_points(pose)).all()
    for _ in range(4):
        grid.integrate_scan(scan, pose, exact=exact)

    rows, cols = np.indices(grid.shape)
    centres = grid.cell_to_world(np.column_stack((rows.ravel(), cols.ravel())))
    dist = wall_distance(centres).reshape(grid.shape)
    xmin, ymin, xmax, ymax = ROOM
    inside = (
        (centres[:, 0] > xmin)
        & (centres[:, 0] < xmax)
        & (centres[:, 1] > ymin)
        & (centres[:, 1] < ymax)
    ).reshape(grid.shape)
    occupied = grid.occupied()
    # Occupied cells lie on the walls, within one cell.
    assert occupied.sum() > 0.9 * 2 * (6.0 + 4.0) / res
    assert np.all(dist[occupied] <= res)
    # Every beam end cell is occupied.
    assert np.all(occupied[tuple(grid.world_to_cell(scan.to_points(pose)).T)])
    # The interior the beams crossed is free (cells 2+ cells from the walls). The
    # exact traversal clears every cell a beam passes through; 0.5° beams are
    # at most 4.1 cm apart here, closer than a 5 cm cell, so that is all of them.
    # An 8-connected Bresenham line skips some crossed cells where it steps
    # diagonally, so that mode leaves a few gaps between neighbouring beams.
    interior = inside & (dist > 2 * res)
    coverage = grid.free()[interior].mean()
    assert coverage == 1.0 if exact else coverage > 0.97
    assert not (occupied & interior).any()
    # Nothing beyond the walls was touched.
    outside = ~inside & (dist > 1.5 * res)
    assert np.all(grid.logodds[outside] == 0.0)


def reference_integrate(
    logodds: np.ndarray,
    origin: Pose2D,
    res: float,
    scan: LaserScan,
    pose: Pose2D,
    clamp: tuple[float, float],
) -> np.ndarray:
    """Pure-Python statement of the update rule, independent of the kernel."""

    def bresenham(a: tuple[int, int], b: tuple[int, int]) -> list[tuple[int, int]]:
        (r0, c0), (r1, c1) = a, b
        dr, dc = abs(r1 - r0), abs(c1 - c0)
        sr, sc = (1 if r1 > r0 else -1), (1 if c1 > c0 else -1)
        err, out = dc - dr, []
        while True:
            out.append((r0, c0))
            if (r0, c0) == (r1, c1):
                return out
            e2 = 2 * err
            if e2 > -dr:
                err -= dr
                c0 += sc
            if e2 < dc:
                err += dc
                r0 += sr

    hits: set[tuple[int, int]] = set()
    misses: set[tuple[int, int]] = set()
    cs, sn = math.cos(origin.theta), math.sin(origin.theta)
    dx, dy = pose.x - origin.x, pose.y - origin.y
    # Same floating-point expressions as the kernel (x * (1 / res), not x / res), so
    # both pick the same cell for points on cell boundaries.
    inv = 1.0 / res
    su, sv = (cs * dx + sn * dy) * inv, (-sn * dx + cs * dy) * inv
    start = (math.floor(sv), math.floor(su))
    base = pose.theta - origin.theta + scan.angle_min
    for k, rng in enumerate(scan.ranges):
        if not rng >= scan.range_min:
            continue
        is_hit = rng < scan.range_max
        d = rng if is_hit else scan.range_max
        phi = base + k * scan.angle_increment  # grid-frame heading
        end = (math.floor(sv + d * inv * math.sin(phi)), math.floor(su + d * inv * math.cos(phi)))
        line = bresenham(start, end)
        if is_hit:
            hits.add(line[-1])
            misses.update(line[:-1])
        else:
            misses.update(line)
    out = logodds.astype(np.float64)
    rows, cols = logodds.shape
    for r, c in misses | hits:
        if 0 <= r < rows and 0 <= c < cols:
            out[r, c] = np.clip(out[r, c] + (HIT if (r, c) in hits else MISS), *clamp)
    return out.astype(np.float32)


@settings(max_examples=40, deadline=None)
@given(
    st.floats(-1.0, 1.0),
    st.floats(-1.0, 1.0),
    st.floats(-math.pi, math.pi),
    st.floats(-0.5, 0.5),
    st.lists(
        st.one_of(
            st.floats(0.0, 4.0),
            st.sampled_from([math.inf, -math.inf, math.nan, 3.0, 0.01]),
        ),
        min_size=1,
        max_size=40,
    ),
    st.integers(0, 3),
)
def test_kernel_matches_reference(
    x: float, y: float, theta: float, yaw: float, ranges: list[float], repeats: int
) -> None:
    # A 10 m grid centred on the world origin: every beam (<= 3 m from a sensor
    # within 1 m of the centre) stays inside, so no clipping is involved.
    origin = Pose2D(0.0, 0.0, yaw).compose(Pose2D(-5.0, -5.0, 0.0))
    grid = OccupancyGrid(np.zeros((100, 100)), resolution=0.1, origin=origin)
    scan = LaserScan(ranges, angle_min=-2.0, angle_increment=0.1, range_min=0.05, range_max=3.0)
    pose = Pose2D(x, y, theta)
    clamp = (-2.0, 3.5)
    expected = grid.logodds.copy()
    for _ in range(repeats + 1):
        integrate_scan(grid, scan, pose, hit=HIT, miss=MISS, clamp=clamp)
        expected = reference_integrate(expected, origin, 0.1, scan, pose, clamp)
    assert np.allclose(grid.logodds, expected, atol=1e-5)


@settings(max_examples=40, deadline=None)
@given(
    st.floats(-6.0, 6.0),
    st.floats(-6.0, 6.0),
    st.floats(-math.pi, math.pi),
    st.lists(st.one_of(st.floats(0.1, 9.0), st.just(math.inf)), min_size=1, max_size=30),
    st.integers(0, 60),
    st.integers(0, 60),
)
def test_clipped_beams_match_a_larger_grid(
    x: float, y: float, theta: float, ranges: list[float], r0: int, c0: int
) -> None:
    """A sub-grid sees exactly what the same cells of a larger grid see (exact mode).

    Sensor and beams may lie anywhere, inside or outside the sub-grid; the beams
    are clipped to it. With the exact traversal the crossed cells do not depend on
    where the walk starts, so clipping must not change any cell.
    """
    yaw = 0.3
    big_origin = Pose2D(0.0, 0.0, yaw).compose(Pose2D(-10.0137, -10.0291, 0.0))
    big = OccupancyGrid(np.zeros((200, 200)), resolution=0.1, origin=big_origin)
    sub_origin = big_origin.compose(Pose2D(c0 * 0.1, r0 * 0.1, 0.0))
    sub = OccupancyGrid(np.zeros((50, 70)), resolution=0.1, origin=sub_origin)
    scan = LaserScan(ranges, angle_min=-1.0, angle_increment=0.21, range_min=0.05, range_max=8.0)
    pose = Pose2D(x, y, theta)
    integrate_scan(big, scan, pose, exact=True)
    integrate_scan(sub, scan, pose, exact=True)
    window = big.logodds[r0 : r0 + 50, c0 : c0 + 70]
    assert np.array_equal(window != 0, sub.logodds != 0)
    assert np.array_equal(window > 0, sub.logodds > 0)


def test_no_double_counting_within_a_scan() -> None:
    one = OccupancyGrid.empty(width=5.0, height=5.0, resolution=0.1)
    many = OccupancyGrid.empty(width=5.0, height=5.0, resolution=0.1)
    pose = Pose2D(2.5, 2.5, 0.0)
    integrate_scan(
        one,
        LaserScan([1.5], angle_min=0.3, angle_increment=0.01, range_min=0.1, range_max=4.0),
        pose,
    )
    # Ten identical beams and a fan of nearly parallel ones crossing the same cells.
    integrate_scan(
        many,
        LaserScan([1.5] * 10, angle_min=0.3, angle_increment=1e-9, range_min=0.1, range_max=4.0),
        pose,
    )
    assert np.array_equal(one.logodds, many.logodds)
    fan = OccupancyGrid.empty(width=5.0, height=5.0, resolution=0.1)
    integrate_scan(
        fan,
        LaserScan(
            np.full(90, 2.0),
            angle_min=0.0,
            angle_increment=2 * math.pi / 90,
            range_min=0.1,
            range_max=4.0,
        ),
        pose,
    )
    # Near the sensor all 90 beams share cells; each still changed once.
    values = fan.logodds.astype(np.float64)
    allowed = np.array([0.0, MISS, HIT])
    assert np.all(np.isclose(values[..., None], allowed, atol=1e-6).any(axis=-1))
    assert np.isclose(values[25, 25], MISS, atol=1e-6)


def test_range_max_and_inf_clear_without_marking() -> None:
    grid = OccupancyGrid.empty(width=10.0, height=1.0, resolution=0.1)
    pose = Pose2D(0.05, 0.55, 0.0)
    n = integrate_scan(
        grid,
        LaserScan([math.inf], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=4.0),
        pose,
    )
    row = grid.logodds[5]
    assert n == 41  # cells 0..40 (x in [0, 4.1)), the last one reached at range_max
    assert np.all(row[:41] < 0) and np.all(row[41:] == 0)
    assert not grid.occupied().any()
    again = OccupancyGrid.empty(width=10.0, height=1.0, resolution=0.1)
    integrate_scan(
        again,
        LaserScan([4.0, 7.0], angle_min=0.0, angle_increment=1e-12, range_min=0.1, range_max=4.0),
        pose,
    )
    assert np.array_equal(again.logodds, grid.logodds)
    capped = OccupancyGrid.empty(width=10.0, height=1.0, resolution=0.1)
    integrate_scan(
        capped,
        LaserScan([7.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=8.0),
        pose,
        range_max=4.0,
    )
    assert np.array_equal(capped.logodds, grid.logodds)


def test_invalid_readings_change_nothing() -> None:
    grid = OccupancyGrid.empty(width=4.0, height=4.0, resolution=0.1)
    scan = LaserScan(
        [math.nan, -math.inf, 0.01],
        angle_min=0.0,
        angle_increment=0.5,
        range_min=0.05,
        range_max=3.0,
    )
    assert integrate_scan(grid, scan, Pose2D(2.0, 2.0, 0.0)) == 0
    assert np.all(grid.logodds == 0)


def test_beams_leaving_the_map_are_clipped() -> None:
    grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.1)
    # Sensor outside the map, beams crossing it and ending beyond it.
    n = integrate_scan(
        grid,
        LaserScan([6.0, 6.0], angle_min=-0.05, angle_increment=0.1, range_min=0.1, range_max=8.0),
        Pose2D(-2.0, 1.0, 0.0),
    )
    assert n > 0
    assert not grid.occupied().any()
    # Each of the two diverging beams crosses every column once (Bresenham, x-major).
    assert n == 2 * grid.shape[1]
    assert np.all((grid.logodds < 0).sum(axis=0) == 2)
    # A sensor far away whose beams never reach the map changes nothing.
    assert (
        integrate_scan(
            grid,
            LaserScan([1.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=2.0),
            Pose2D(50, 50, 0),
        )
        == 0
    )


@pytest.mark.parametrize("exact", [False, True])
def test_beams_along_the_top_or_right_edge_enter_no_cell(exact: bool) -> None:
    """Cells are half-open: the lines y = height and x = width lie outside the grid.

    Such beams used to be clipped against the closed window and their cells
    clamped into it, clearing the whole top row or right column.
    """
    beam = {"angle_increment": 0.1, "range_min": 0.1, "range_max": 3.0}
    cases = [
        (LaserScan([5.0], angle_min=0.0, **beam), (-1.0, 2.0, 0.0)),  # along y = 2 (top)
        (LaserScan([1.0], angle_min=math.pi / 2, **beam), (2.0, 0.25, 0.0)),  # along x = 2
        (LaserScan([1.0], angle_min=0.0, **beam), (2.0, 0.25, math.pi / 2)),  # same, yawed
        (LaserScan([2.0], angle_min=-math.pi / 4, **beam), (1.0, 3.0, 0.0)),  # touches (2, 2)
    ]
    for scan, pose in cases:
        grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5)
        assert integrate_scan(grid, scan, pose, hit=1.0, miss=-0.5, exact=exact) == 0
        assert not grid.logodds.any()
    # The bottom and left edge lines belong to the grid's first row and column.
    for scan, pose, cells in (
        (LaserScan([5.0], angle_min=0.0, **beam), (-1.0, 0.0, 0.0), (0, slice(None))),
        (LaserScan([5.0], angle_min=math.pi / 2, **beam), (0.0, -1.0, 0.0), (slice(None), 0)),
    ):
        grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5)
        assert integrate_scan(grid, scan, pose, hit=1.0, miss=-0.5, exact=exact) == 4
        assert np.all(grid.logodds[cells] == -0.5) and np.count_nonzero(grid.logodds) == 4


def test_clamping() -> None:
    grid = OccupancyGrid.empty(width=3.0, height=1.0, resolution=0.1)
    scan = LaserScan([2.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=2.5)
    for _ in range(20):
        integrate_scan(grid, scan, Pose2D(0.05, 0.55, 0.0), clamp=(-1.0, 2.0))
    assert grid.logodds.max() == pytest.approx(2.0)
    assert grid.logodds.min() == pytest.approx(-1.0)


def test_integrate_rejects_bad_input() -> None:
    grid = OccupancyGrid.empty(width=3.0, height=3.0, resolution=0.1)
    scan = LaserScan([1.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=2.0)
    before = grid.logodds.copy()
    with pytest.raises(TypeError, match="scan must be a LaserScan"):
        grid.integrate_scan([1.0], Pose2D(0, 0, 0))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="pose"):
        grid.integrate_scan(scan, [1.0, math.nan, 0.0])
    with pytest.raises(ValueError, match="miss must be <= 0"):
        grid.integrate_scan(scan, Pose2D(1, 1, 0), miss=0.4)
    with pytest.raises(ValueError, match="hit must be >= 0"):
        grid.integrate_scan(scan, Pose2D(1, 1, 0), hit=-0.4)
    with pytest.raises(ValueError, match="clamp"):
        grid.integrate_scan(scan, Pose2D(1, 1, 0), clamp=(2.0, -2.0))
    with pytest.raises(ValueError, match="range_max must be > 0"):
        grid.integrate_scan(scan, Pose2D(1, 1, 0), range_max=-1.0)
    with pytest.raises(TypeError, match="grid must be an OccupancyGrid"):
        integrate_scan(grid.logodds, scan, Pose2D(1, 1, 0))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="scan must be a LaserScan"):
        integrate_scan(grid, scan.ranges, Pose2D(1, 1, 0))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="positional"):
        integrate_scan(grid, scan, Pose2D(1, 1, 0), 0.5)  # type: ignore[call-arg]
    assert np.array_equal(grid.logodds, before)
    # Function and method are one: a 3-sequence pose works for both.
    a, b = grid.copy(), grid.copy()
    assert integrate_scan(a, scan, (1.0, 1.0, 0.3)) == b.integrate_scan(scan, [1.0, 1.0, 0.3]) > 0
    assert np.array_equal(a.logodds, b.logodds)


@settings(max_examples=40, deadline=None)
@given(
    st.floats(0.3, 4.7),
    st.floats(0.3, 3.7),
    st.floats(-math.pi, math.pi),
    st.floats(0.2, 3.0),
)
def test_exact_traversal_visits_the_cells_the_segment_crosses(
    x: float, y: float, heading: float, rng: float
) -> None:
    # Origin off the round numbers hypothesis likes, so no end point sits on a
    # cell boundary (where either neighbour is a correct answer).
    ox, oy = -0.0137, -0.0291
    grid = OccupancyGrid.empty(width=5.0, height=4.0, resolution=0.1, origin=Pose2D(ox, oy, 0.0))
    pose = Pose2D(x, y, heading)
    grid.integrate_scan(
        LaserScan([rng], angle_min=0.0, angle_increment=0.1, range_min=0.05, range_max=5.0),
        pose,
        exact=True,
    )
    visited = {(int(r), int(c)) for r, c in np.argwhere(grid.logodds != 0)}
    end = (x + rng * math.cos(heading), y + rng * math.sin(heading))
    segment = shapely.LineString([(x, y), end])
    rows, cols = np.indices(grid.shape)
    r, c = rows.ravel(), cols.ravel()
    x0, y0 = ox + c * 0.1, oy + r * 0.1
    cells = shapely.box(x0, y0, x0 + 0.1, y0 + 0.1)
    # Crossed: the segment enters the cell's interior; touched: it meets the closed cell.
    enters = shapely.relate_pattern(segment, cells, "T********")
    meets = shapely.intersects(segment, cells)
    crossed = set(zip(r[enters].tolist(), c[enters].tolist(), strict=True))
    touched = set(zip(r[meets].tolist(), c[meets].tolist(), strict=True))
    assert crossed <= visited
    assert visited <= touched


def test_long_beams_from_far_away_are_clipped_to_the_map() -> None:
    # A sensor 500 km away with a 1000 km range: only the part inside is walked.
    grid = OccupancyGrid.empty(width=2.0, height=1.0, resolution=0.1)
    far = Pose2D(-5e5, 0.55, 0.0)
    n = grid.integrate_scan(
        LaserScan(
            [math.inf, 5e5 + 1.05],
            angle_min=0.0,
            angle_increment=1e-12,
            range_min=0.1,
            range_max=1e6,
        ),
        far,
    )
    assert n == grid.shape[1]
    row = grid.logodds[5]
    assert np.all(row[:10] < 0) and row[10] > 0 and np.all(row[11:] < 0)
    assert np.count_nonzero(grid.logodds) == grid.shape[1]


# ------------------------------------------------------------ issue 12: bad input
def test_integrate_flags_and_ranges() -> None:
    grid = OccupancyGrid.empty(width=3.0, height=3.0, resolution=0.1)
    scan = LaserScan([1.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=2.0)
    before = grid.logodds.copy()
    for flag in ("no", 1, None, np.array([False])):
        with pytest.raises(TypeError, match="exact must be a bool"):
            integrate_scan(grid, scan, (1, 1, 0), exact=flag)  # type: ignore[arg-type]
    for kwargs, match in [
        ({"hit": 1e308}, r"hit must be >= 0 and <= 1e6"),
        ({"miss": -1e308}, r"miss must be >= -1e6 and <= 0"),
        ({"clamp": (-1e308, 1.0)}, r"clamp\[0\] must be >= -1e6 and <= 1e6"),
        ({"clamp": (0.0, 1e7)}, r"clamp\[1\] must be >= -1e6 and <= 1e6"),
        ({"clamp": 3.0}, r"clamp must be a \(low, high\) pair"),
        ({"hit": True}, "hit must be a real number"),
        ({"range_max": "2"}, "range_max must be a real number"),
    ]:
        with pytest.raises((TypeError, ValueError), match=match):
            integrate_scan(grid, scan, (1, 1, 0), **kwargs)  # type: ignore[arg-type]
    assert np.array_equal(grid.logodds, before)
    assert integrate_scan(grid, scan, (1, 1, 0), exact=np.True_) > 0


def test_extreme_log_odds_stay_finite_and_the_grid_usable() -> None:
    grid = OccupancyGrid.empty(width=2.0, height=0.5, resolution=0.5)
    scan = LaserScan([1.4], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=3.0)
    for _ in range(3):
        grid.integrate_scan(scan, (0.25, 0.25, 0.0), hit=1e6, miss=-1e6, clamp=(-1e6, 1e6))
    assert np.all(np.isfinite(grid.logodds)) and grid.logodds.max() == 1e6
    assert np.all(np.isfinite(grid.probability()))
    assert grid.copy().occupied().sum() == 1  # a copy re-validates the log-odds


@pytest.mark.parametrize(
    "pose",
    [
        (1e300, 1e300, 0.0),
        (-1.7e308, 1.7e308, 0.0),
        (1.7e308, -1.7e308, math.pi / 2),
        (1e18, 0.5, math.pi),  # far away, pointing at the map
    ],
)
def test_sensor_far_away_updates_nothing(pose: tuple[float, float, float]) -> None:
    grid = OccupancyGrid.empty(width=2.0, height=1.0, resolution=0.1, origin=(1e9, -1e9, 0.3))
    scan = LaserScan(
        [1e8, math.inf, 5.0], angle_min=-1.0, angle_increment=1.0, range_min=0.1, range_max=1e9
    )
    for exact in (False, True):
        assert integrate_scan(grid, scan, pose, exact=exact) == 0
    assert not grid.logodds.any()


@settings(max_examples=60, deadline=None)
@given(
    st.floats(allow_nan=False, allow_infinity=False),
    st.floats(allow_nan=False, allow_infinity=False),
    st.floats(-10.0, 10.0),
    st.floats(1e-6, 1e6),
    st.floats(1e-3, 1e9),
)
def test_any_finite_pose_and_range_keeps_the_grid_finite(
    x: float, y: float, theta: float, res: float, range_max: float
) -> None:
    grid = OccupancyGrid.empty(
        width=30 * res, height=20 * res, resolution=res, origin=(-3e3, 2e3, 0.2)
    )
    scan = LaserScan(
        np.array([0.5, 0.999, 2.0, math.inf]) * range_max,
        angle_min=-math.pi,
        angle_increment=math.pi / 2,
        range_min=0.0,
        range_max=range_max,
    )
    n = integrate_scan(grid, scan, (x, y, theta), exact=bool(int(res * 1e6) % 2))
    assert 0 <= n <= grid.shape[0] * grid.shape[1]
    assert np.all(np.isfinite(grid.logodds))
