"""ScanMapper: synthetic runs with navkit.sim's LiDAR, map files, CARMEN accuracy (reduced)."""

from __future__ import annotations

import copy
import math
import warnings
from pathlib import Path

import numpy as np
import pytest
from shapely import affinity
from shapely.geometry import Polygon, box

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, ScanMapper, ScanMatcher
from navkit.mapping.io import read_carmen, read_map, write_map
from navkit.sim import Lidar, RangeNoise, World

HOKUYO = RangeNoise(limits=(math.inf,), sigma=(0.01,))


def _rel(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Pose b in the frame of pose a."""
    c, s = math.cos(a[2]), math.sin(a[2])
    dx, dy = b[0] - a[0], b[1] - a[1]
    return np.array([c * dx + s * dy, -s * dx + c * dy, math.remainder(b[2] - a[2], math.tau)])


def _compose(a: np.ndarray, d: np.ndarray) -> np.ndarray:
    c, s = math.cos(a[2]), math.sin(a[2])
    return np.array([a[0] + c * d[0] - s * d[1], a[1] + s * d[0] + c * d[1], a[2] + d[2]])


def _noisy_odometry(truth: np.ndarray, sxy: float, sth: float, seed: int) -> np.ndarray:
    """True relative motion plus N(0, sxy) per axis and N(0, sth), chained (the issue's prior)."""
    rng = np.random.default_rng(seed)
    out = [truth[0]]
    for k in range(1, len(truth)):
        step = _rel(truth[k - 1], truth[k]) + rng.normal(0.0, [sxy, sxy, sth])
        out.append(_compose(out[-1], step))
    return np.array(out)


def _pair_errors(est: np.ndarray, truth: np.ndarray) -> np.ndarray:
    return np.array(
        [_rel(_rel(truth[k - 1], truth[k]), _rel(est[k - 1], est[k])) for k in range(1, len(truth))]
    )


def _ate(est: np.ndarray, truth: np.ndarray) -> float:
    a = est[:, :2] - est[:, :2].mean(axis=0)
    b = truth[:, :2] - truth[:, :2].mean(axis=0)
    u, _, vt = np.linalg.svd(a.T @ b)
    d = np.diag([1.0, np.sign(np.linalg.det(vt.T @ u.T))])
    aligned = (vt.T @ d @ u.T @ a.T).T
    return float(np.sqrt(np.mean(np.sum((aligned - b) ** 2, axis=1))))


# ----------------------------------------------------------------- synthetic
def _office() -> World:
    rooms = [box(0, 0, 12, 8).exterior, box(4, 3, 4.5, 8), box(8, 0, 8.5, 5), box(2, 1, 2.6, 1.5)]
    return World(rooms)


def _route() -> np.ndarray:
    t = np.linspace(0.0, 1.0, 60)
    xs = np.interp(t, [0, 0.3, 0.5, 0.7, 1.0], [1.5, 3.2, 6.2, 7.0, 10.5])
    ys = np.interp(t, [0, 0.3, 0.5, 0.7, 1.0], [4.0, 2.0, 1.5, 6.5, 6.0])
    th = np.unwrap(np.arctan2(np.gradient(ys), np.gradient(xs)))
    return np.column_stack((xs, ys, th))


def test_maps_a_synthetic_office_from_noisy_odometry() -> None:
    world = _office()
    truth = _route()
    lidar = Lidar(n_beams=360, range_max=10.0, noise=HOKUYO)
    rng = np.random.default_rng(4)
    scans = [lidar.scan(world, p, seed=rng) for p in truth]
    odometry = _noisy_odometry(truth, 0.05, math.radians(2), seed=1)
    mapper = ScanMapper(pose=truth[0])
    for scan, odom in zip(scans, odometry, strict=True):
        mapper.update(scan, odometry=odom)
    est = np.array(mapper.trajectory)
    assert est.shape == (60, 3) and not mapper.trajectory.flags.writeable
    err = np.hypot(*(est[:, :2] - truth[:, :2]).T)
    assert err.max() < 0.1
    assert np.abs(np.remainder(est[:, 2] - truth[:, 2] + math.pi, math.tau) - math.pi).max() < (
        math.radians(1.5)
    )
    prior_err = _pair_errors(odometry, truth)
    pair = _pair_errors(est, truth)
    assert np.hypot(pair[:, 0], pair[:, 1]).mean() < 0.5 * np.hypot(*prior_err[:, :2].T).mean()
    # The map: the walls' cells are occupied, the route is free.
    grid = mapper.map
    assert grid.resolution == 0.05
    walls = np.vstack([[x, 0.0] for x in np.arange(1, 11, 0.5)] + [[12.0, y] for y in (2, 5)])
    cells = grid.world_to_cell(walls)
    near = [grid.occupied()[r - 1 : r + 2, c - 1 : c + 2].any() for r, c in cells]
    assert np.mean(near) > 0.9
    route = grid.world_to_cell(truth[:, :2])
    assert grid.free()[route[:, 0], route[:, 1]].all()


# ------------------------------------------------- no systematic offset
# A grid-convention mismatch (cell corners against cell centres between the
# ray casting that writes the map and the interpolation the matcher reads)
# would offset every pose by the same half cell whatever the world. What a
# noise-free occupancy grid cannot avoid is the quantisation of the walls: an
# end point is written into the cell holding it, and the matcher pulls it to
# that cell's centre, so a straight wall at a fraction ``f`` of a cell (corner
# coordinates) reads ``(1/2 - f)`` cells off. Axis-aligned walls all at the
# same fraction shift the whole trajectory by that much (+1/2 cell for walls on
# cell boundaries: a simulated world with round coordinates and a map origin
# on the same lattice); averaged over the fraction, or along a slanted wall, it
# is zero.
def _lab(rotation_deg: float, shift: float) -> World:
    shapes = [
        box(0.0, 0.0, 8.0, 6.0).exterior,
        box(2.0, 2.0, 3.0, 2.6),
        Polygon([(5.0, 4.0), (6.2, 4.3), (5.6, 5.0)]),
    ]
    return World(
        [
            affinity.translate(affinity.rotate(g, rotation_deg, origin=(4.0, 3.0)), shift, shift)
            for g in shapes
        ]
    )


def _lab_tour_error(world: World, resolution: float) -> np.ndarray:
    """Noise-free LiDAR, exact odometry: the mapper's mean (x, y) error, in cells."""
    a = np.linspace(0.0, math.tau, 36, endpoint=False)
    truth = np.column_stack(
        (4.0 + 2.2 * np.cos(a), 3.0 + 1.8 * np.sin(a), np.remainder(a + 0.5 * math.pi, math.tau))
    )
    lidar = Lidar(n_beams=360, range_max=10.0, noise=None)
    mapper = ScanMapper(resolution=resolution, pose=truth[0])
    for pose in truth:
        mapper.update(lidar.scan(world, pose), odometry=pose)
    err = np.asarray(mapper.trajectory) - truth
    assert np.abs(np.remainder(err[:, 2] + math.pi, math.tau) - math.pi).max() < math.radians(2.0)
    return np.asarray(err[:, :2].mean(axis=0) / resolution)


@pytest.mark.parametrize("resolution", [0.05, 0.1])
def test_no_systematic_offset_on_noise_free_data(resolution: float) -> None:
    # Slanted walls: every sub-cell position occurs along each wall (measured
    # 0.02-0.07 cells at 5 cm, up to 0.12 at 10 cm from a small heading drift).
    assert np.abs(_lab_tour_error(_lab(17.0, 0.0), resolution)).max() < 0.2
    # Axis-aligned walls at a fraction f of a cell: the error is the
    # quantisation (1/2 - f) cells on both axes, and zero on average over f.
    # f = 0 (walls on cell boundaries) is the reported +1/2 cell; the other
    # four fractions are spread evenly over the cell.
    fractions = [0.0, 0.125, 0.375, 0.625, 0.875]
    errors = np.array([_lab_tour_error(_lab(0.0, f * resolution), resolution) for f in fractions])
    expected = 0.5 - np.array(fractions)
    assert np.abs(errors - expected[:, None]).max() < 0.1
    assert np.abs(errors[1:].mean(axis=0)).max() < 0.1


def test_constant_velocity_without_odometry() -> None:
    world = _office()
    truth = _route()[:25]
    lidar = Lidar(n_beams=360, range_max=10.0, noise=None)
    mapper = ScanMapper(pose=truth[0])
    for p in truth:
        mapper.update(lidar.scan(world, p))
    est = np.array(mapper.trajectory)
    assert np.hypot(*(est[:, :2] - truth[:, :2]).T).max() < 0.05


def test_writes_only_after_moving_and_saves_a_map(tmp_path: Path) -> None:
    world = _office()
    lidar = Lidar(n_beams=360, range_max=10.0, noise=None)
    mapper = ScanMapper(pose=(2.0, 4.0, 0.0), min_distance=0.4, min_angle=0.9)
    scan = lidar.scan(world, (2.0, 4.0, 0.0))
    first = mapper.update(scan)
    assert first.reason == "degenerate" and first.pose == Pose2D(2.0, 4.0, 0.0)
    before = mapper.map.logodds.copy()
    mapper.update(scan, odometry=(0.0, 0.0, 0.0))  # not moved: nothing written
    mapper.update(scan, odometry=(0.0, 0.0, 0.0))
    assert np.array_equal(mapper.map.logodds, before)
    moved = lidar.scan(world, (2.6, 4.0, 0.0))
    mapper.update(moved, odometry=(0.6, 0.0, 0.0))
    assert not np.array_equal(mapper.map.logodds, before)
    # The map is a copy; write_map saves it as a map_server map.
    grid = mapper.map
    image = write_map(grid, tmp_path / "office.yaml")
    assert image.exists() and not (Path.cwd() / "office.yaml").exists()
    back = read_map(tmp_path / "office.yaml")
    assert back.shape == grid.shape and back.resolution == pytest.approx(grid.resolution)
    assert np.array_equal(back.occupied(), grid.occupied())


def test_a_scan_with_nothing_to_write_does_not_count_as_written() -> None:
    # A first scan without valid returns (a sensor starting up) used to count as the
    # first write, so the next scans waited for the robot to move min_distance.
    world = _office()
    lidar = Lidar(n_beams=360, range_max=10.0, noise=None)
    mapper = ScanMapper(pose=(2.0, 4.0, 0.0), min_distance=0.4, min_angle=0.9)
    blank = LaserScan(np.full(360, np.inf), angle_min=-math.pi, angle_increment=math.tau / 360,
                      range_min=0.1, range_max=10.0)  # fmt: skip
    mapper.update(blank)
    assert not mapper.map.occupied().any()
    mapper.update(lidar.scan(world, (2.0, 4.0, 0.0)), odometry=(0.0, 0.0, 0.0))
    assert mapper.map.occupied().any()


def test_map_grows_with_the_route() -> None:
    # A 60 m corridor walked end to end: the map starts ±10 m around the start.
    world = World([box(0, 0, 60, 3).exterior] + [box(x, 0, x + 0.3, 0.6) for x in range(3, 60, 4)])
    lidar = Lidar(n_beams=360, range_max=8.0, noise=None)
    xs = np.arange(1.0, 59.0, 0.5)
    mapper = ScanMapper(resolution=0.1, pose=(1.0, 1.5, 0.0))
    before = mapper.map.shape
    for x in xs:
        mapper.update(lidar.scan(world, (x, 1.5, 0.0)), odometry=(x, 1.5, 0.0))
    grid = mapper.map
    assert grid.width > 60 and grid.shape != before
    est = np.array(mapper.trajectory)
    assert np.abs(est[:, 0] - xs).max() < 0.2 and np.abs(est[:, 1] - 1.5).max() < 0.1
    # Walls far from the start are where they belong.
    cell = grid.world_to_cell([55.0, 3.0])
    assert grid.occupied()[cell[0] - 1 : cell[0] + 2, cell[1]].any()


def test_arguments() -> None:
    with pytest.raises(ValueError, match="hit"):
        ScanMapper(hit=-0.4)
    with pytest.raises(ValueError, match="miss"):
        ScanMapper(miss=0.4)
    with pytest.raises(ValueError, match="resolution"):
        ScanMapper(resolution=0.0)
    with pytest.raises(ValueError, match="min_angle"):
        ScanMapper(min_angle=4.0)
    with pytest.raises(ValueError, match="clamp"):
        ScanMapper(clamp=(1.0, -1.0))
    with pytest.raises(TypeError, match="matcher"):
        ScanMapper(matcher="hector")  # type: ignore[arg-type]
    mapper = ScanMapper(matcher=ScanMatcher(levels=2))
    with pytest.raises(TypeError, match="scan"):
        mapper.update([1.0, 2.0])  # type: ignore[arg-type]
    scan = LaserScan([1.0] * 8, angle_min=0.0, angle_increment=0.5, range_min=0.1, range_max=5)
    with pytest.raises(ValueError, match="odometry"):
        mapper.update(scan, odometry=(math.nan, 0.0, 0.0))
    assert len(mapper) == 0 and mapper.trajectory.shape == (0, 3)
    assert mapper.map.shape == (20, 20)
    mapper.update(
        LaserScan([math.nan] * 8, angle_min=0.0, angle_increment=0.5, range_min=0.1, range_max=5.0)
    )
    assert len(mapper) == 1 and "<1 scan>" in repr(mapper)


def test_odometry_after_a_scan_without_it_is_not_counted_twice() -> None:
    # Scans with no valid return keep the guess, so the trajectory is the guesses.
    blank = LaserScan(
        [math.nan] * 8, angle_min=0.0, angle_increment=0.5, range_min=0.1, range_max=5.0
    )
    mapper = ScanMapper()
    mapper.update(blank, odometry=(0.0, 0.0, 0.0))
    mapper.update(blank, odometry=(1.0, 0.0, 0.0))
    mapper.update(blank)  # no odometry: the previous motion, 1 m, is repeated
    # The odometry moved 1 m since the previous scan (2 m since the last odometry):
    # the increment across two scans must not be added to the repeated motion.
    mapper.update(blank, odometry=(3.0, 0.0, 0.0))
    mapper.update(blank, odometry=(4.0, 0.0, 0.5))
    np.testing.assert_allclose(
        mapper.trajectory,
        [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0], [4, 0, 0.5]],
        atol=1e-12,
    )


def _ring_scan() -> LaserScan:
    """90 returns at 1 m all around."""
    return LaserScan([1.0] * 90, angle_min=-math.pi, angle_increment=2 * math.pi / 90,
                     range_min=0.1, range_max=5.0)  # fmt: skip


def test_first_map_fits_the_cell_limit(monkeypatch: pytest.MonkeyPatch) -> None:
    # At the finest documented resolutions (1e-3 m) ±10 m would be 4e8 cells of
    # the 2**28 allowed; a smaller limit shows the cap at everyday sizes.
    import navkit.mapping._scan_mapper as scan_mapper

    limit = 2**16
    monkeypatch.setattr(scan_mapper, "MAX_CELLS", limit)
    mapper = ScanMapper(resolution=0.05)  # ±10 m would be 400 x 400 cells
    scan = _ring_scan()
    mapper.update(scan, odometry=(0.0, 0.0, 0.0))
    grid = mapper.map
    assert grid.shape == (256, 256) and grid.contains([[-1.5, -1.5], [1.5, 1.5]]).all()
    # No level count whose smallest map (2 x 2 coarsest cells) cannot fit.
    ScanMapper(matcher=ScanMatcher(levels=14))
    with pytest.raises(ValueError, match=r"matcher\.levels=15 .* would need 1\.07e\+09 cells"):
        ScanMapper(matcher=ScanMatcher(levels=15))


def test_a_pose_far_off_the_map_keeps_the_map_without_warnings() -> None:
    scan = _ring_scan()
    mapper = ScanMapper()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow warning on the way to "too big"
        mapper.update(scan, odometry=(0.0, 0.0, 0.0))
        shape = mapper.map.shape
        result = mapper.update(scan, odometry=(1e300, -1e300, 0.0))
    assert result.reason == "guess outside the map" and result.pose.x == 1e300
    assert result.pose.y == -1e300
    assert mapper.map.shape == shape


# -------------------------------------------------------------------- CARMEN
def test_intel_first_100_scans_beat_the_prior_and_kiss_icp(shared_data: Path) -> None:
    log = read_carmen(shared_data / "carmen-logs" / "intel-corrected.log.gz")
    n = 100
    truth = np.array([[p.x, p.y, p.theta] for p in log.laser_poses[:n]])
    odometry = _noisy_odometry(truth, 0.05, math.radians(2.0), seed=0)
    mapper = ScanMapper()
    for scan, odom in zip(log.scans[:n], odometry, strict=True):
        mapper.update(scan, odometry=odom)
    est = np.array(mapper.trajectory)
    pair = _pair_errors(est, truth)
    trans = np.hypot(pair[:, 0], pair[:, 1])
    rot = np.degrees(np.abs(pair[:, 2]))
    prior = _pair_errors(odometry, truth)
    # No gross failure; better than the prior and than the KISS-ICP
    # figures on the whole log (0.045 m, 1.04°).
    assert trans.max() < 0.5 and rot.max() < 10.0
    assert trans.mean() < 0.045 and rot.mean() < 1.04
    assert rot.mean() < 0.5 * np.degrees(np.abs(prior[:, 2])).mean()
    assert _ate(est, truth) < 0.5 * _ate(odometry, truth)


#: The CARMEN harness's matcher (benchmarks/carmen_navkit.py): a heading pull of
#: 3.5/rad towards its 2° motion prior.
HARNESS_MATCHER = {
    "translation_weight": 1.0,
    "rotation_weight": 3.5,
    "search_distance": 0.1,
    "search_angle": 0.1,
}


@pytest.mark.parametrize(("first", "stop"), [(0, 60), (350, 410)])
def test_csail_in_place_turns_without_gross_failure(
    shared_data: Path, first: int, stop: int
) -> None:
    # Between scans 41-43 and 363-400 the corrected csail log turns 10-20° in
    # place between keyframes; with the default 1/rad pull the matcher follows
    # the scans into > 10° disagreements with the corrected poses there.
    log = read_carmen(shared_data / "carmen-logs" / "csail-corrected.log.gz")
    truth = np.array([[p.x, p.y, p.theta] for p in log.laser_poses[first:stop]])
    for seed in (0, 1, 2):
        odometry = _noisy_odometry(truth, 0.05, math.radians(2.0), seed=seed)
        mapper = ScanMapper(matcher=ScanMatcher(**HARNESS_MATCHER))
        for scan, odom in zip(log.scans[first:stop], odometry, strict=True):
            mapper.update(scan, odometry=odom)
        pair = _pair_errors(np.array(mapper.trajectory), truth)
        prior = _pair_errors(odometry, truth)
        trans, rot = np.hypot(pair[:, 0], pair[:, 1]), np.degrees(np.abs(pair[:, 2]))
        assert trans.max() < 0.5 and rot.max() < 10.0, (seed, trans.max(), rot.max())
        assert trans.mean() < np.hypot(prior[:, 0], prior[:, 1]).mean()
        assert rot.mean() < np.degrees(np.abs(prior[:, 2])).mean()


def test_a_shallow_copy_is_independent() -> None:
    # update() appends to the trajectory and writes into the map levels in place:
    # copy.copy shared them, so updating the copy changed the original.
    world = _office()
    lidar = Lidar(n_beams=360, range_max=10.0, noise=None)
    mapper = ScanMapper(pose=(2.0, 4.0, 0.0))
    mapper.update(lidar.scan(world, (2.0, 4.0, 0.0)), odometry=(2.0, 4.0, 0.0))
    before_map = mapper.map.logodds.copy()
    before_path = mapper.trajectory.copy()
    twin = copy.copy(mapper)
    for x in (2.5, 3.0):
        twin.update(lidar.scan(world, (x, 4.0, 0.0)), odometry=(x, 4.0, 0.0))
    assert len(twin) == 3 and len(mapper) == 1
    assert np.array_equal(mapper.trajectory, before_path)
    assert np.array_equal(mapper.map.logodds, before_map)
    assert not np.array_equal(twin.map.logodds[: before_map.shape[0], : before_map.shape[1]],
                              before_map)  # fmt: skip


def test_start_is_checked_and_the_map_stays_within_the_origin_range() -> None:
    # A start beyond ±1e9 m was taken and failed at the first update with a message
    # about a grid "origin"; one near -1e9 m (in range) failed the same way, as did
    # growing the map past -1e9 m.
    with pytest.raises(ValueError, match=r"^pose\b"):
        ScanMapper(pose=(2e9, 0.0, 0.0))
    scan = LaserScan(np.full(3, 3.0), angle_min=-1.0, angle_increment=1.0,
                     range_min=0.1, range_max=5.0)  # fmt: skip
    for start in ((-1e9, -1e9, 0.0), (-1e9 + 30.0, -1e9 + 30.0, 0.0)):
        mapper = ScanMapper(pose=start, resolution=0.5)
        assert mapper.map.origin.x >= -1e9 and mapper.map.origin.y >= -1e9
        for step in (0.0, -10.0, -20.0, -30.0, -40.0):
            mapper.update(scan, odometry=(step, step, 0.0))
        grid = mapper.map
        assert len(mapper) == 5 and grid.origin.x >= -1e9 and grid.origin.y >= -1e9
        assert grid.occupied().any()
