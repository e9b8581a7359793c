"""Metamorphic relations of the simulator: rigid motions, mirrors, truncation, shifts.

Each test runs the same thing twice, in a world and its image under an SE(2)
motion or the mirror ``y -> -y``, and checks the relation the geometry
guarantees, instead of comparing with a reference implementation.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray
from shapely.geometry import LineString, Polygon

from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.mapping import OccupancyGrid
from navkit.sim import (
    Circle,
    Compass,
    CompassReading,
    EncoderReading,
    Imu,
    ImuReading,
    Lidar,
    MovingObstacle,
    Observation,
    RangeNoise,
    Robot,
    ScanReading,
    Simulation,
    Trace,
    WheelEncoders,
    World,
)
from navkit.sim._latency import DelayLine

# Coordinates stay within ~200 m and ranges within 30 m: transformed coordinates
# differ from exact by a few ulp(200) ~ 1e-13 m, and so do the ranges cast through
# them, far below this tolerance.
_TOL = 1e-9


@dataclass(frozen=True)
class _Motion:
    """``p -> R(phi) M p + (tx, ty)``, ``M`` the mirror ``y -> -y`` when ``mirror``."""

    tx: float = 0.0
    ty: float = 0.0
    phi: float = 0.0
    mirror: bool = False

    def point(self, x: float, y: float) -> tuple[float, float]:
        c, s = math.cos(self.phi), math.sin(self.phi)
        if self.mirror:
            y = -y
        return c * x - s * y + self.tx, s * x + c * y + self.ty

    def vector(self, x: float, y: float) -> tuple[float, float]:
        c, s = math.cos(self.phi), math.sin(self.phi)
        if self.mirror:
            y = -y
        return c * x - s * y, s * x + c * y

    def angle(self, theta: float) -> float:
        return (-theta if self.mirror else theta) + self.phi

    def pose(self, x: float, y: float, theta: float) -> tuple[float, float, float]:
        return (*self.point(x, y), self.angle(theta))


_IDENTITY = _Motion()

_motions = st.builds(
    _Motion,
    tx=st.floats(-100.0, 100.0),
    ty=st.floats(-100.0, 100.0),
    phi=st.floats(-math.pi, math.pi),
    mirror=st.booleans(),
)


@dataclass(frozen=True)
class _Scene:
    polygons: list[list[tuple[float, float]]]
    circles: list[tuple[tuple[float, float], float]]
    logodds: NDArray[np.float64]
    grid_origin: tuple[float, float, float]
    moving: list[tuple[Any, list[tuple[float, float]]]]

    def world(self, m: _Motion) -> World:
        """The scene moved by ``m``: every obstacle, the grid's frame and the moving paths."""
        obstacles: list[Any] = [
            LineString([m.point(x, y) for x, y in [(-10, -10), (10, -10), (10, 10), (-10, 10)]])
        ]
        obstacles += [Polygon([m.point(x, y) for x, y in poly]) for poly in self.polygons]
        obstacles += [Circle(np.array(m.point(*c)), r) for c, r in self.circles]
        ox, oy, oth = self.grid_origin
        logodds = self.logodds
        if m.mirror:
            # A mirrored grid has its rows the other way: the mirror of its top edge
            # is the new origin, the rows flipped.
            h = logodds.shape[0] * 0.5
            ox, oy = ox - h * math.sin(oth), oy + h * math.cos(oth)
            logodds = logodds[::-1]
        grid = OccupancyGrid(logodds, resolution=0.5, origin=m.pose(ox, oy, oth))
        moving = [
            MovingObstacle(
                shape if isinstance(shape, float) else [m.vector(*v) for v in shape],
                np.array([m.point(*p) for p in path]),
                np.array([0.0, 1.0, 2.5]),
            )
            for shape, path in self.moving
        ]
        return World(obstacles, grid=grid, moving=moving)


_xy = st.tuples(st.floats(-8.0, 8.0), st.floats(-8.0, 8.0))
_offset = st.tuples(st.floats(-1.5, 1.5), st.floats(-1.5, 1.5))


@st.composite
def _scenes(draw: st.DrawFn) -> _Scene:
    polygons = []
    for _ in range(draw(st.integers(0, 3))):
        cx, cy = draw(_xy)
        pts = [(cx + dx, cy + dy) for dx, dy in draw(st.lists(_offset, min_size=3, max_size=3))]
        poly = Polygon(pts)
        assume(poly.is_valid and poly.area > 1e-3)
        polygons.append(pts)
    circles = draw(st.lists(st.tuples(_xy, st.floats(0.1, 1.0)), max_size=2))
    seed = draw(st.integers(0, 2**32 - 1))
    cells = np.random.default_rng(seed).random((30, 40))
    logodds = np.where(cells < 0.04, 5.0, -5.0)
    corner = st.floats(-12.0, -8.0)
    origin = (draw(corner), draw(corner), draw(st.floats(-0.5, 0.5)))
    moving: list[tuple[Any, list[tuple[float, float]]]] = []
    for _ in range(draw(st.integers(0, 2))):
        vertex = st.tuples(st.floats(-0.5, 0.5), st.floats(-0.5, 0.5))
        shape: Any = draw(st.floats(0.2, 0.6) | st.lists(vertex, min_size=3, max_size=3))
        if not isinstance(shape, float):
            assume(Polygon(shape).is_valid and Polygon(shape).area > 1e-3)
        moving.append((shape, draw(st.lists(_xy, min_size=3, max_size=3))))
    return _Scene(polygons, circles, logodds, origin, moving)


def _well_conditioned(world: World, sensor: Pose2D, angles: NDArray[np.float64], t: float) -> Any:
    """Beams whose range is continuous in the beam angle (not grazing a corner or a tangent).

    Where a beam grazes a vertex or a circle, the range jumps between two surfaces
    within an angle of an ulp: either answer is right, and the rounding of the
    moved scene may pick the other.
    """
    step = 1e-9
    lo = world.raycast(sensor, angles - step, range_max=30.0, t=t)
    hi = world.raycast(sensor, angles + step, range_max=30.0, t=t)
    both_inf = np.isinf(lo) & np.isinf(hi)
    # A smooth change over 2e-9 rad is below 30 m · 2e-9 / cos(incidence): 1e-4 m
    # allows incidences up to ~89.9°.
    gap = np.subtract(hi, lo, out=np.zeros_like(hi), where=~both_inf)
    return both_inf | (np.abs(gap) < 1e-4)


@settings(max_examples=40)
@given(
    scene=_scenes(),
    motion=_motions,
    pose=st.tuples(st.floats(-9.0, 9.0), st.floats(-9.0, 9.0), st.floats(-math.pi, math.pi)),
    t=st.floats(0.0, 3.0),
    full=st.booleans(),
)
def test_lidar_ranges_move_with_the_scene(
    scene: _Scene, motion: _Motion, pose: tuple[float, float, float], t: float, full: bool
) -> None:
    """Move scene and robot together: the same ranges; mirror them: the beams in reverse."""
    mount = (0.1, 0.05, 0.3)
    n = 90 if full else 61
    fov = 2.0 * math.pi if full else math.pi

    def lidar(m: _Motion) -> Lidar:
        # The mount is in the robot frame: a mirror flips it, a rigid motion does not move it.
        mx, my, mth = mount
        return Lidar(n_beams=n, fov=fov, noise=None, range_min=0.0, range_max=30.0,
                     mount=Pose2D(mx, -my, -mth) if m.mirror else Pose2D(*mount))  # fmt: skip

    original = scene.world(_IDENTITY)
    lid = lidar(_IDENTITY)
    ranges = lid.scan(original, pose, t=t).ranges
    moved = lid.scan(scene.world(motion), motion.pose(*pose), t=t).ranges
    if motion.mirror:
        # The same lidar with its mount mirrored; beam k at angle a sees what the
        # original's beam at -a saw: index -k mod n on a full circle (-π is +π),
        # reversed on a field centred on the x axis.
        moved = lidar(motion).scan(scene.world(motion), motion.pose(*pose), t=t).ranges
        moved = moved[(-np.arange(n)) % n] if full else moved[::-1]
    sensor = Pose2D(*pose).compose(mount)
    ok = _well_conditioned(original, sensor, lid.angles(), t)
    assert ok.mean() > 0.5  # the filter leaves most beams to compare
    np.testing.assert_allclose(moved[ok], ranges[ok], rtol=0.0, atol=_TOL)


# ----------------------------------------------------------------------- simulation
class _Wiggle:
    """An open-loop command of the observation time; ``sign`` mirrors its turning."""

    def __init__(self, sign: float, lateral: float) -> None:
        self.sign = sign
        self.lateral = lateral
        self.seen: list[Observation] = []

    def __call__(self, obs: Observation) -> Twist2D:
        self.seen.append(obs)
        t = obs.t
        return Twist2D(
            0.3 + 0.2 * math.sin(t),
            self.sign * self.lateral * math.cos(0.7 * t),
            self.sign * 0.8 * math.cos(1.3 * t),
        )

    def readings(self) -> list[Any]:
        return [r for obs in self.seen for r in obs.new]


def _sim_world(m: _Motion) -> World:
    # A small room the robot keeps hitting (collisions and put-backs are part of
    # the relation), a triangle and a pillar.
    return World([
        LineString([m.point(x, y) for x, y in [(-2, -2), (2.2, -2), (2.2, 2), (-2, 2), (-2, -2)]]),
        Polygon([m.point(x, y) for x, y in [(1.0, 0.1), (1.5, 0.5), (1.2, 0.9)]]),
        Circle(np.array(m.point(0.6, -0.9)), 0.3),
    ])  # fmt: skip


def _simulate(
    m: _Motion, *, noisy: bool, omni: bool = False, duration: float = 6.0, seed: int = 3
) -> tuple[Trace, _Wiggle]:
    drive: Any = (
        OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
        if omni
        else DiffDrive(track=0.3, wheel_radius=0.05)
    )
    robot = Robot(
        drive=drive,
        footprint=0.2,
        max_wheel_acceleration=20.0,
        wheel_slip=0.05 if noisy else 0.0,
        encoders=WheelEncoders(ticks_per_rev=1024, bits=16),
        lidar=Lidar(n_beams=90, noise=RangeNoise() if noisy else None, range_max=20.0),
        compass=Compass(north=m.angle(math.pi / 2), noise=0.01 if noisy else 0.0),
        imu=Imu(gyro_noise=0.01 if noisy else 0.0, accel_noise=0.02 if noisy else 0.0),
    )
    ctrl = _Wiggle(-1.0 if m.mirror else 1.0, 0.2 if omni else 0.0)
    trace = Simulation(
        _sim_world(m), robot, ctrl, start=m.pose(0.0, 0.0, 0.3), duration=duration, seed=seed,
        end_on_collision=False,
    ).run()  # fmt: skip
    return trace, ctrl


def _wrap(a: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.asarray(np.angle(np.exp(1j * a)), dtype=np.float64)


def _check_readings(
    original: list[Any], moved: list[Any], mirror: bool, close: Callable[..., None]
) -> None:
    assert [type(r) for r in moved] == [type(r) for r in original]
    for a, b in zip(original, moved, strict=True):
        assert a.stamp == b.stamp
        if isinstance(a, ScanReading):
            n = a.scan.ranges.shape[0]
            close(b.scan.ranges[(-np.arange(n)) % n] if mirror else b.scan.ranges, a.scan.ranges)
        elif isinstance(a, EncoderReading):
            # Mirrored, a differential drive's wheels swap sides (exact: the same sums).
            np.testing.assert_array_equal(b.ticks[::-1] if mirror else b.ticks, a.ticks)
        elif isinstance(a, CompassReading):
            want = -a.heading_deg if mirror else a.heading_deg
            assert abs((b.heading_deg - want + 180.0) % 360.0 - 180.0) < _TOL
        else:
            assert isinstance(a, ImuReading)
            s = -1.0 if mirror else 1.0
            close(np.array([b.yaw_rate, b.acceleration_x, b.acceleration_y]),
                  np.array([s * a.yaw_rate, a.acceleration_x, s * a.acceleration_y]))  # fmt: skip


def _close(a: Any, b: Any) -> None:
    np.testing.assert_allclose(a, b, rtol=0.0, atol=_TOL)


@settings(max_examples=8)
@given(motion=_motions, omni=st.booleans(), seed=st.integers(0, 2**31))
def test_a_run_moves_with_its_world(motion: _Motion, omni: bool, seed: int) -> None:
    """Start, world and compass north moved together: poses move, readings stay.

    With noise and slip (the same draws, in the same order); mirrored runs are
    noise-free differential drives (noise and slip draws are not mirrored), whose
    wheels swap and whose yaw rate, lateral acceleration and heading change sign.
    """
    if motion.mirror:
        omni = False
    noisy = not motion.mirror
    base, base_ctrl = _simulate(_IDENTITY, noisy=noisy, omni=omni, seed=seed)
    moved, moved_ctrl = _simulate(motion, noisy=noisy, omni=omni, seed=seed)
    assert moved.metrics.collisions == base.metrics.collisions
    np.testing.assert_array_equal(moved.times, base.times)
    x, y = motion.point(base.poses[:, 0], base.poses[:, 1])  # type: ignore[arg-type]
    _close(moved.poses[:, 0], x)
    _close(moved.poses[:, 1], y)
    _close(_wrap(moved.poses[:, 2] - motion.angle(base.poses[:, 2])), 0.0)  # type: ignore[arg-type]
    _check_readings(base_ctrl.readings(), moved_ctrl.readings(), motion.mirror, _close)


@settings(max_examples=6)
@given(short=st.floats(0.5, 5.0), extra=st.floats(0.01, 3.0), seed=st.integers(0, 2**31))
def test_a_shorter_run_is_a_prefix_of_a_longer_one(short: float, extra: float, seed: int) -> None:
    """The same seed: the first steps and readings of a longer run are the shorter run, exactly."""
    a, ca = _simulate(_IDENTITY, noisy=True, duration=short, seed=seed)
    b, cb = _simulate(_IDENTITY, noisy=True, duration=short + extra, seed=seed)
    n = a.times.shape[0]
    assert b.times.shape[0] >= n
    np.testing.assert_array_equal(b.poses[:n], a.poses)
    np.testing.assert_array_equal(b.commands[:n], a.commands)
    first = ca.readings()
    _check_readings(first, cb.readings()[: len(first)], False, np.testing.assert_array_equal)


# -------------------------------------------------------------------- sensors alone
@settings(max_examples=60)
@given(
    tpr=st.integers(1, 100_000).map(float),
    angles=st.lists(st.floats(-1e6, 1e6), min_size=1, max_size=8),
    bits=st.integers(2, 64),
)
def test_encoder_counts_are_odd_about_each_boundary_and_wrap_consistently(
    tpr: float, angles: list[float], bits: int
) -> None:
    """``count(-a) = -count(a)`` on a boundary, ``-count(a) - 1`` between; wrapping is a mask."""
    unwrapped = WheelEncoders(ticks_per_rev=tpr, bits=None)
    a = np.array(angles)
    up = unwrapped.ticks(a)
    down = unwrapped.ticks(-a)
    # (k / tpr) * 2π is odd in k exactly: rounding is symmetric about 0.
    on_boundary = (up / tpr) * (2.0 * math.pi) == a
    np.testing.assert_array_equal(down, np.where(on_boundary, -up, -up - 1))
    wrapped = WheelEncoders(ticks_per_rev=tpr, bits=bits).ticks(a)
    if bits == 64:
        np.testing.assert_array_equal(wrapped, up)
    else:
        # Python ints: 2**63 does not fit an int64.
        assert wrapped.tolist() == [u % (1 << bits) for u in up.tolist()]


@settings(max_examples=60)
@given(
    yaw=st.floats(-100.0, 100.0),
    phi=st.floats(-math.pi, math.pi),
    north=st.floats(-math.pi, math.pi),
    bias=st.floats(-1.0, 1.0),
)
def test_compass_reading_moves_with_north_and_mirrors(
    yaw: float, phi: float, north: float, bias: float
) -> None:
    """Turning robot and north together keeps the heading; mirroring both negates it."""
    base = Compass(north=north, bias=bias).heading_deg(yaw)
    turned = Compass(north=north + phi, bias=bias).heading_deg(yaw + phi)
    mirrored = Compass(north=-north, bias=-bias).heading_deg(-yaw)

    def gap(a: float, b: float) -> float:
        return abs((a - b + 180.0) % 360.0 - 180.0)

    # Angles up to ~100 rad: a few ulp(100) rad is ~1e-12 degrees.
    assert gap(turned, base) < _TOL
    assert gap(mirrored, -base) < _TOL
    assert 0.0 <= base < 360.0


_dyadic = st.integers(0, 4096).map(lambda k: k / 64.0)  # exact sums: no tolerance cases


@settings(max_examples=60)
@given(
    stamps=st.lists(_dyadic, max_size=20).map(sorted),
    delay=_dyadic,
    queries=st.lists(_dyadic, min_size=1, max_size=10).map(sorted),
)
def test_delay_line_is_a_pure_shift_and_reads_the_same_in_chunks(
    stamps: list[float], delay: float, queries: list[float]
) -> None:
    """Delayed by d, read at t: what an undelayed line gives at t - d, however it is read."""
    delayed: DelayLine[int] = DelayLine(delay)
    direct: DelayLine[int] = DelayLine(0.0)
    for k, s in enumerate(stamps):
        delayed.push_at(s + delay, k)  # the due time, as the simulator computes it
        direct.push_at(s, k)
    whole = copy.copy(delayed)
    got: list[tuple[float, int]] = []
    for q in queries:
        chunk = delayed.pop_due(q)
        assert [k for _, k in chunk] == [k for _, k in direct.pop_due(q - delay)]
        got += chunk
    # Reading in chunks == reading once at the last time; the copy was untouched.
    assert got == whole.pop_due(queries[-1])
    assert got == [(s + delay, k) for k, s in enumerate(stamps) if s + delay <= queries[-1]]
