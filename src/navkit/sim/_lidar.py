"""A simulated planar LiDAR returning :class:`navkit.mapping.LaserScan` readings."""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.deprecation import renamed_keyword
from navkit._shared.frozen import frozen_setattr
from navkit._shared.types import FloatArray
from navkit._shared.validation import bounded_int, finite_float, is_ndarray, positive_float
from navkit.geometry import Pose2D, as_pose, wrap_angle
from navkit.mapping import LaserScan
from navkit.sim._lidar_kernels import apply_range_noise
from navkit.sim._noise import RangeNoise
from navkit.sim._world import MAX_COORD, World, as_query_pose, as_world

__all__ = ["Lidar", "Scanner", "as_generator", "check_latency", "check_rate"]

#: Most beams of one scan.
MAX_BEAMS = 100_000
#: Fastest sensor or loop rate, Hz.
MAX_RATE = 10_000.0
#: Longest latency, s.
MAX_LATENCY = 1e4
_TWO_PI = 2.0 * math.pi
_PAPER_NOISE = RangeNoise()
_IDENTITY = Pose2D(0.0, 0.0, 0.0)


def check_rate(value: object, name: str = "rate") -> float:
    """A rate in Hz in (0, 10^4]."""
    rate = positive_float(value, name)
    if rate > MAX_RATE:
        raise ValueError(f"{name} must be at most {MAX_RATE:g} Hz, got {rate}")
    return rate


def check_latency(value: object, name: str = "latency") -> float:
    """A delivery delay in s in [0, 10^4]."""
    latency = positive_float(value, name, allow_zero=True)
    if latency > MAX_LATENCY:
        raise ValueError(f"{name} must be at most {MAX_LATENCY:g} s, got {latency}")
    return latency


def as_generator(value: object, name: str = "rng") -> np.random.Generator:
    """A NumPy Generator from a Generator, an int seed or None (fresh entropy)."""
    if isinstance(value, np.random.Generator):
        return value
    if value is None:
        return np.random.default_rng()
    if is_ndarray(value) and value.ndim == 0 and value.dtype.kind in "iu":
        value = bounded_int(value, name)  # np.array(3): its integer (a masked one refused)
    if isinstance(value, bool):
        raise TypeError(f"{name} must be a numpy Generator, an int seed or None, got bool")
    if isinstance(value, numbers.Integral):
        # "as a seed": ``name`` may itself be "seed" (Simulation's argument).
        if int(value) < 0:
            raise ValueError(f"{name} must be >= 0 as a seed, got {value}")
        if int(value) >= 1 << 128:
            raise ValueError(f"{name} must be below 2**128 as a seed, got {value}")
        return np.random.default_rng(int(value))
    raise TypeError(
        f"{name} must be a numpy Generator, an int seed or None, got {type(value).__name__}"
    )


@frozen_setattr
@dataclass(frozen=True, slots=True, kw_only=True)
class Lidar:
    """A planar scanning LiDAR: geometry, noise, rate and latency.

    Beams are evenly spaced over the field of view. A full circle
    (``fov = 2π``) has ``n_beams`` beams from -π at ``2π / n_beams`` apart (no
    beam repeated at +π); a narrower field has its first and last beams on its
    edges, ``fov / (n_beams - 1)`` apart, centred on the sensor's x axis. Each
    beam measures the exact distance to the first obstacle (see
    :meth:`World.raycast`), then, in this order: a dropout (probability
    ``dropout``) reads NaN; range noise by band (:class:`RangeNoise`) is
    applied; a reading below ``range_min`` reads ``-inf`` and one at or beyond
    ``range_max`` (or no obstacle in range) reads ``+inf``, as ROS REP 117
    asks. The noise moves only what a beam found: an obstacle at or beyond
    ``range_max`` reads ``+inf`` whatever the noise, while one just inside
    reads ``+inf`` when its noise carries it out, so that near ``range_max``
    the finite readings are biased short (a truncated sample of the noise;
    ``range_min`` has no such edge: a range just below it may read above
    it). With ``angle_jitter`` each beam is cast off its nominal angle by a
    zero-mean Gaussian error but reported at the nominal angle, as a real
    scanner does. A sensor inside an obstacle (a blocked cell of the world's
    grid, a solid polygon or :class:`Circle`, a moving obstacle) or on its
    boundary measures 0 on every beam: it reads ``-inf`` (too close) when
    ``range_min > 0``, 0 otherwise (NaN on dropped beams). Walls and polygon
    edges are met to within 1e-9 m, against the rounding of a beam's
    direction: an end of one that close to a beam's line is on the line (a
    beam grazing it stops there), and a beam crossing one that close to the
    sensor, ahead or behind, reads 0 (a sensor on it, to rounding).

    Every parameter is keyword-only; defaults describe an RPLIDAR A1 (0.15 to
    12 m, 360 beams, 10 Hz) with the omnidirectional robot paper's range
    noise.

    A LiDAR is immutable: threads may share it, and share the world they
    scan (:meth:`scan` writes only new arrays), each with its own ``seed``
    (a NumPy Generator is not thread-safe; an int seed is).

    Parameters
    ----------
    n_beams : int, default 360
        Beams per scan, 1 to 100,000.
    fov : float, default 2π
        Field of view, rad, in (0, 2π].
    range_min : float, default 0.15
        Shortest valid reading, m, >= 0.
    range_max : float, default 12.0
        Readings at or beyond it are "no return", m, in (range_min, 1e6].
    noise : RangeNoise or None, default RangeNoise()
        Range noise by band; None for exact ranges.
    angle_jitter : float, default 0.0
        Standard deviation of each beam's direction error, rad, in [0, π].
    dropout : float, default 0.0
        Probability that a beam returns nothing (NaN), in [0, 1].
    rate : float, default 10.0
        Scans per second in a :class:`Simulation`, Hz, in (0, 10^4].
    latency : float, default 0.0
        Delay between taking a scan and delivering it, s, in [0, 10^4] (the
        omnidirectional paper measured 0.50 s for its LiDAR topic).
    mount : Pose2D or array_like [x, y, theta], default (0, 0, 0)
        Pose of the sensor in the robot frame. Scans are in the sensor frame:
        pass this ``mount`` to what takes a scan in the robot frame
        (:func:`~navkit.planning.repulsive_force_from_scan`,
        :meth:`~navkit.control.PotentialFieldController.step`);
        ``scan.to_points(pose @ mount)`` gives its world points.

    Raises
    ------
    TypeError
        A parameter of the wrong type (``n_beams`` not an integer, ``noise``
        not a :class:`RangeNoise` or None, ...).
    ValueError
        A parameter outside its range, NaN or inf.

    Examples
    --------
    >>> from shapely.geometry import box
    >>> world = World(box(0.0, 0.0, 4.0, 3.0).exterior)
    >>> lidar = Lidar(n_beams=4, noise=None)
    >>> lidar.angles().round(4).tolist()
    [3.1416, -1.5708, 0.0, 1.5708]
    >>> scan = lidar.scan(world, (1.0, 1.0, 0.0))
    >>> scan.ranges.round(12).tolist()
    [1.0, 1.0, 3.0, 2.0]
    >>> Lidar(n_beams=3, fov=math.pi, range_min=0.5, noise=None).scan(
    ...     world, (0.2, 1.5, 0.0)).ranges.round(12).tolist()
    [1.5, 3.8, 1.5]
    """

    n_beams: int = 360
    fov: float = _TWO_PI
    range_min: float = 0.15
    range_max: float = 12.0
    noise: RangeNoise | None = _PAPER_NOISE
    angle_jitter: float = 0.0
    dropout: float = 0.0
    rate: float = 10.0
    latency: float = 0.0
    mount: Pose2D = _IDENTITY

    if TYPE_CHECKING:
        # The generated ``__init__`` takes ``mount`` as ``(x, y, theta)`` too
        # (``__post_init__`` converts it); this signature tells type checkers so.
        def __init__(
            self,
            *,
            n_beams: int = ...,
            fov: float = ...,
            range_min: float = ...,
            range_max: float = ...,
            noise: RangeNoise | None = ...,
            angle_jitter: float = ...,
            dropout: float = ...,
            rate: float = ...,
            latency: float = ...,
            mount: Pose2D | ArrayLike = ...,
        ) -> None: ...

    def __post_init__(self) -> None:
        object.__setattr__(self, "n_beams", bounded_int(self.n_beams, "n_beams", 1, MAX_BEAMS))
        fov = positive_float(self.fov, "fov")
        if fov > _TWO_PI + 1e-12:
            # A field of view does not wrap: up to two turns it may be radians meant
            # as all round (review 46: 7.0 was only asked "degrees?").
            hints = ["radians? a full turn, 2π, is the widest: pass 2 * math.pi"] if (
                fov <= 2.0 * _TWO_PI) else []  # fmt: skip
            if fov <= 360.0:
                hints.append(f"degrees? pass math.radians({fov:g})")
            hint = f" ({'; or '.join(hints)})" if hints else ""
            raise ValueError(f"fov must lie in (0, 2π] rad, got {fov}{hint}")
        object.__setattr__(self, "fov", min(fov, _TWO_PI))
        rmin = positive_float(self.range_min, "range_min", allow_zero=True)
        rmax = positive_float(self.range_max, "range_max")
        if rmax > MAX_COORD:
            raise ValueError(f"range_max must be at most {MAX_COORD:g} m, got {rmax}")
        if rmin >= rmax:
            raise ValueError(f"range_min ({rmin}) must be smaller than range_max ({rmax})")
        object.__setattr__(self, "range_min", rmin)
        object.__setattr__(self, "range_max", rmax)
        if self.noise is not None and not isinstance(self.noise, RangeNoise):
            raise TypeError(f"noise must be a RangeNoise or None, got {type(self.noise).__name__}")
        jitter = positive_float(self.angle_jitter, "angle_jitter", allow_zero=True)
        if jitter > math.pi:
            raise ValueError(f"angle_jitter must lie in [0, π] rad, got {jitter}")
        object.__setattr__(self, "angle_jitter", jitter)
        drop = finite_float(self.dropout, "dropout")
        if not 0.0 <= drop <= 1.0:
            raise ValueError(f"dropout must lie in [0, 1], got {drop}")
        object.__setattr__(self, "dropout", drop)
        object.__setattr__(self, "rate", check_rate(self.rate))
        object.__setattr__(self, "latency", check_latency(self.latency))
        object.__setattr__(self, "mount", as_pose(self.mount, "mount"))

    @property
    def full_circle(self) -> bool:
        """Whether the field of view is a whole turn."""
        return self.fov >= _TWO_PI

    @property
    def angle_min(self) -> float:
        """Angle of the first beam in the sensor frame, rad."""
        if self.full_circle:
            return -math.pi
        return 0.0 if self.n_beams == 1 else -0.5 * self.fov

    @property
    def angle_increment(self) -> float:
        """Angle between consecutive beams, rad (``fov`` for a single beam)."""
        if self.full_circle:
            return _TWO_PI / self.n_beams
        return self.fov if self.n_beams == 1 else self.fov / (self.n_beams - 1)

    def angles(self) -> FloatArray:
        """Nominal beam angles in the sensor frame, rad, shape (n_beams,).

        Returns
        -------
        ndarray, shape (n_beams,)
            New array ``angle_min + k * angle_increment`` wrapped to (-π, π],
            the angles :meth:`LaserScan.angles` gives of the scans' beams (a
            full circle's first beam, at ``angle_min = -π``, is +π).

        Examples
        --------
        >>> Lidar(n_beams=5, fov=math.pi / 2).angles().round(4).tolist()  # edges at ±fov/2
        [-0.7854, -0.3927, 0.0, 0.3927, 0.7854]
        >>> Lidar(n_beams=4).angles().round(4).tolist()  # a full circle: backwards is +π
        [3.1416, -1.5708, 0.0, 1.5708]
        """
        return np.asarray(wrap_angle(self._raw_angles()), dtype=np.float64)

    def _raw_angles(self) -> FloatArray:
        """``angle_min + k * angle_increment``, not wrapped: the directions the kernels cast."""
        return self.angle_min + self.angle_increment * np.arange(self.n_beams, dtype=np.float64)

    def scan(
        self,
        world: World,
        pose: Pose2D | ArrayLike,
        *,
        t: float = 0.0,
        seed: np.random.Generator | int | None = None,
        rng: np.random.Generator | int | None = None,
    ) -> LaserScan:
        """One scan of ``world`` from a robot at ``pose``.

        Parameters
        ----------
        world : World
            What the beams hit.
        pose : Pose2D or array_like [x, y, theta]
            Pose of the robot, its position within ±1e12 m (as
            :meth:`World.raycast` and a :class:`Simulation`'s start); the
            sensor sits at ``pose ⊕ mount``.
        t : float, default 0.0
            Time of the scan (places the moving obstacles), s, within ±1e9 s
            when the world has moving obstacles.
        seed : int, numpy Generator or None, optional
            Randomness for noise, jitter and dropouts (unused without them).
            Default None: fresh draws at every call, unlike
            ``Simulation(seed=)``'s default 0 (a simulation keeps one
            generator for its whole run, so its 0 gives a repeatable sequence;
            a per-call 0 would repeat one scan's noise in every scan of a
            loop). An int repeats one scan's draws; a Generator passed to
            every call gives a repeatable sequence of scans.

        Other Parameters
        ----------------
        rng : int, numpy Generator or None, optional
            Deprecated name of `seed`.

        Returns
        -------
        LaserScan
            Ranges per REP 117, m, shape (n_beams,) (NaN for a dropout,
            ``-inf`` below ``range_min``, ``+inf`` for no return); angles in
            the sensor frame, rad (those of :meth:`angles`).

        Raises
        ------
        TypeError, ValueError
            ``pose`` not a pose, or its position beyond ±1e12 m; ``t`` not
            a finite time within range.

        Examples
        --------
        >>> from shapely.geometry import box
        >>> from navkit.sim import MovingObstacle
        >>> room = box(0.0, 0.0, 4.0, 3.0).exterior
        >>> lidar = Lidar(n_beams=4, range_max=2.5, noise=None)  # back, right, ahead, left
        >>> lidar.scan(World(room), (1.0, 1.0, 0.0)).ranges.tolist()  # wall ahead at 3 m
        [1.0, 1.0, inf, 2.0]
        >>> lidar.scan(World(room), (1.0, 1.0, math.pi / 2)).ranges.round(12).tolist()
        [1.0, inf, 2.0, 1.0]
        >>> ball = MovingObstacle.constant_velocity(0.25, start_xy=(3, 1), velocity_xy=(-0.5, 0))
        >>> world = World(room, moving=[ball])
        >>> [float(lidar.scan(world, (1.0, 1.0, 0.0), t=t).ranges[2]) for t in (0.0, 2.0)]
        [1.75, 0.75]
        >>> noisy = Lidar(n_beams=4)  # the paper's range noise: 2.23 % below 3 m
        >>> a = noisy.scan(world, (1.0, 1.0, 0.0), seed=7)
        >>> b = noisy.scan(world, (1.0, 1.0, 0.0), seed=7)  # the same seed, the same draws
        >>> np.array_equal(a.ranges, b.ranges), bool(abs(a.ranges[0] - 1.0) < 0.1)
        (True, True)
        """
        w = as_world(world)
        scanner = w._scanners.get(self)
        if scanner is None:
            if len(w._scanners) >= 16:
                w._scanners.clear()
            scanner = w._scanners[self] = Scanner(self, w)
        p = as_query_pose(pose, "pose")
        time = w._query_time(t)
        seed_name = "seed"
        if rng is not None:  # the old name of seed (Simulation's word); errors name it
            seed, seed_name = renamed_keyword("rng", rng, "seed", seed, None), "rng"
        generator = as_generator(seed, seed_name) if scanner.random or seed is not None else None
        return scanner.scan(p, time, generator)


class Scanner:
    """A LiDAR bound to a world, with its work arrays: the simulation's fast path.

    An ordinary class with ``__slots__``. A world keeps one per LiDAR for
    :meth:`Lidar.scan`, which threads may call at once: a scan writes only
    arrays of its own, never the scanner's.
    """

    __slots__ = (
        "_absolute",
        "_angles",
        "_bias",
        "_lidar",
        "_limits",
        "_noisy",
        "_normals",
        "_sigma",
        "_uniforms",
        "_world",
        "random",
    )

    def __init__(self, lidar: Lidar, world: World) -> None:
        self._lidar = lidar
        self._world = world
        n = lidar.n_beams
        self._angles = np.ascontiguousarray(lidar._raw_angles())
        self._normals = np.zeros(n)
        self._uniforms = np.ones(n)
        noise = lidar.noise
        self._noisy = noise is not None and any(
            s > 0.0 or b != 0.0 or a > 0.0
            for s, b, a in zip(noise.sigma, noise.bias, noise.absolute, strict=True)
        )
        if noise is None:
            noise = RangeNoise(limits=(math.inf,), sigma=(0.0,))
        self._limits, self._bias, self._sigma = noise.arrays()
        self._absolute = np.array(noise.absolute, dtype=np.float64)
        self.random = self._noisy or lidar.angle_jitter > 0.0 or lidar.dropout > 0.0
        """Whether a scan draws random numbers."""

    def scan(self, pose: Pose2D, t: float, rng: np.random.Generator | None) -> LaserScan:
        """One scan from the robot at ``pose`` (validated) at time ``t``.

        ``rng`` may be None only when :attr:`random` is false.
        """
        lidar = self._lidar
        m = lidar.mount
        if m.x == 0.0 and m.y == 0.0 and m.theta == 0.0:
            x, y, heading = pose.x, pose.y, pose.theta
        else:
            sensor = pose.compose(m)
            x, y, heading = sensor.x, sensor.y, sensor.theta
        angles = self._angles
        if lidar.angle_jitter > 0.0:
            assert rng is not None
            angles = rng.standard_normal(lidar.n_beams)
            angles *= lidar.angle_jitter
            angles += self._angles
        ranges = np.empty(lidar.n_beams)
        self._world._cast(ranges, x, y, heading, angles, lidar.range_max, t)
        # The draws go to new arrays: the scanner's zeros and ones are only read.
        normals, uniforms = self._normals, self._uniforms
        if self.random:
            assert rng is not None
            if self._noisy:
                normals = rng.standard_normal(lidar.n_beams)
            if lidar.dropout > 0.0:
                uniforms = rng.random(lidar.n_beams)
        apply_range_noise(
            ranges, normals, uniforms, self._limits, self._bias, self._sigma, self._absolute,
            lidar.dropout, lidar.range_min, lidar.range_max,
        )  # fmt: skip
        return LaserScan(
            ranges,
            angle_min=lidar.angle_min,
            angle_increment=lidar.angle_increment,
            range_min=lidar.range_min,
            range_max=lidar.range_max,
        )
