"""The closed loop: world, robot, sensors with latency, estimator and controller."""

from __future__ import annotations

import copy
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from types import MappingProxyType, MemberDescriptorType
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.angles import wrap_float
from navkit._shared.deprecation import renamed_keyword
from navkit._shared.dunders import slot_state
from navkit._shared.frozen import frozen_setattr, restore_read_only, slot_names
from navkit._shared.goal import at_goal
from navkit._shared.metres import metres_text
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_bool, as_float_array, finite_float, positive_float
from navkit.estimation import DiffOdometry, OmniOdometry, PlanarFusion
from navkit.geometry import Pose2D, Twist2D, as_twist
from navkit.planning import Path2D
from navkit.sim._done import done_flag
from navkit.sim._estimators import (
    Estimator,
    FusionEstimator,
    _DiffOdometryEstimator,
    _OmniOdometryEstimator,
    as_estimator,
)
from navkit.sim._latency import DelayLine
from navkit.sim._lidar import Scanner, as_generator, check_rate
from navkit.sim._robot import Body, Robot
from navkit.sim._segment_kernels import (
    COLLIDED,
    GOAL,
    GOAL_UNDECIDED,
    STAT_COLLISIONS,
    STAT_MIN_CLEARANCE,
    STAT_TIME_TO_GOAL,
    decide_goal,
    due_step,
    run_edge_segment,
    run_segment,
)
from navkit.sim._sensors import (
    CompassReading,
    EncoderReading,
    ImuReading,
    Reading,
    ScanReading,
)
from navkit.sim._trace import (
    Event,
    Metrics,
    Trace,
    adopted_trace,
    cross_track,
    nan_if_empty,
)
from navkit.sim._world import MAX_POSE_COORD, World, as_query_pose, as_world

__all__ = ["Controller", "Observation", "Simulation"]

#: Most physics steps of one run (duration × rate).
MAX_STEPS = 10_000_000
#: Longest simulated duration, s.
MAX_DURATION = 1e7
_EPS = 1e-9
_EPS_EXACT = Fraction(1, 10**9)
#: Event kinds that end a run by themselves (noted when the loop stops).
_CLOSING_KINDS = ("timeout", "controller done", "wall-clock timeout")
#: Rows of the trace's arrays allocated before a long run first grows them.
_FIRST_ROWS = 1 << 14


def _check_pose_source(controller: Controller) -> None:
    """Refuse a tracker adapter that tracks an estimate in a run without an estimator.

    It would send zero twists for the whole run (no estimate ever comes), ending
    on the timeout with the robot where it started and no event saying why.
    """
    from navkit.sim._adapters import TrackerController  # it imports this module

    if isinstance(controller, TrackerController) and controller._use_estimate:
        raise ValueError(
            "controller: TrackerController(use_estimate=True) tracks the estimator's pose, "
            "and this Simulation has no estimator: pass estimator=..., or "
            "use_estimate=False to track the true pose"
        )


def _step_count(duration: float, rate: float) -> int:
    """Physics steps of a run, ``ceil(duration * rate)``, at least one.

    ``_EPS`` absorbs rounding (0.07 * 100 = 7.000000000000001 is 7 steps); a
    positive duration below ``_EPS`` steps still runs one, as documented.
    """
    return max(1, math.ceil(duration * rate - _EPS))


#: Float tick counts at or beyond this magnitude do not fit an int64 reading.
_INT64_SPAN = 2.0**63


def _int64_counts(counts: FloatArray) -> FloatArray:
    """Whole-number float tick counts as the int64 values a 64-bit counter holds.

    Counts within the int64 range are returned as they are. The others (a long
    run of fast wheels on a fine encoder: 2**63 ticks are 5.8e10 rad at 1e9
    ticks a turn) are reduced modulo 2**64 into ``[-2**63, 2**63)``, exactly:
    ``fmod`` is exact, and so is adding or subtracting 2**64 to a count within
    a factor 2 of it. Casting them as they were is undefined (NumPy gave
    INT64_MIN with a RuntimeWarning). Congruent modulo 2**64, the result keeps
    a narrower counter's reading under its mask.

    Examples
    --------
    >>> counts = np.array([5.0, 2.0**64 + 4096.0, -(2.0**63) - 4096.0])
    >>> _int64_counts(counts).astype(np.int64).tolist()  # the last is 2**63 - 4096
    [5, 4096, 9223372036854771712]
    """
    if counts.size == 0 or float(np.max(np.abs(counts))) < _INT64_SPAN:
        return counts
    wrapped = np.fmod(counts, 2.0 * _INT64_SPAN)
    wrapped[wrapped >= _INT64_SPAN] -= 2.0 * _INT64_SPAN
    wrapped[wrapped < -_INT64_SPAN] += 2.0 * _INT64_SPAN
    return wrapped


def _lag_steps(latency: float, rate: float) -> int:
    """Whole physics steps from a reading's step to its delivery's.

    The fewest ``m`` with ``m / rate >= latency - 1e-9`` s, in exact rational
    arithmetic on the two floats: one count for every reading of the stream. The
    tolerance lets a latency of whole steps that is not a binary fraction (0.03 s
    at 100 Hz) count as those steps. Comparing ``stamp + latency`` with each
    step's time in floats instead rounded a latency 1e-9 s over whole steps
    either way from one reading to the next (7 % of them a step late at 100 Hz).
    """
    if latency == 0.0:
        return 0
    return max(math.ceil((Fraction(latency) - _EPS_EXACT) * Fraction(rate)), 0)


def _unknown_hold(obs: Any) -> None:
    """``dt`` of an :class:`Observation` made before it existed: not known."""
    return None


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class Observation:
    """What a controller is given at a control step.

    Attributes
    ----------
    t : float
        Simulated time of the control step, s.
    scan, encoders, compass, imu : reading or None
        The latest delivered reading of each sensor (None before the first or
        without that sensor). With latency they are stale: compare their
        ``stamp`` with ``t``.
    new : tuple of Reading
        Every reading delivered since the previous control step, in delivery
        order.
    estimate : Pose2D or None
        The estimator's current pose (None without an estimator).
    true_pose : Pose2D
        The robot's true pose: ground truth, for oracle controllers and tests.
    dt : float or None, default None
        Simulated time until the next control step, s: how long the command
        returned now is held. The physics steps between the two over the physics
        rate, counted exactly (0.05 for 5 steps of 100 Hz); a control rate that
        does not divide the physics rate gives unequal periods (0.03 and 0.04 s
        at 30 Hz of 100 Hz, not 1/30 s). Always set by :class:`Simulation`
        (None: not known, for observations made elsewhere).

    Examples
    --------
    >>> obs = Observation(0.0, None, None, None, None, (), None, Pose2D(0.0, 0.0, 0.0))
    >>> obs.true_pose.x, obs.dt
    (0.0, None)
    >>> Observation(0.07, None, None, None, None, (), None, Pose2D(0.0, 0.0, 0.0), dt=0.04).dt
    0.04
    """

    t: float
    scan: ScanReading | None
    encoders: EncoderReading | None
    compass: CompassReading | None
    imu: ImuReading | None
    new: tuple[Reading, ...]
    estimate: Pose2D | None
    true_pose: Pose2D
    dt: float | None = None

    # Fields added since a release, for pickles made before (see
    # navkit._shared.frozen.fill_added_fields). Not annotated: it would be a field.
    _added_fields = MappingProxyType({"dt": _unknown_hold})

    def __post_init__(self) -> None:
        object.__setattr__(self, "t", finite_float(self.t, "t"))
        if self.dt is not None:
            object.__setattr__(self, "dt", positive_float(self.dt, "dt"))
        for name, cls in (
            ("scan", ScanReading), ("encoders", EncoderReading), ("compass", CompassReading),
            ("imu", ImuReading), ("estimate", Pose2D),
        ):  # fmt: skip
            value = getattr(self, name)
            if value is not None and not isinstance(value, cls):
                kind = type(value).__name__
                raise TypeError(f"{name} must be a {cls.__name__} or None, got {kind}")
        if not isinstance(self.true_pose, Pose2D):
            raise TypeError(f"true_pose must be a Pose2D, got {type(self.true_pose).__name__}")
        if not isinstance(self.new, (tuple, list)):
            raise TypeError(f"new must be a tuple of readings, got {type(self.new).__name__}")
        readings = (ScanReading, EncoderReading, CompassReading, ImuReading)
        for item in self.new:
            if not isinstance(item, readings):
                raise TypeError(f"new must hold readings, got a {type(item).__name__}")
        object.__setattr__(self, "new", tuple(self.new))

    def __setstate__(self, state: list[Any] | tuple[Any, Any]) -> None:
        """Restore from a pickle or copy (and what a subclass adds, see ``restore_read_only``).

        A pickle made before ``dt`` existed holds the eight other fields: its
        ``dt`` is None, not known (it was left unset, and ``repr`` and ``obs.dt``
        raised ``AttributeError``, review 50).
        """
        restore_read_only(self, state, ())


Controller = Callable[[Observation], Twist2D | ArrayLike]
"""A controller: ``Observation -> Twist2D`` (or ``[vx, vy, omega]``), robot frame.

If the controller object has a ``done`` attribute that becomes true, the run
ends (reason ``"controller done"``).
"""


def _goal(value: Any) -> tuple[float, float, float | None] | None:
    if value is None:
        return None
    if isinstance(value, Pose2D):
        p = as_query_pose(value, "goal")
        return p.x, p.y, p.theta
    arr = as_float_array(value, "goal")
    if arr.shape == (2,):
        # Within the bound of a pose, as the start: the distance to a farther goal
        # (the final error) overflows.
        x, y = float(arr[0]), float(arr[1])
        if abs(x) > MAX_POSE_COORD or abs(y) > MAX_POSE_COORD:
            raise ValueError(f"goal must lie within ±{MAX_POSE_COORD:g} m, got ({x!r}, {y!r})")
        return x, y, None
    if arr.shape == (3,):
        p = as_query_pose(arr, "goal")
        return p.x, p.y, p.theta
    raise ValueError(f"goal must be (x, y), (x, y, theta) or a Pose2D, got shape {arr.shape}")


def _reference(value: Any) -> FloatArray | None:
    if value is None:
        return None
    if isinstance(value, Path2D):
        if value.frame != "world":
            # The trackers' advice for the same mistake (control's as_world_path).
            raise ValueError(
                f"reference_path must be in the world frame, got a {value.frame!r} Path2D "
                "(convert it with path.to_world(grid), grid the map it was planned on, or plan "
                "with MapPlanner)"
            )
        pts = value.points
    else:
        pts = as_float_array(value, "reference_path", shape=(None, 2))
    if pts.shape[0] == 0:
        raise ValueError("reference_path must hold at least one point")
    # The cross-track distances square the legs' lengths: beyond this they overflow.
    if float(np.max(np.abs(pts))) > MAX_POSE_COORD:
        raise ValueError(f"reference_path must lie within ±{MAX_POSE_COORD:g} m")
    return np.ascontiguousarray(pts, dtype=np.float64)


class Simulation:
    """A closed-loop run of one robot in a world, at a fixed physics rate.

    Every ``1 / rate`` seconds the robot's wheels and pose advance (see
    :class:`Robot`) and its footprint is checked against the world: a
    collision is found at the first physics step whose footprint touches an
    obstacle. A step along which a point of the footprint moves farther than
    the radius of the largest disc inside the footprint is also checked
    against the static obstacles along its way, at poses that far apart (or
    farther, where the clearance shows that nothing lies in between), so that
    a fast robot or a low ``rate`` cannot carry the robot through a thin wall
    or into a solid obstacle: the first of those poses that touches an
    obstacle then stands for the step's end (the collision's pose). Moving
    obstacles are checked only at the end of each step, where they are at
    that step's time (a robot inside one counts as a collision), never along
    the step: a moving obstacle that crosses the robot's path within one step
    (fast, or thinner than its motion over ``1 / rate``) is missed, so raise
    ``rate`` for fast ones. Each
    sensor of the robot samples at its own rate (at the first physics step at
    or after each of its sample times, within 1e-9 s, or ``2**-50`` of the
    time beyond 1.1e6 s, where the times' rounding exceeds 1e-9 s: 8.9e-9 s at
    10^7 s, as the controller's steps); each reading is delivered ``latency``
    seconds later, at the first step at or after that within 1e-9 s, counted
    exactly on the floats given: the same whole number of steps after its own
    for every reading of a sensor (0.03 s is 3 steps of 100 Hz, 0.03 s + 2e-9 s
    is 4),
    to the estimator, which is given it with that delivery time, and to the
    controller. Readings delivered at one step are handed over sensor by
    sensor, scans, encoders, compass, then IMU, each sensor's in the order
    taken (so with unequal latencies an older reading may follow a newer one
    of another sensor). The controller runs at ``control_rate``: it receives an
    :class:`Observation` (the latest readings, those new since its last call,
    how long its command will be held, the estimator's pose and the true pose) and returns a
    body twist, which the wheels follow until the next control step. The physics between two control
    steps or scans runs in one compiled kernel, so a run goes hundreds of times
    faster than real time.

    The run ends when the goal is reached (with ``stop_at_goal``), on a
    collision (with ``end_on_collision``; otherwise the robot is put back
    where it was, stopped, and the run goes on), when the controller's
    ``done`` attribute turns true, when ``duration`` is reached or when
    ``wall_timeout`` seconds of real time have passed; the reason is in
    ``Trace.metrics.reason``. Every random draw (sensor noise, slip) comes from
    one seeded NumPy Generator, so a run with the same seed, controller and
    estimator state is reproduced exactly. The draws are taken in the order
    the run needs them (between two control steps or scans: the slip of each
    physics step, then the noise of the compass and IMU readings taken, then
    a scan's): the sensors' noises are independent of each other and of the
    slip, but a change that adds, removes or moves draws (a noise or the
    slip turned on or off, a sensor added, a sensor's rate or beams, the
    control rate) changes every later draw of every sensor. Changing only
    the size of a noise that is on (a compass ``noise`` of 0.01 rad to 0.02,
    a ``RangeNoise`` sigma or absolute term, ``wheel_slip``) or a compass or IMU bias keeps
    every draw: that noise's errors scale with it and every other error is
    as before, so that runs compare on common random numbers. A ``Simulation``
    runs once; a copy
    (:func:`copy.copy` too) has its own copy of the generator, so that running
    one leaves the other's draws as they would have been. A shallow copy
    shares the world and robot (which no run changes) and the controller and
    estimator (which a run changes): run after the original, the copy's
    controller and estimator go on from the state that run left them in, and
    its run is that of a new Simulation given them in that state (a
    ``PlanarFusion`` past 0 s is refused then, as by a new Simulation). For
    independent runs, copy with :func:`copy.deepcopy` or build each
    Simulation with its own controller and estimator.

    An ordinary class with ``__slots__``: it holds the run's state. Runs of
    different Simulations may go on in different threads at once, sharing
    their :class:`World` and :class:`Robot` (neither is changed by a run);
    each needs its own controller, estimator and Generator ``seed`` (which a
    run changes), and gives what it gives alone. A Simulation runs once: a
    :meth:`run` called while its run is under way (another thread's, or a
    signal handler's interrupting it in the same thread) raises
    ``RuntimeError`` as a second run does and changes nothing; the run under
    way goes on as alone.

    Parameters
    ----------
    world : World
    robot : Robot
    controller : callable
        ``controller(observation) -> Twist2D`` or ``[vx, vy, omega]``.
    start : Pose2D or array_like [x, y, theta]
        Start pose, within ±1e12 m; the footprint must be free there
        (keyword-only, as is everything below).
    goal : Pose2D or array_like (x, y) or (x, y, theta), optional
        Goal for the metrics (and the end of the run with ``stop_at_goal``),
        within ±1e12 m (as ``start``). Its heading counts only with
        ``yaw_tolerance``; without it, the position alone is the goal.
    goal_tolerance : float, default 0.1
        The goal is reached within this distance, m, in (0, 1e6] (the name the
        controllers use), by the controllers' own test: exactly where a
        controller with this tolerance is done, also for an offset on the
        tolerance's last ulp. It is the run's criterion, not the controller's:
        below the distance at which the controller brings the robot to rest it
        is never met, and the run ends at its ``duration`` (or when the
        controller is done), ``reached`` False. The simulator cannot see that
        distance: a ``PotentialFieldController``'s attraction rests the robot
        off the goal (3.75 mm with the default ``BlendedAttraction``; its own
        ``goal_tolerance`` must exceed that distance), a path tracker is done
        within its own ``goal_tolerance`` on exact wheels (down to 1e-9 m), but
        on slipping or acceleration-limited wheels (``Robot(wheel_slip=,
        max_wheel_acceleration=)``) one that turns in place near the goal may
        turn and creep about it for ever, never done, below the distance such a
        turn (or an overshoot of a ramping wheel) moves the robot: micrometres
        to a millimetre in the control guide's runs. Give at least the
        controller's, and one the robot can hold.
    yaw_tolerance : float, optional
        With a goal heading: also require the heading within this, rad, in
        (0, π].
    reference_path : Path2D (world frame) or array_like (K, 2), optional
        Path for the cross-track error, within ±1e12 m.
    estimator : PlanarFusion, OmniOdometry, DiffOdometry or Estimator, optional
        Fed every delivered reading (at its delivery time). Initialise it at
        the start pose (e.g. ``PlanarFusion(pose=(x, y, θ), t0=0.0)``).
        A ``PlanarFusion`` needs a drive that cannot move sideways (its state
        has no sideways speed; ``ValueError`` for an omnidirectional drive)
        and a time of at most 0 s, the run's start (``ValueError`` for a later
        ``t0`` or a filter used in an earlier run, which would refuse the
        readings as out of order: to carry one's estimate on into a new run,
        ``fusion.reset(fusion.x, fusion.P, t0=0.0)``); an earlier ``t0`` is taken, and its first
        reading predicts over the gap from ``t0`` as well (build it with
        ``t0=0.0`` unless the robot moved before the run). It is given the
        sensors' own noise as variances: the compass's ``noise²`` (at least
        1e-6 rad²) for the yaw, the IMU's ``gyro_noise²`` (at least 1e-6) and
        ``accel_noise²`` (at least 1e-4) for the yaw rate and the forward
        acceleration, and for the odometry's speed and yaw rate the
        encoders' quantisation (a uniform error of one tick at each end of
        each interval); biases, slip and wheel-radius errors are not in
        them. Each reading is fused as if taken at its delivery time, so with
        latency the estimate lags the robot by it, which its covariance does
        not include (turning at 0.4 rad/s with 0.1 s on every sensor: the
        heading 0.043 rad behind, a mean heading NEES of about 1.9 where 1 is
        consistent, 0.8 without latency); an :class:`Estimator` of your own
        can pass ``reading.stamp`` to a ``PlanarFusion`` whose ``history``
        covers the latencies.
        A ``DiffOdometry`` is given the counter readings as counters of its
        own ``bits`` (the same tick changes), so that the encoders'
        wrap-around does not depend on the two widths agreeing. The robot's
        counters count from 0 in every run: the counters a ``DiffOdometry``
        read before (in an earlier run) are forgotten when the run starts,
        as its ``reset()`` forgets them, so its first reading only latches
        them and its pose goes on from where it was (a route driven leg by
        leg with one odometry, each leg started at its pose).
    rate : float, default 100.0
        Physics rate, Hz, in (0, 10^4]; no sensor or controller may be faster.
        Step ``i`` happens at ``i / rate`` s (the time of its trace row, its
        readings and events: 0.35 at step 35 of 100 Hz, not ``35 * 0.01``).
    control_rate : float, default 20.0
        Controller rate, Hz, in (0, ``rate``].
    duration : float, default 300.0
        Simulated time after which the run times out, s, in (0, 10^7]: at the
        first physics step at or after it, step ``ceil(duration * rate)``
        (so a duration that is not a whole number of steps runs up to one step
        longer). ``duration * rate`` may be at most 10^7 steps.
    seed : int, numpy Generator or None, default 0
        Randomness of the run (None: fresh entropy, not reproducible).
    record_scans : bool, default False
        Keep every scan in the trace.
    stop_at_goal : bool, default True
    end_on_collision : bool, default True
    wall_timeout : float, optional
        Real-time limit of :meth:`run`, s, in (0, 1e6].

    Other Parameters
    ----------------
    goal_radius : float, optional
        Deprecated name of `goal_tolerance`.
    goal_yaw_tolerance : float, optional
        Deprecated name of `yaw_tolerance`.

    Raises
    ------
    ValueError
        A bad rate, duration or tolerance, a sensor faster than the physics,
        a ``"grid"`` ``Path2D`` as ``reference_path`` (the message says how
        to convert it), a robot starting in collision, an estimator that
        cannot serve the run (see ``estimator``), or a ``TrackerController``
        tracking the estimate in a run without an estimator.
    TypeError
        Arguments of the wrong type.

    Notes
    -----
    Far from the origin: each physics step moves the absolute pose and rounds
    it to float64, so a run's poses carry the rounding of its coordinates, at
    most about one float spacing of them per step and axis (two roundings of
    half a spacing), as :func:`navkit.geometry.rollout`. Near the origin it is
    negligible; a run whose world, start and goal are all translated by
    (1e5, 1e5) m, where floats are 1.5e-11 m apart, measured against the same
    run at the origin (seed 0): a straight drive at 0.02 m/s, whose rounding
    has the same sign every step, drifted 9.9e-8 m after 2·10^4 steps of 100
    Hz and 9.9e-7 m after 2·10^5; a weave on a 5 m circle, whose roundings
    mix their signs, at most 2.8e-9 m and 6e-9 m. A goal, collision or scan decided
    that close to its edge may then go the other way. The simulator cannot
    shift the world itself (its obstacles are given in world coordinates):
    for long high-rate runs far from the origin, give the world, start, goal
    and reference path relative to a point near the robot's area.

    Examples
    --------
    >>> from shapely.geometry import box
    >>> from navkit.kinematics import DiffDrive
    >>> world = World(box(-1.0, -1.0, 4.0, 2.0).exterior)
    >>> robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2)
    >>> def go(obs: Observation) -> Twist2D:  # drive straight ahead at 0.5 m/s
    ...     return Twist2D(0.5, 0.0, 0.0)
    >>> trace = Simulation(world, robot, go, start=(0.0, 0.0, 0.0), goal=(2.0, 0.0)).run()
    >>> trace.metrics.reached, trace.metrics.reason, round(trace.metrics.time_to_goal, 2)
    (True, 'goal reached', 3.8)
    >>> trace = Simulation(world, robot, go, start=(0.0, 0.0, 0.0)).run()
    >>> trace.metrics.reason, trace.metrics.collisions
    ('collision', 1)
    """

    __slots__ = (
        "__weakref__",
        "_control_rate",
        "_controller",
        "_duration",
        "_end_on_collision",
        "_estimator",
        "_goal",
        "_goal_radius",
        "_goal_yaw_tolerance",
        "_ran",
        "_rate",
        "_record_scans",
        "_reference",
        "_rng",
        "_robot",
        "_start",
        "_stop_at_goal",
        "_wall_timeout",
        "_world",
    )
    __getstate__ = slot_state  # pickle protocols 0 and 1 too

    def __init__(
        self,
        world: World,
        robot: Robot,
        controller: Controller,
        *,
        start: Pose2D | ArrayLike,
        goal: Pose2D | ArrayLike | None = None,
        goal_tolerance: float = 0.1,
        yaw_tolerance: float | None = None,
        reference_path: Path2D | ArrayLike | None = None,
        estimator: PlanarFusion | OmniOdometry | DiffOdometry | Estimator | None = None,
        rate: float = 100.0,
        control_rate: float = 20.0,
        duration: float = 300.0,
        seed: int | np.random.Generator | None = 0,
        record_scans: bool = False,
        stop_at_goal: bool = True,
        end_on_collision: bool = True,
        wall_timeout: float | None = None,
        goal_radius: float | None = None,
        goal_yaw_tolerance: float | None = None,
    ) -> None:
        # The controllers' names for the same tolerances; the old ones warn, and errors
        # name the keyword the caller wrote.
        tol_name = "goal_tolerance" if goal_radius is None else "goal_radius"
        yaw_name = "yaw_tolerance" if goal_yaw_tolerance is None else "goal_yaw_tolerance"
        goal_tolerance = renamed_keyword(
            "goal_radius", goal_radius, "goal_tolerance", goal_tolerance, 0.1
        )
        yaw_tolerance = renamed_keyword(
            "goal_yaw_tolerance", goal_yaw_tolerance, "yaw_tolerance", yaw_tolerance, None
        )
        self._world = as_world(world)
        if not isinstance(robot, Robot):
            raise TypeError(f"robot must be a Robot, got {type(robot).__name__}")
        self._robot = robot
        if not callable(controller) or isinstance(controller, type):
            raise TypeError(f"controller must be callable, got {type(controller).__name__}")
        self._controller = controller
        self._rate = check_rate(rate, "rate")
        self._control_rate = check_rate(control_rate, "control_rate")
        self._check_not_faster("control_rate", self._control_rate)
        for name in ("lidar", "compass", "imu", "encoders"):
            sensor = getattr(robot, name)
            if sensor is not None:
                self._check_not_faster(
                    f"robot.{name}.rate", sensor.rate, f"{type(sensor).__name__}(rate=...)"
                )
        self._duration = positive_float(duration, "duration")
        if self._duration > MAX_DURATION:
            raise ValueError(f"duration must be at most {MAX_DURATION:g} s, got {self._duration}")
        steps = _step_count(self._duration, self._rate)
        if steps > MAX_STEPS:
            raise ValueError(
                f"duration × rate is {steps} physics steps; the maximum is {MAX_STEPS} "
                "(shorten the run or lower the rate)"
            )
        self._start = as_query_pose(start, "start")
        self._goal = _goal(goal)
        # The private names predate the renames (goal_radius, goal_yaw_tolerance).
        self._goal_radius = positive_float(goal_tolerance, tol_name)
        if self._goal_radius > 1e6:
            raise ValueError(f"{tol_name} must be at most 1e6 m, got {self._goal_radius}")
        self._goal_yaw_tolerance: float | None = None
        if yaw_tolerance is not None:
            tol = positive_float(yaw_tolerance, yaw_name)
            if tol > math.pi:
                raise ValueError(f"{yaw_name} must lie in (0, π] rad, got {tol}")
            if self._goal is None or self._goal[2] is None:
                raise ValueError(f"{yaw_name} needs a goal with a heading (x, y, theta)")
            self._goal_yaw_tolerance = tol
        self._reference = _reference(reference_path)
        self._estimator: Estimator | None = as_estimator(estimator, robot)
        if self._estimator is None:
            _check_pose_source(controller)
        self._rng = as_generator(seed, "seed")
        self._record_scans = as_bool(record_scans, "record_scans")
        self._stop_at_goal = as_bool(stop_at_goal, "stop_at_goal")
        self._end_on_collision = as_bool(end_on_collision, "end_on_collision")
        self._wall_timeout: float | None = None
        if wall_timeout is not None:
            wt = positive_float(wall_timeout, "wall_timeout")
            if wt > 1e6:
                raise ValueError(f"wall_timeout must be at most 1e6 s, got {wt}")
            self._wall_timeout = wt
        if self._world.collides(robot.footprint, self._start, t=0.0):
            s = self._start
            raise ValueError(
                f"start: the robot starts inside an obstacle at ({metres_text(s.x)}, "
                f"{metres_text(s.y)}, {s.theta:g}): "
                "its footprint touches or overlaps the world's obstacles"
            )
        self._ran = False

    def __copy__(self) -> Simulation:
        """A shallow copy with its own random generator (a copy of this one's state)."""
        twin = object.__new__(type(self))
        for name in slot_names(type(self)):
            if hasattr(self, name):
                object.__setattr__(twin, name, getattr(self, name))
        if hasattr(self, "__dict__"):
            twin.__dict__.update(self.__dict__)
        # Shared, the generator would make a run of one change the other's draws.
        twin._rng = copy.deepcopy(self._rng)
        return twin

    def __repr__(self) -> str:
        # Where, from where to where, how long: the robot (hundreds of characters) and
        # the controller (any callable) are left out.
        goal = self._goal if self._goal is None or self._goal[2] is not None else self._goal[:2]
        return (
            f"{type(self).__name__}({self._world!r}, start={self._start!r}, goal={goal!r}, "
            f"duration={self._duration!r}, rate={self._rate!r}, "
            f"control_rate={self._control_rate!r})"
        )

    def _check_not_faster(self, name: str, rate: float, remedy: str | None = None) -> None:
        if rate > self._rate * (1.0 + 1e-12):
            lower = name if remedy is None else f"{name} ({remedy})"
            raise ValueError(
                f"{name} ({rate:g} Hz) must not exceed the simulation rate ({self._rate:g} Hz): "
                f"lower {lower} or raise Simulation(rate=)"
            )

    # ------------------------------------------------------------------ run
    def run(self) -> Trace:
        """Run the loop to its end and return the :class:`Trace`.

        Collisions are found at the end of each physics step; a long step is
        also swept against the static obstacles, but moving obstacles are
        checked only at the end of each step (see :class:`Simulation`): one
        that crosses the robot's way within a step is missed.

        Returns
        -------
        Trace
            One row per physics step (true and estimated poses, commands), the
            scans when recorded, the events and the run's :class:`Metrics`.

        Raises
        ------
        RuntimeError
            When called a second time (build a new Simulation), also while the
            first run is under way (another thread's, or a signal handler's).
        ValueError
            When the controller asks a differential robot to move sideways, or
            a robot without ``max_wheel_speed`` for wheel speeds beyond float64
            (with one, such commands are scaled down like any other); before
            anything runs, for a ``PlanarFusion`` estimator whose time is past
            0 s (run by another simulation since this one was built), the
            filter unchanged.
        Exception
            Whatever the controller or the estimator raises (a
            ``KeyboardInterrupt`` too), unchanged: the run ends there and no
            trace is returned.

        Notes
        -----
        A run that ends with an exception is not undone: this Simulation counts
        as run (:meth:`run` again, or on a copy of it, raises RuntimeError) and
        its random generator has been drawn from, and the controller and the
        estimator keep what the run did to them (an estimator has taken the
        readings delivered up to the failure). The world and the robot are
        unchanged. To run again, build a new Simulation with a fresh controller
        and estimator (the same int ``seed`` gives the same draws).

        Memory: the trace takes 80 bytes a physics step (its four arrays),
        recorded straight into the arrays it returns (grown in place by a
        quarter at a time, trimmed in place at the end). A long run peaks at
        about 1.3 times its trace, whether it runs its whole ``duration`` or
        ends early (1.30 at 10^5 steps of a diff-drive robot with a LiDAR, 1.33
        for a goal reached at step 16390 of 10^5, measured with tracemalloc);
        the scans, when recorded, come on top.

        Examples
        --------
        >>> from shapely.geometry import box
        >>> from navkit.kinematics import DiffDrive
        >>> robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2)
        >>> def spin(obs: Observation) -> Twist2D:  # turn on the spot at 1 rad/s
        ...     return Twist2D(0.0, 0.0, 1.0)
        >>> sim = Simulation(World(box(-1.0, -1.0, 1.0, 1.0).exterior), robot, spin,
        ...                  start=(0.0, 0.0, 0.0), duration=0.5)
        >>> trace = sim.run()
        >>> m = trace.metrics
        >>> m.reason, round(float(trace.poses[-1, 2]), 6), round(m.min_clearance, 6)  # rad, m
        ('timeout', 0.5, 0.8)
        >>> sim.run()
        Traceback (most recent call last):
        ...
        RuntimeError: a Simulation runs once; build a new one for another run
        """
        if self._ran:
            raise RuntimeError("a Simulation runs once; build a new one for another run")
        # Marked run at once: no call between the check and the store, where Python
        # could switch threads or run a signal handler. A second run() started there
        # (the isinstance below, the filter's check) ran the whole loop, and this run
        # went on after it with the controller, estimator and generator it left: two
        # traces, this one wrong, and no error.
        self._ran = True
        estimator = self._estimator
        try:
            if isinstance(estimator, FusionEstimator):
                estimator.check_start()  # run since this simulation was built?
        except BaseException:
            self._ran = False  # refused before anything ran: this Simulation may run
            raise
        if isinstance(estimator, (_DiffOdometryEstimator, _OmniOdometryEstimator)):
            # Counters (and a compass yaw) read in an earlier run are not this run's:
            # a shallow copy shares the adapter, and runs as a new Simulation would.
            estimator.start_run()
        return _Run(self).execute()


class _Stream:
    """One sensor's readings on their way to delivery, each ``lag`` steps after its own."""

    __slots__ = ("lag", "line", "rank")

    def __init__(self, latency: float, rank: int, rate: float) -> None:
        self.line: DelayLine[Reading] = DelayLine(latency)
        self.rank = rank
        self.lag = _lag_steps(latency, rate)


class _Run:
    """The state of one run (kept apart from the configuration)."""

    __slots__ = (
        "body",
        "carry",
        "cmd",
        "commands",
        "compass",
        "contacts",
        "counts",
        "dt",
        "dyn_circles",
        "dyn_segs",
        "enc_mask",
        "enc_span",
        "enc_tpr",
        "encoders",
        "est_t",
        "est_xyt",
        "estimates",
        "events",
        "fast",
        "filled",
        "goal",
        "imu",
        "imu_bias",
        "imu_noise",
        "latest",
        "lidar",
        "n_out",
        "out_compass",
        "out_encoders",
        "out_imu",
        "pending",
        "poses",
        "prev",
        "rates",
        "scanner",
        "scans",
        "sim",
        "slip_z",
        "stats",
        "steps",
        "times",
    )

    def __init__(self, sim: Simulation) -> None:
        self.sim = sim
        s = sim._start
        robot = sim._robot
        self.body = Body(robot, s.x, s.y, s.theta)
        self.dt = 1.0 / sim._rate
        self.scanner = Scanner(robot.lidar, sim._world) if robot.lidar is not None else None
        # The run's own work arrays for the moving obstacles, which the kernel places at
        # every step: the world may be shared (its queries, other runs in other threads).
        self.dyn_segs = np.empty_like(sim._world._dyn_base_segs)
        self.dyn_circles = np.empty_like(sim._world._dyn_base_circles)
        rate = sim._rate
        self.lidar = _Stream(robot.lidar.latency, 0, rate) if robot.lidar is not None else None
        enc, cmp, imu = robot.encoders, robot.compass, robot.imu
        self.encoders = _Stream(enc.latency, 1, rate) if enc is not None else None
        self.compass = _Stream(cmp.latency, 2, rate) if cmp is not None else None
        self.imu = _Stream(imu.latency, 3, rate) if imu is not None else None
        self.rates = np.array(
            [0.0 if x is None else x.rate for x in (robot.encoders, robot.compass, robot.imu)]
        )
        self.counts = np.zeros(3, dtype=np.int64)
        enc = robot.encoders
        self.enc_tpr = 1.0 if enc is None else enc.ticks_per_rev
        # The kernel wraps counters in floats, exact up to 52 bits; wider ones (up to 63)
        # are wrapped in int64 when queued, 64-bit ones stay signed (as WheelEncoders.ticks).
        self.enc_span = 0.0 if enc is None or enc.bits is None or enc.bits > 52 else 2.0**enc.bits
        bits = None if enc is None else enc.bits
        self.enc_mask = (1 << bits) - 1 if bits is not None and 52 < bits < 64 else 0
        imu = robot.imu
        self.imu_bias = (
            np.zeros(3)
            if imu is None
            else np.array([imu.gyro_bias, imu.accel_bias, imu.accel_bias])
        )
        self.imu_noise: FloatArray | None = None
        if imu is not None and (imu.gyro_noise > 0.0 or imu.accel_noise > 0.0):
            self.imu_noise = np.array([imu.gyro_noise, imu.accel_noise, imu.accel_noise])
        self.n_out = np.zeros(3, dtype=np.int64)
        # The longest segment: from one control step or scan to the next, and never
        # longer than the run (a very slow controller must not size these by its period).
        steps = _step_count(sim._duration, sim._rate)
        slowest = min(sim._control_rate, robot.lidar.rate if robot.lidar is not None else math.inf)
        span = min(math.ceil(sim._rate / slowest), steps) + 2
        n_wheels = robot.n_wheels
        # What the wheel angles' sums lost to rounding (Kahan), the run's own as the
        # Body is (a Body's angles start at 0 for each run).
        self.carry = np.zeros(n_wheels)
        self.out_encoders = np.zeros((span, 1 + n_wheels))
        self.out_compass = np.zeros((span, 2))
        self.out_imu = np.zeros((span, 4))
        self.slip_z = np.zeros((span, n_wheels))
        # The trace's own arrays, NaN until written (estimates before the first one):
        # grown in place while the run goes on and trimmed in place at its end, they
        # become the Trace's arrays without a copy.
        self.steps = steps
        rows = min(steps + 2, _FIRST_ROWS)
        self.times = np.full(rows, np.nan)
        self.poses = np.full((rows, 3), np.nan)
        self.estimates = np.full((rows, 3), np.nan)
        self.commands = np.full((rows, 3), np.nan)
        self.cmd = np.zeros(3)
        # The start pose counts for the smallest clearance too (the steps measure after
        # each move); collides() already refused a start touching an obstacle.
        self.stats = np.array([sim._world.clearance(robot.footprint, s, t=0.0), math.nan, 0.0, 0.0])
        self.contacts = np.zeros(1024)
        self.prev = np.zeros(3)
        goal = sim._goal
        # x, y, tolerance, heading, its tolerance, and the position decide_goal last
        # found not at the goal (the run kernels' memory of it, NaN until then).
        self.goal = np.full(7, np.nan)
        if goal is not None:
            self.goal[0], self.goal[1], self.goal[2] = goal[0], goal[1], sim._goal_radius
            if goal[2] is not None and sim._goal_yaw_tolerance is not None:
                self.goal[3], self.goal[4] = goal[2], sim._goal_yaw_tolerance
        self.latest: dict[type, Reading] = {}
        self.pending: list[Reading] = []
        self.scans: list[ScanReading] = []
        self.events: list[Event] = []
        # Estimates: the times they changed and the poses, to fill the trace.
        self.est_t: list[float] = []
        self.est_xyt: list[tuple[float, float, float]] = []
        self.filled = 0
        # The wrapped PlanarFusion's pose as three floats, cheaper than a Pose2D. Only
        # for that wrapper: a user's estimator may have an ``xyt`` of its own.
        est = sim._estimator
        self.fast: Callable[[], tuple[float, float, float] | None] | None = (
            est.xyt if isinstance(est, FusionEstimator) else None
        )

    # ------------------------------------------------------------ sensing
    def _segment(self, i0: int, i_end: int, sample_first: bool) -> tuple[int, int]:
        """Run the physics kernel from step ``i0`` to ``i_end`` and queue its readings."""
        sim = self.sim
        world = sim._world
        body = self.body
        robot = sim._robot
        need = i_end + 2
        if need > self.times.shape[0]:
            # By a quarter, in place: a run that ends early (goal, collision) peaks
            # at most that much above its trace. Never past the last step (need <=
            # steps + 2): a run of its full duration ends with arrays of its size.
            rows = self.times.shape[0]
            self._grow(min(max(need, rows + rows // 4), self.steps + 2))
        n = i_end - i0
        # Room for a collision at every step of the segment: Trace.events lists them all.
        need = int(self.stats[STAT_COLLISIONS]) + n + 2
        if self.contacts.shape[0] < need:
            grown_contacts = np.zeros(max(need, 2 * self.contacts.shape[0]))
            grown_contacts[: self.contacts.shape[0]] = self.contacts
            self.contacts = grown_contacts
        if robot.wheel_slip > 0.0 and n > 0:
            self.slip_z[:n] = sim._rng.standard_normal((n, robot.n_wheels))
        self.n_out[:] = 0
        gx0, gy0, h, nx, ny = world._index
        bookkeeping = (
            self.goal, sim._stop_at_goal, sim._end_on_collision,
            self.rates, self.counts, self.n_out, self.enc_tpr, self.enc_span,
            self.out_encoders, self.out_compass, self.out_imu,
            self.times, self.poses, self.commands, self.cmd, self.stats, self.contacts,
            self.prev,
        )  # fmt: skip
        motion = (
            i0, i_end, sim._rate, sample_first,
            body.state, body.wheels, body.angles, self.carry, body.command,
            robot.max_wheel_acceleration, body.radius_factor, robot.wheel_slip,
            self.slip_z, body.forward, body.radius, body.reach, body.sweep,
            body.verts, body.work, world._segs, world._circles, gx0, gy0, h, nx, ny,
            world._cell_start, world._cell_items,
        )  # fmt: skip
        kernel: Callable[..., tuple[int, int]] = run_edge_segment
        grid: tuple[Any, ...] = ()
        if not world._edges_only:
            # (Edges only, no grid and no moving obstacles: the kernel that compiles
            # without their code.)
            gox, goy, gcos, gsin, res = world._occ_frame
            kernel = run_segment
            grid = (
                body.scratch, world._occ, gox, goy, gcos, gsin, res,
                world._mv_path, world._mv_times, world._mv_first, world._mv_count,
                world._mv_after, world._dyn_base_segs, world._dyn_seg_owner,
                self.dyn_segs, world._dyn_base_circles, world._dyn_circle_owner,
                self.dyn_circles,
            )  # fmt: skip
        status, i = kernel(*motion, *grid, *bookkeeping)
        # The kernels remember one position decided here (goal[5:7]), not more: a robot
        # moving among band positions would stop them at each move, but the band is
        # 2**-48 of the tolerance wide and no run found one (review 51: an omni
        # controller chattering through its goal over 1-23 mm tolerances, 360,000
        # steps: no decision; 150 runs 3e4-1e6 m out with tolerances below the
        # coordinates' spacing, where trackers creep ulps around the goal: at most 3
        # decisions a run, none for a position seen before).
        while status == GOAL_UNDECIDED:
            # The robot is on the goal tolerance's band: decided exactly here, then on
            # from that step (its samples and row first), with its slip draws on
            # (motion[:4] is the step range, the rate and sample_first; motion[12] the
            # slip draws).
            if decide_goal(
                i, sim._rate, body.state, self.goal, sim._stop_at_goal, self.stats,
                self.times, self.poses, self.commands, self.cmd,
            ):  # fmt: skip
                status = GOAL
                break
            status, i = kernel(
                i, i_end, sim._rate, True, *motion[4:12], self.slip_z[i - i0 :],
                *motion[13:], *grid, *bookkeeping,
            )  # fmt: skip
        self._queue_proprioceptive()
        return int(status), int(i)

    def _grow(self, rows: int) -> None:
        """Give the trace's arrays ``rows`` rows (more or fewer), the new ones NaN.

        In place (realloc: the old and the new array never both exist, so the
        run's memory peaks at its arrays, not 1.5 times them); a copy where NumPy
        refuses that.
        """
        for name in ("times", "poses", "estimates", "commands"):
            old = getattr(self, name).shape
            shape = (rows, *old[1:])
            try:
                # Without NumPy's reference check, which refuses for references that
                # cannot move the data (a tracer's or debugger's, numpy#11538; the
                # call's own on Python 3.14, numpy#30991, where every growth would
                # then copy). What it guards against, a view of the old memory, does
                # not exist: these arrays leave the run only at its end, as the
                # Trace's, and no view of them outlives the statement making it.
                getattr(self, name).resize(shape, refcheck=False)
            except ValueError:
                grown = np.full(shape, np.nan)
                grown[: min(old[0], rows)] = getattr(self, name)[:rows]
                setattr(self, name, grown)
            else:
                getattr(self, name)[old[0] :] = np.nan

    def _queue_proprioceptive(self) -> None:
        """Noise and delivery times for the readings the kernel took."""
        n_enc, n_cmp, n_imu = self.n_out.tolist()
        if n_enc:
            stream = self.encoders
            assert stream is not None
            rows = self.out_encoders[:n_enc]
            stamps = rows[:, 0].tolist()
            dues = self._dues(stream, rows[:, 0], stamps)
            # Counters wider than 52 bits (and those that never wrap) are wrapped
            # here, in int64: as a 64-bit counter once beyond its range.
            ticks = _int64_counts(rows[:, 1:]).astype(np.int64)
            if self.enc_mask:  # modulo 2**bits in two's complement
                ticks &= self.enc_mask
            for k in range(n_enc):
                stream.line.push_at(dues[k], EncoderReading(stamps[k], ticks[k]))
        if n_cmp:
            c = self.sim._robot.compass
            stream = self.compass
            assert c is not None and stream is not None
            rows = self.out_compass[:n_cmp]
            yaw = rows[:, 1]
            if c.noise > 0.0:
                yaw = yaw - c.noise * self.sim._rng.standard_normal(n_cmp)
            deg = np.degrees(c.north - yaw + c.bias) % 360.0
            deg[deg >= 360.0] = 0.0
            stamps = rows[:, 0].tolist()
            dues = self._dues(stream, rows[:, 0], stamps)
            for k, value in enumerate(deg.tolist()):
                stream.line.push_at(dues[k], CompassReading(stamps[k], value))
        if n_imu:
            imu = self.sim._robot.imu
            stream = self.imu
            assert imu is not None and stream is not None
            rows = self.out_imu[:n_imu]
            values = rows[:, 1:] + self.imu_bias
            if self.imu_noise is not None:
                values += self.sim._rng.standard_normal((n_imu, 3)) * self.imu_noise
            stamps = rows[:, 0].tolist()
            dues = self._dues(stream, rows[:, 0], stamps)
            for k, (w, ax, ay) in enumerate(values.tolist()):
                stream.line.push_at(dues[k], ImuReading(stamps[k], w, ax, ay))

    def _dues(self, stream: _Stream, times: FloatArray, stamps: list[float]) -> list[float]:
        """Delivery times of readings the kernel took at ``times`` (``stamps`` as floats)."""
        if stream.lag == 0:
            return stamps
        rate = self.sim._rate
        # ``times`` are ``i / rate``: times rate is within 3e-9 of i (i <= 1e7, two
        # roundings). The delivery step's time is ``(i + lag) / rate``, as every step's.
        return ((np.rint(times * rate) + stream.lag) / rate).tolist()  # type: ignore[no-any-return]

    def _scan(self, i: int, t: float) -> None:
        assert self.scanner is not None and self.lidar is not None
        state = self.body.state
        scan = self.scanner.scan(
            Pose2D(float(state[0]), float(state[1]), float(state[2])), t, self.sim._rng
        )
        reading = ScanReading(t, scan)
        if self.sim._record_scans:
            self.scans.append(reading)
        self.lidar.line.push_at((i + self.lidar.lag) / self.sim._rate, reading)

    def _deliver(self, t: float) -> None:
        """Hand every reading due by ``t`` to the estimator and the controller's queue."""
        due: list[tuple[float, int, Reading]] = []
        for stream in (self.lidar, self.encoders, self.compass, self.imu):
            if stream is not None:
                for when, reading in stream.line.pop_due(t):
                    due.append((when, stream.rank, reading))
        if not due:
            return
        due.sort(key=lambda item: (item[0], item[1]))
        est = self.sim._estimator
        latest = self.latest
        pending = self.pending
        if est is None:
            for _, _, reading in due:
                latest[type(reading)] = reading
                pending.append(reading)
            return
        last_t = math.nan
        for when, _, reading in due:
            if when != last_t and not math.isnan(last_t):
                # The estimate as of the earlier delivery time: noted before this later
                # reading changes it.
                self._note_estimate(last_t)
            latest[type(reading)] = reading
            pending.append(reading)
            est.observe(when, reading)
            last_t = when
        self._note_estimate(last_t)

    def _note_estimate(self, t: float) -> None:
        est = self.sim._estimator
        assert est is not None
        xyt: tuple[float, float, float] | None
        if self.fast is not None:
            xyt = self.fast()
        else:
            pose = est.pose
            if pose is None:
                return
            if not isinstance(pose, Pose2D):
                raise TypeError(
                    f"estimator.pose must be a Pose2D or None, got {type(pose).__name__}"
                )
            xyt = (pose.x, pose.y, pose.theta)
        if xyt is None:
            return
        if self.est_t and self.est_t[-1] == t:
            self.est_xyt[-1] = xyt
        else:
            self.est_t.append(t)
            self.est_xyt.append(xyt)

    def _fill_estimates(self, last: int) -> None:
        """Write the estimates into trace rows ``filled .. last``."""
        est_t = self.est_t
        if est_t and last >= self.filled:
            estimates = self.estimates
            rate = self.sim._rate
            k = 0
            n = len(est_t)
            for i in range(self.filled, last + 1):
                t = i / rate + _EPS
                while k + 1 < n and est_t[k + 1] <= t:
                    k += 1
                if est_t[k] <= t:
                    estimates[i] = self.est_xyt[k]
            # Keep only the last estimate: later rows never look further back.
            del est_t[:-1]
            del self.est_xyt[:-1]
        self.filled = max(self.filled, last + 1)

    # ------------------------------------------------------------ control
    def _control(self, i: int, t: float, hold: int) -> bool:
        """Run the controller for a command held ``hold`` steps; True when it says it is done."""
        sim = self.sim
        state = self.body.state
        latest = self.latest
        estimate: Pose2D | None = None
        if self.est_xyt:
            ex, ey, eth = self.est_xyt[-1]
            estimate = Pose2D(ex, ey, eth)
        obs = Observation(
            t,
            latest.get(ScanReading),  # type: ignore[arg-type]
            latest.get(EncoderReading),  # type: ignore[arg-type]
            latest.get(CompassReading),  # type: ignore[arg-type]
            latest.get(ImuReading),  # type: ignore[arg-type]
            tuple(self.pending),
            estimate,
            Pose2D(float(state[0]), float(state[1]), float(state[2])),
            # Counted in steps, as the times are: a difference of times is off the
            # decimal (0.15 - 0.1 is 0.04999999999999999).
            hold / sim._rate,
        )
        self.pending.clear()
        out = sim._controller(obs)
        if out is None:
            raise TypeError("the controller returned None; it must return a Twist2D")
        twist = as_twist(out, "controller output")
        self.body.set_command(twist)
        self.cmd[0] = twist.vx
        self.cmd[1] = twist.vy
        self.cmd[2] = twist.omega
        self.commands[i] = self.cmd
        controller: Any = sim._controller
        on_type = getattr(type(controller), "done", None)
        if on_type is not None and not isinstance(on_type, MemberDescriptorType):
            # A property (or class attribute): an AttributeError from inside it (a typo
            # in the property) is the user's bug, not "no done" ending nothing silently.
            done = controller.done
        else:
            done = getattr(controller, "done", False)
        return done_flag(done, "the controller's done")

    # ------------------------------------------------------------------ loop
    def execute(self) -> Trace:
        sim = self.sim
        robot = sim._robot
        dt = self.dt
        rate = sim._rate
        n_steps = _step_count(sim._duration, rate)
        control_k = 0
        next_control = 0
        lidar_k = 0
        next_lidar = 0 if robot.lidar is not None else n_steps + 1
        wall_start = time.perf_counter()
        reason = ""
        if sim._estimator is not None:
            # An estimator initialised at the start has a pose before its first reading
            # arrives (late, with latency): the controller and the trace see it from t = 0.
            self._note_estimate(0.0)
        # Step 0: sample the start.
        self._segment(0, 0, True)
        i = 0
        while True:
            # Not i * dt, which is 0.30000000000000004 at step 3 of 10 Hz: users print
            # and compare these times (the kernel's are i / rate too).
            t = i / rate
            if i == 0 and self._at_start_goal():
                reason = "goal reached"
            if not reason:
                if i == next_lidar:
                    self._scan(i, t)
                    lidar_k += 1
                    assert robot.lidar is not None
                    next_lidar = due_step(lidar_k, robot.lidar.rate, dt)
                self._deliver(t)
                if i == next_control:
                    control_k += 1
                    next_control = due_step(control_k, sim._control_rate, dt)
                    if self._control(i, t, next_control - i):
                        reason = "controller done"
                        self.events.append(Event(t, reason, "the controller reported done"))
            if not reason and i >= n_steps:
                reason = "timeout"
                self.events.append(
                    Event(t, reason, f"the run reached its duration of {sim._duration:g} s")
                )
            if (
                not reason
                and sim._wall_timeout is not None
                and time.perf_counter() - wall_start > sim._wall_timeout
            ):
                reason = "wall-clock timeout"
                self.events.append(
                    Event(t, reason, f"the run took more than {sim._wall_timeout:g} s of real time")
                )
            self._fill_estimates(i)
            if reason:
                break
            target = min(next_control, next_lidar, n_steps)
            status, i = self._segment(i, target, False)
            if status == COLLIDED:
                reason = "collision"
            elif status == GOAL:
                reason = "goal reached"
            if reason:
                # Readings due before the last step still reach the estimator.
                self._deliver((i - 1) / rate)
                self._fill_estimates(i)
                break
        return self._trace(i, reason)

    def _at_start_goal(self) -> bool:
        state = self.body.state
        g = self.goal
        # The controllers' own test, as the run kernel's (review 48).
        if math.isnan(g[0]) or not at_goal(
            float(state[0]), float(state[1]), float(g[0]), float(g[1]), float(g[2])
        ):
            return False
        if not math.isnan(g[3]) and abs(wrap_float(float(state[2]) - float(g[3]))) > g[4]:
            return False
        self.stats[STAT_TIME_TO_GOAL] = 0.0
        return self.sim._stop_at_goal

    def _trace(self, last: int, reason: str) -> Trace:
        sim = self.sim
        stats = self.stats
        n_contacts = int(stats[STAT_COLLISIONS])
        for k in range(min(n_contacts, self.contacts.shape[0])):
            tc = float(self.contacts[k])
            self.events.append(Event(tc, "collision", "the footprint touched an obstacle"))
        time_to_goal = float(stats[STAT_TIME_TO_GOAL])
        if not math.isnan(time_to_goal):
            self.events.append(Event(time_to_goal, "goal reached", "the robot reached the goal"))
        # At equal times the end of the run comes last: a collision or the goal at the
        # final step happened before the run was stopped there.
        self.events.sort(key=lambda e: (e.t, e.kind in _CLOSING_KINDS))
        self._grow(last + 1)
        times, poses, estimates, commands = self.times, self.poses, self.estimates, self.commands
        goal = sim._goal
        final = poses[-1]
        final_est = estimates[-1]
        if goal is not None:
            final_error = math.hypot(final[0] - goal[0], final[1] - goal[1])
            final_error_est = math.hypot(final_est[0] - goal[0], final_est[1] - goal[1])
        else:
            final_error = final_error_est = math.nan
        if sim._reference is not None:
            xte = cross_track(poses[:, :2], sim._reference)
            xte_mean, xte_max = nan_if_empty(xte, "mean"), nan_if_empty(xte, "max")
            del xte
        else:
            xte_mean = xte_max = math.nan
        steps = np.diff(poses[:, :2], axis=0)
        metrics = Metrics(
            reached=not math.isnan(time_to_goal),
            reason=reason,
            duration=float(times[-1]),
            time_to_goal=time_to_goal,
            final_error=final_error,
            final_error_estimated=final_error_est,
            estimate_error=math.hypot(final_est[0] - final[0], final_est[1] - final[1]),
            cross_track_mean=xte_mean,
            cross_track_max=xte_max,
            min_clearance=max(float(stats[STAT_MIN_CLEARANCE]), 0.0),
            collisions=n_contacts,
            distance=float(np.sum(np.hypot(steps[:, 0], steps[:, 1]))),
        )
        del steps
        # The run's own arrays, handed over: copies would double the run's peak memory.
        return adopted_trace(
            times, poses, estimates, commands, tuple(self.scans), tuple(self.events), metrics
        )
