"""Feeding a simulation's sensor readings to a pose estimator."""

from __future__ import annotations

import math
from typing import Any, Protocol, runtime_checkable

import numpy as np

from navkit._shared.products import ordered_dot
from navkit._shared.types import FloatArray
from navkit.estimation import DiffOdometry, OmniOdometry, PlanarFusion
from navkit.geometry import Pose2D, wrap_angle
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.sim._robot import Robot
from navkit.sim._sensors import CompassReading, EncoderReading, ImuReading, Reading

__all__ = ["Estimator", "FusionEstimator", "as_estimator"]

_TWO_PI = 2.0 * math.pi


@runtime_checkable
class Estimator(Protocol):
    """What :class:`Simulation` needs of a pose estimator.

    ``observe(t, reading)`` is called with every reading when it is delivered
    (``t``, s; the reading's own ``stamp`` is when it was taken), in delivery
    order; ``pose`` is the current estimate (None before there is one).
    ``navkit.estimation.PlanarFusion``, ``OmniOdometry`` and ``DiffOdometry``
    instances are wrapped into estimators automatically.

    Examples
    --------
    >>> import math
    >>> from navkit.geometry import Pose2D, Twist2D, wrap_angle
    >>> from navkit.kinematics import DiffDrive
    >>> from navkit.sim import (Compass, CompassReading, Estimator, Observation, Reading,
    ...                         Robot, Simulation, World)
    >>> class CompassHeading:  # an Estimator of the heading only, from the compass
    ...     def __init__(self, north: float) -> None:
    ...         self.north, self.readings = north, 0
    ...         self.pose: Pose2D | None = None
    ...     def observe(self, t: float, reading: Reading) -> None:
    ...         if isinstance(reading, CompassReading):
    ...             self.readings += 1
    ...             yaw = wrap_angle(self.north - math.radians(reading.heading_deg))
    ...             self.pose = Pose2D(0.0, 0.0, yaw)
    >>> estimator = CompassHeading(north=math.pi / 2)
    >>> isinstance(estimator, Estimator)
    True
    >>> robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2,
    ...               compass=Compass(rate=10.0))
    >>> def spin(obs: Observation) -> Twist2D:  # turn on the spot at 1 rad/s
    ...     return Twist2D(0.0, 0.0, 1.0)
    >>> trace = Simulation(World(), robot, spin, start=(0.0, 0.0, 0.0), estimator=estimator,
    ...                    duration=0.5).run()
    >>> assert estimator.pose is not None  # it has seen the compass
    >>> estimator.readings, round(estimator.pose.theta, 6)  # 10 Hz from t = 0 to 0.5 s; rad
    (6, 0.5)
    >>> trace.estimates[-1].round(6).tolist()  # the trace records its pose at every step
    [0.0, 0.0, 0.5]
    """

    def observe(self, t: float, reading: Reading) -> None:
        """Take one delivered reading.

        Parameters
        ----------
        t : float
            Simulated time of delivery, s (at or after ``reading.stamp``, later
            with sensor latency).
        reading : Reading
            A :class:`ScanReading`, :class:`EncoderReading`,
            :class:`CompassReading` or :class:`ImuReading`; its ``stamp`` is
            when it was taken.

        Examples
        --------
        >>> from navkit.geometry import Twist2D
        >>> from navkit.kinematics import DiffDrive
        >>> from navkit.sim import Compass, Reading, Simulation, World
        >>> class Log:  # an Estimator that only notes when each reading came
        ...     pose = None
        ...     def __init__(self) -> None:
        ...         self.seen: list[tuple[str, float, float]] = []
        ...     def observe(self, t: float, reading: Reading) -> None:
        ...         kind = type(reading).__name__
        ...         self.seen.append((kind, round(reading.stamp, 6), round(t, 6)))
        >>> robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2,
        ...               encoders=None, compass=Compass(rate=10.0, latency=0.05))
        >>> log = Log()
        >>> _ = Simulation(World(), robot, lambda obs: Twist2D(0.0, 0.0, 0.0),
        ...                start=(0.0, 0.0, 0.0), estimator=log, duration=0.3).run()
        >>> log.seen  # (kind, taken at, delivered at), s: the compass's 0.05 s latency
        [('CompassReading', 0.0, 0.05), ('CompassReading', 0.1, 0.15),
         ('CompassReading', 0.2, 0.25)]
        """

    @property
    def pose(self) -> Pose2D | None:
        """The current pose estimate."""


#: Half the range of a 64-bit counter: int64 readings lie in [-2**63, 2**63).
_INT64_HALF = 1 << 63


def _signed_delta(previous: list[int], current: list[int], bits: int | None) -> list[int]:
    """Tick changes corrected for counter wrap-around (Python integers: exact, and
    quicker than NumPy for a few wheels).

    ``bits`` None: 64-bit counters and those that never wrap, which a simulation
    wraps as 64-bit ones past the int64 range (see :class:`WheelEncoders`).
    """
    span = 1 << (64 if bits is None else bits)
    half = span >> 1
    return [((c - p + half) % span) - half for p, c in zip(previous, current, strict=True)]


class _Wheels:
    """Wheel speeds and rotation increments from successive encoder readings."""

    __slots__ = ("_bits", "_last", "_last_stamp", "_rad_per_tick")

    def __init__(self, robot: Robot) -> None:
        if robot.encoders is None:
            raise ValueError(
                "estimator: this estimator needs wheel encoders: give the Robot some "
                "(Robot(encoders=WheelEncoders()))"
            )
        bits = robot.encoders.bits
        self._bits = None if bits is None or bits >= 64 else bits
        self._rad_per_tick = _TWO_PI / robot.encoders.ticks_per_rev
        self._last: list[int] | None = None
        self._last_stamp = 0.0

    def start_run(self) -> None:
        """Forget the readings of an earlier run: the next reading only latches."""
        self._last = None
        self._last_stamp = 0.0

    def increments(self, reading: EncoderReading) -> tuple[FloatArray, float] | None:
        """Wheel rotations (rad) since the previous reading and the time between them."""
        last = self._last
        ticks = reading.ticks.tolist()
        self._last = ticks
        dt = reading.stamp - self._last_stamp
        self._last_stamp = reading.stamp
        if last is None or dt <= 0.0:
            return None
        delta = _signed_delta(last, ticks, self._bits)
        return np.array(delta, dtype=np.float64) * self._rad_per_tick, dt


class FusionEstimator:
    """PlanarFusion fed with wheel odometry, compass yaw and IMU yaw rate/acceleration."""

    __slots__ = (
        "_accel_var",
        "_compass_var",
        "_forward",
        "_fusion",
        "_gyro_var",
        "_north",
        "_omega_var",
        "_quantum",
        "_v_var",
        "_wheels",
    )

    def __init__(self, fusion: PlanarFusion, robot: Robot) -> None:
        self._fusion = fusion
        self.check_start()
        self._wheels = _Wheels(robot)
        drive = robot.drive
        n = robot.n_wheels
        self._forward = np.asarray(drive.forward_batch(np.eye(n)).T)  # (3, n)
        if np.any(self._forward[1] != 0.0):
            # The unicycle state has no sideways speed: a strafing robot would stay
            # put in the estimate, a silent wrong result.
            raise ValueError(
                "estimator: PlanarFusion's state has no sideways speed, and this robot's "
                "drive can move sideways; use OmniOdometry (with the compass for its "
                "heading) or an Estimator of your own"
            )
        assert robot.encoders is not None
        quantum = _TWO_PI / robot.encoders.ticks_per_rev
        # Variance of a twist from wheel speeds quantised to one tick per reading
        # interval at each end (uniform errors), per second squared of interval.
        self._quantum = quantum
        self._v_var = float(np.sum(self._forward[0] ** 2)) * quantum**2 / 6.0
        self._omega_var = float(np.sum(self._forward[2] ** 2)) * quantum**2 / 6.0
        compass = robot.compass
        self._north = compass.north if compass is not None else 0.0
        self._compass_var = max(compass.noise**2, 1e-6) if compass is not None else 1e-6
        imu = robot.imu
        self._gyro_var = max(imu.gyro_noise**2, 1e-6) if imu is not None else 1e-6
        self._accel_var = max(imu.accel_noise**2, 1e-4) if imu is not None else 1e-4

    def check_start(self) -> None:
        """Refuse a filter whose time is past the run's start (ValueError, naming it).

        When the simulation is built and again as it runs: one filter given to
        two simulations built before either ran is past 0 s when the second runs.
        """
        t = self._fusion.t
        if t is not None and t > 0.0:
            # The run starts at 0 s and feeds readings at their delivery times: the
            # filter would refuse each one up to its own time as out of order (results
            # nobody sees here) and the estimate would stand still, a silent wrong run.
            raise ValueError(
                f"estimator: this PlanarFusion's time is {t:g} s, after the run's start "
                "at 0 s, so it would refuse every reading taken before then (out of "
                "order) and its estimate would stand still: build it for this run with "
                "t0=0.0 (a filter used in an earlier run: build a new one, or carry its "
                "estimate on into this run with fusion.reset(fusion.x, fusion.P, t0=0.0))"
            )

    def observe(self, t: float, reading: Reading) -> None:
        fusion = self._fusion
        kind = type(reading)
        if kind is ImuReading:
            assert isinstance(reading, ImuReading)
            fusion.update_yaw_rate(t, reading.yaw_rate, variance=self._gyro_var)
            fusion.update_acceleration(t, reading.acceleration_x, variance=self._accel_var)
        elif kind is EncoderReading:
            assert isinstance(reading, EncoderReading)
            step = self._wheels.increments(reading)
            if step is None:
                return
            inc, dt = step
            # Added in order, not by a BLAS kernel of the CPU's choosing: the same bits
            # on every machine (a straight drive's yaw rate exactly 0, say).
            rates = inc / dt
            v = ordered_dot(self._forward[0], rates)
            omega = ordered_dot(self._forward[2], rates)
            scale = 1.0 / (dt * dt)
            fusion.update_odometry(
                t, v, omega,
                v_variance=max(self._v_var * scale, 1e-6),
                omega_variance=max(self._omega_var * scale, 1e-6),
            )  # fmt: skip
        elif kind is CompassReading:
            assert isinstance(reading, CompassReading)
            yaw = wrap_angle(self._north - math.radians(reading.heading_deg))
            fusion.update_yaw(t, yaw, variance=self._compass_var)

    @property
    def pose(self) -> Pose2D | None:
        return self._fusion.pose if self._fusion.t is not None else None

    def xyt(self) -> tuple[float, float, float] | None:
        """The pose as three floats (cheaper than :attr:`pose`)."""
        if self._fusion.t is None:
            return None
        x = self._fusion.x
        return float(x[0]), float(x[1]), float(x[2])


class _OmniOdometryEstimator:
    """OmniOdometry: wheel increments rotated by the latest compass yaw."""

    __slots__ = ("_north", "_odometry", "_wheels", "_yaw")

    def __init__(self, odometry: OmniOdometry, robot: Robot) -> None:
        if robot.compass is None:
            raise ValueError(
                "estimator: OmniOdometry takes its heading from a compass: "
                "give the Robot one (Robot(compass=Compass()))"
            )
        if not isinstance(robot.drive, OmniDrive):
            raise ValueError(
                "estimator: OmniOdometry needs an omnidirectional robot "
                "(Robot(drive=OmniDrive(...)))"
            )
        self._odometry = odometry
        self._wheels = _Wheels(robot)
        self._north = robot.compass.north
        self._yaw: float | None = None

    def start_run(self) -> None:
        """Forget the compass yaw and the counters read in an earlier run.

        A shallow copy of a Simulation shares this adapter: run after the
        original, it would rotate its first wheel increments (those before its
        own first compass reading) by the yaw the original's run read last,
        where a new Simulation with the same odometry takes the odometry's
        heading. Each run starts as a new adapter does; the odometry's pose
        goes on from where it is.
        """
        self._yaw = None
        self._wheels.start_run()

    def observe(self, t: float, reading: Reading) -> None:
        if isinstance(reading, CompassReading):
            self._yaw = wrap_angle(self._north - math.radians(reading.heading_deg))
        elif isinstance(reading, EncoderReading):
            step = self._wheels.increments(reading)
            if step is None:
                return
            yaw = self._odometry.pose.theta if self._yaw is None else self._yaw
            self._odometry.update(step[0], yaw)

    @property
    def pose(self) -> Pose2D | None:
        return self._odometry.pose


class _DiffOdometryEstimator:
    """DiffOdometry fed with the encoder counters, as counters of its own width.

    The raw readings when the odometry decodes counters as wide as the robot's
    (its ``bits`` equal to the encoders' ``bits``; 64 and None alike: both are
    64-bit counters, which a run wraps past the int64 range, and DiffOdometry
    decodes them so). Otherwise an odometry built for other
    counters (the default ``bits=None`` on the default 16-bit encoders)
    would read the robot's wrap-around, after 64 wheel turns, as a jump of
    -65535 ticks: it is fed the readings unwrapped at the robot's width and
    wrapped again at its own, the same tick changes.
    """

    __slots__ = ("_fed", "_last", "_odometry", "_robot_bits", "_span", "_translate")

    def __init__(self, odometry: DiffOdometry, robot: Robot) -> None:
        if robot.encoders is None:
            raise ValueError(
                "estimator: DiffOdometry needs wheel encoders: give the Robot some "
                "(Robot(encoders=WheelEncoders()))"
            )
        if not isinstance(robot.drive, DiffDrive):
            raise ValueError(
                "estimator: DiffOdometry needs a differential-drive robot "
                "(Robot(drive=DiffDrive(...)))"
            )
        self._odometry = odometry
        bits = robot.encoders.bits
        own = odometry.bits
        self._robot_bits = None if bits is None or bits >= 64 else bits
        self._span = None if own is None or own >= 64 else 1 << own
        self._translate = self._span != (
            None if self._robot_bits is None else 1 << self._robot_bits
        )
        self._last: list[int] | None = None
        self._fed: list[int] | None = None

    def start_run(self) -> None:
        """Forget the counters read before this run: the robot's count from 0 in every run.

        An odometry that read counters before (an earlier run's: a route driven
        leg by leg, a Simulation a leg, with one odometry) would take the
        difference to this run's first reading as motion, a jump by the whole
        distance counted before. So the run's first reading only latches the
        counters, as a new odometry's does (:meth:`DiffOdometry.reset`); the
        pose goes on from where it is.
        """
        self._last = None
        self._fed = None
        self._odometry.reset()

    def observe(self, t: float, reading: Reading) -> None:
        if isinstance(reading, EncoderReading):
            if self._translate:
                left, right = self._counters(reading.ticks.tolist())
                self._odometry.update(left, right)
            else:
                self._odometry.update(int(reading.ticks[0]), int(reading.ticks[1]))

    def _counters(self, raw: list[int]) -> list[int]:
        """``raw`` readings of the robot's counters as readings of the odometry's."""
        last, fed = self._last, self._fed
        self._last = raw
        if last is None or fed is None:
            new = raw
        else:
            delta = _signed_delta(last, raw, self._robot_bits)
            new = [f + d for f, d in zip(fed, delta, strict=True)]
        span = self._span
        if span is not None:
            new = [v % span for v in new]
        else:
            # A 64-bit (or never-wrapping) odometry: the int64 values a 64-bit counter
            # holds, which it decodes across the wrap (a sum past them is refused).
            new = [(v + _INT64_HALF) % (2 * _INT64_HALF) - _INT64_HALF for v in new]
        self._fed = new
        return new

    @property
    def pose(self) -> Pose2D | None:
        return self._odometry.pose


def as_estimator(value: Any, robot: Robot) -> Estimator | None:
    """Wrap a navkit estimator for a simulation, or check a user's :class:`Estimator`."""
    if value is None:
        return None
    if isinstance(value, PlanarFusion):
        return FusionEstimator(value, robot)
    if isinstance(value, OmniOdometry):
        return _OmniOdometryEstimator(value, robot)
    if isinstance(value, DiffOdometry):
        return _DiffOdometryEstimator(value, robot)
    if isinstance(value, Estimator):
        # The protocol check sees only that the names exist: a non-callable observe
        # would fail at the first reading, as "'int' object is not callable".
        if not callable(value.observe):
            raise TypeError(
                f"estimator.observe must be a method observe(t, reading), "
                f"got {type(value.observe).__name__}"
            )
        return value
    raise TypeError(
        "estimator must be a PlanarFusion, OmniOdometry, DiffOdometry or an object with "
        f"observe(t, reading) and pose, got {type(value).__name__}"
    )
