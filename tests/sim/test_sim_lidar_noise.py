"""LiDAR noise: band statistics over 10^5 readings (within 5 %), jitter, dropouts, REP 117."""

from __future__ import annotations

import math

import numpy as np
import pytest
from shapely.geometry import LineString, box

from navkit.geometry import Pose2D
from navkit.sim import Circle, Lidar, RangeNoise, World

N_BEAMS = 1000
N_SCANS = 100  # 10^5 readings


def relative_errors(noise: RangeNoise, radius: float, seed: int = 0) -> np.ndarray:
    """Relative errors of 10^5 readings from the centre of a circular room (all ranges = radius)."""
    world = World(Circle((0.0, 0.0), radius, solid=False))
    lidar = Lidar(n_beams=N_BEAMS, noise=noise, range_max=40.0)
    rng = np.random.default_rng(seed)
    ranges = np.concatenate(
        [lidar.scan(world, (0.0, 0.0, 0.0), seed=rng).ranges for _ in range(N_SCANS)]
    )
    assert ranges.shape == (N_BEAMS * N_SCANS,)
    assert np.all(np.isfinite(ranges))
    return ranges / radius - 1.0


def check_band(errors: np.ndarray, bias: float, sigma: float) -> None:
    """Mean and spread within 5 % of the configured band."""
    assert abs(errors.std() / sigma - 1.0) <= 0.05
    if bias == 0.0:
        assert abs(errors.mean()) <= 0.05 * sigma
    else:
        assert abs(errors.mean() / bias - 1.0) <= 0.05


@pytest.mark.parametrize(("radius", "sigma"), [(1.5, 0.0223), (6.0, 0.0538)])
def test_default_bands_are_the_papers(radius: float, sigma: float) -> None:
    """Short range (below 3 m): 2.23 %; long range: 5.38 % (relative standard deviation)."""
    assert Lidar().noise == RangeNoise()
    check_band(relative_errors(RangeNoise(), radius), 0.0, sigma)


@pytest.mark.parametrize(("radius", "bias", "sigma"), [(0.8, 0.01, 0.01), (2.5, -0.02, 0.03),
                                                       (8.0, 0.015, 0.05)])  # fmt: skip
def test_configured_bands(radius: float, bias: float, sigma: float) -> None:
    noise = RangeNoise(
        limits=(1.0, 4.0, math.inf), sigma=(0.01, 0.03, 0.05), bias=(0.01, -0.02, 0.015)
    )
    check_band(relative_errors(noise, radius, seed=3), bias, sigma)


def test_dropouts_read_nan() -> None:
    world = World(Circle((0.0, 0.0), 2.0, solid=False))
    lidar = Lidar(n_beams=N_BEAMS, noise=None, dropout=0.1)
    rng = np.random.default_rng(1)
    ranges = np.concatenate([lidar.scan(world, (0, 0, 0), seed=rng).ranges for _ in range(N_SCANS)])
    frac = np.isnan(ranges).mean()
    assert abs(frac / 0.1 - 1.0) <= 0.05
    assert np.allclose(ranges[~np.isnan(ranges)], 2.0)


def test_angular_jitter_casts_beams_off_their_nominal_angle() -> None:
    """Against a wall 1 m ahead a beam cast at error d reads 1 / cos d: |d| is half-normal."""
    world = World(LineString([(1.0, -50.0), (1.0, 50.0)]))
    lidar = Lidar(n_beams=1, fov=0.1, noise=None, angle_jitter=0.02)
    rng = np.random.default_rng(2)
    ranges = np.array([lidar.scan(world, (0, 0, 0), seed=rng).ranges[0] for _ in range(20000)])
    delta = np.arccos(1.0 / ranges)
    assert abs(delta.mean() / (0.02 * math.sqrt(2.0 / math.pi)) - 1.0) <= 0.05
    # The scan still reports the nominal angle.
    assert lidar.scan(world, (0, 0, 0), seed=rng).angle_min == 0.0


def test_rep117_readings() -> None:
    """Too close: -inf; nothing in range: +inf; at or beyond range_max: +inf; dropout: NaN."""
    world = World([LineString([(0.1, -1.0), (0.1, 1.0)]), box(-9.0, 3.0, 9.0, 4.0)])
    lidar = Lidar(n_beams=4, noise=None, range_max=5.0)  # beams at -π, -π/2, 0, π/2
    scan = lidar.scan(world, Pose2D(0.0, 0.0, 0.0))
    assert lidar.range_min == 0.15  # the RPLIDAR's minimum
    assert scan.ranges[2] == -math.inf  # the wall 0.1 m ahead is too close
    assert scan.ranges[0] == math.inf and scan.ranges[1] == math.inf  # nothing there
    assert scan.ranges[3] == pytest.approx(3.0)
    far = Lidar(n_beams=4, noise=None, range_max=3.0).scan(world, Pose2D(0.0, 0.0, 0.0))
    assert far.ranges[3] == math.inf  # exactly at range_max: no return
    assert scan.valid_mask().tolist() == [False, False, False, True]
    # Noise that pushes a reading past range_max turns it into "no return".
    noisy = Lidar(n_beams=1, fov=0.1, range_max=3.05,
                  noise=RangeNoise(limits=(math.inf,), sigma=(0.5,)))  # fmt: skip
    rng = np.random.default_rng(0)
    readings = np.array(
        [noisy.scan(world, Pose2D(0, 0, math.pi / 2), seed=rng).ranges[0] for _ in range(200)]
    )
    assert np.all((readings < 3.05) | (readings == math.inf))
    assert np.any(readings == math.inf) and np.any(np.isfinite(readings))


def test_scans_are_reproducible_with_a_seed() -> None:
    world = World(Circle((0.0, 0.0), 3.0, solid=False))
    lidar = Lidar(angle_jitter=0.01, dropout=0.05)
    a = lidar.scan(world, (0.2, 0.1, 0.3), seed=7).ranges
    b = lidar.scan(world, (0.2, 0.1, 0.3), seed=7).ranges
    np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize(
    ("kwargs", "error"),
    [
        ({"limits": (3.0, 2.0, math.inf), "sigma": (0.1, 0.1, 0.1)}, ValueError),
        ({"limits": (3.0, 5.0), "sigma": (0.1, 0.1)}, ValueError),
        ({"limits": (math.inf,), "sigma": (-0.1,)}, ValueError),
        ({"limits": (math.inf,), "sigma": (0.1,), "bias": (0.9,)}, ValueError),
        ({"limits": (3.0, math.inf), "sigma": (0.1,)}, ValueError),
        ({"limits": (), "sigma": ()}, ValueError),
        ({"limits": "3", "sigma": (0.1,)}, TypeError),
        ({"limits": (math.nan, math.inf), "sigma": (0.1, 0.1)}, ValueError),
        # Empty arrays of the wrong dtype or dimension: no element to refuse, but
        # the array itself is not a sequence of numbers (found by the slow fuzz run).
        ({"limits": (math.inf,), "sigma": (0.1,), "bias": np.array([], dtype="<U2")}, TypeError),
        ({"limits": (math.inf,), "sigma": (0.1,), "bias": np.array([], dtype=bool)}, TypeError),
        ({"limits": (math.inf,), "sigma": (0.1,), "bias": np.zeros((0, 1, 3))}, ValueError),
        ({"limits": np.array([[math.inf]]), "sigma": (0.1,)}, ValueError),
    ],
)
def test_bad_noise_bands(kwargs: dict[str, object], error: type[Exception]) -> None:
    with pytest.raises(error):
        RangeNoise(**kwargs)  # type: ignore[arg-type]


def test_bands_as_arrays_equal_bands_as_tuples() -> None:
    as_arrays = RangeNoise(
        limits=np.array([1.0, math.inf]), sigma=np.array([0.01, 0.02]), bias=np.array([0, 0.01])
    )
    assert as_arrays == RangeNoise(limits=(1.0, math.inf), sigma=(0.01, 0.02), bias=(0.0, 0.01))
    assert RangeNoise(limits=(math.inf,), sigma=(0.1,), bias=np.array([])).bias == (0.0,)


@pytest.mark.parametrize(
    ("seed", "message"),
    [(-1, "must be >= 0 as a seed, got -1"), (1 << 128, "must be below 2\\*\\*128 as a seed")],
)
def test_bad_seeds_name_their_argument_once(seed: int, message: str) -> None:
    """The seed's argument is named once: Simulation's ``seed`` read "seed seed must ..."."""
    from navkit.kinematics import DiffDrive
    from navkit.sim import Robot, Simulation

    world = World(Circle((0.0, 0.0), 3.0, solid=False))
    with pytest.raises(ValueError, match=f"^seed {message}"):
        Lidar(dropout=0.1).scan(world, (0.0, 0.0, 0.0), seed=seed)
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2)
    with pytest.raises(ValueError, match=f"^seed {message}"):
        Simulation(world, robot, lambda obs: (0.0, 0.0, 0.0), start=(0, 0, 0), seed=seed)
