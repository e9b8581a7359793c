"""The ON-OFF waypoint tracker (the indoor-navigation paper's controller)."""

from __future__ import annotations

import math
import warnings
from typing import Literal

from navkit._shared.deprecation import renamed_keyword
from navkit._shared.validation import finite_float
from navkit.control._goal import at_goal
from navkit.control._path_following import (
    PathState,
    PathTracker,
    Phase,
    Polyline,
    body_velocity,
    bounded,
    wrap,
)
from navkit.geometry import Pose2D, Twist2D

__all__ = ["OnOffTracker"]

_ROTATE_ANGLE = math.radians(10.0)


def _renamed_property(old: str, new: str) -> None:
    """Warn that the property ``old`` was read (stacklevel: the reader's line)."""
    warnings.warn(
        f"OnOffTracker.{old} is deprecated and will be removed in a future release: use {new}",
        DeprecationWarning,
        stacklevel=3,
    )


class _WaypointState(PathState):
    """:class:`PathState` and the index of the waypoint approached (``waypoint``)."""

    __slots__ = ("waypoint",)

    def __init__(self, line: Polyline | None, goal_heading: float | None, phase: Phase) -> None:
        super().__init__(line, goal_heading, phase)
        self.waypoint = 0


class OnOffTracker(PathTracker[_WaypointState]):
    """ON-OFF waypoint tracker: turn in place, or drive straight, never both.

    The path's points are waypoints taken in order. For each one, a
    differential robot (``drive="diff"``) at every step:

    * **rotate** — while its heading error to the waypoint is at least
      ``rotate_angle`` (10°), turns in place at ``rotate_omega``;
    * **track** — otherwise drives straight (``omega = 0``) at ``max_speed``;

    and takes the next waypoint once within ``goal_tolerance`` (0.05 m) of this
    one. After the last waypoint it turns in place at ``rotate_omega`` to the goal
    heading (phase **final**, if :meth:`set_path` was given one) until within
    ``yaw_tolerance``; then :attr:`done`.

    An omnidirectional robot (``drive="omni"``) never turns on the way: it
    translates straight toward the waypoint at ``max_speed`` (``omega = 0``), and
    turns to the goal heading at the end.

    No command overshoots within one step: a turn is at most ``|error| / dt``,
    the speed at most ``distance / dt`` to the waypoint (both only bind when a
    step would otherwise pass the target).

    Give the path with :meth:`set_path`, then call :meth:`step` once per
    control period.

    Parameters
    ----------
    max_speed : float, default 0.2
        Driving speed (m/s), in (0, 100].
    rotate_omega : float, default 0.5
        In-place turn rate (rad/s), in (0, 100].
    rotate_angle : float, default 10° (0.1745 rad)
        Heading error (rad) to the waypoint from which the robot turns in place
        (below it, it drives), in (0, π/2).
    goal_tolerance : float, default 0.05
        Distance (m) at which a waypoint (the last one included) is reached, in
        (0, 1e4].
    yaw_tolerance : float, default 0.01
        Heading error (rad) at which the goal heading is reached, in (0, π].
    drive : {"diff", "omni"}, default "diff"
        Differential (``vy = 0``) or omnidirectional robot (the default of
        every path tracker; ``PotentialFieldController``'s is ``"omni"``).

    Other Parameters
    ----------------
    speed : float, optional
        Deprecated name of `max_speed`.
    turn_rate : float, optional
        Deprecated name of `rotate_omega`.
    heading_tolerance : float, optional
        Deprecated name of `rotate_angle`.

    Notes
    -----
    Driving with a heading error just under ``β = rotate_angle`` the robot
    spirals onto the waypoint; its distance from the line of sight it started
    on is at most ``r₀ sin β · exp(−β / tan β)`` (6.45 % of the start distance
    ``r₀`` for β = 10°). So on a segment of length ``ℓ`` the robot stays within
    ``tol + (ℓ + tol) sin β · exp(−β / tan β)`` of it, ``tol`` the goal tolerance.

    The goal tolerance is met only as closely as the robot follows the
    commands, which are dead-beat for a robot that does so exactly: on exact
    wheels the tracker is done within 1e-9 m (in a
    :class:`~navkit.sim.Simulation`, also 1e6 m from the origin). The last
    drive toward a waypoint leaves the robot up to ``sin β`` of the distance
    to one side, and the turn in place that corrects it moves a real robot:
    slipping wheels carry its centre sideways by half the track times their
    unequal slips, turned through the angle, and wheels with an acceleration
    limit go on turning or rolling after the command stops. Below the
    distance such a turn moves it, the robot turns and creeps about the
    waypoint for ever, never done. A ``Simulation`` of a 0.3 m track, 20 Hz,
    ten starts 2 to 4 m away, 120 s runs: with ``wheel_slip=0.05`` each turn
    moved it micrometres to tenths of a millimetre, done at 1e-5 m (some runs
    only after a minute of turning and creeping, when a drive happened to
    end within it) and never at 1e-6 m (``wheel_slip=0.01``: the same;
    0.001: done at 1e-6 m); with ``max_wheel_acceleration=20`` rad/s², done
    at 1e-3 m and never at 1e-4 m (200 rad/s²: done at 1e-4 m). The tracker
    cannot know its robot's slip or acceleration, so it refuses no tolerance
    for them: give one the robot can hold (the odometry or localisation it
    steers by is rarely better than millimetres; Nav2's goal checker's
    default is 0.25 m). :class:`~navkit.control.FollowTheCarrot`, which
    steers while it drives, met 1e-6 m with ``wheel_slip=0.05``.

    A tracker takes one :meth:`step` at a time: a step called while another
    is under way (another thread's, or a signal handler's) raises
    ``RuntimeError``, saying which, and changes nothing; the step under way
    goes on as alone (the check costs about 0.2 µs of a 2.5 to 6.5 µs step).
    A :meth:`set_path` and a :meth:`step` overlapping (from another thread or
    a signal handler) are safe: :meth:`set_path` installs the new path's state
    whole, and a step works on the state it read as it began, so its command is
    for the old path (the new one, had the :meth:`set_path` come first) and the
    next step follows the new path from its start. In a ROS 2 node the path
    subscription may run in a callback group of its own; the control timer's
    must not let its callback overlap itself (mutually exclusive, the default),
    or its overlapping steps are refused. Different trackers may run in
    different threads at once.

    Subclasses may add attributes (their own ``__slots__`` or an instance
    ``__dict__``) and methods, and override the public methods, calling the
    base's through ``super()``: the base's methods call none of the public
    ones, so an override changes only its own callers. Copies and pickles
    rebuild a subclass as itself, with what it adds (its ``__init__`` is not
    called), and ``repr`` names it. A tracker of a new kind cannot be written
    this way: the hooks each step calls (``_command`` and the like) belong to
    a private base class and, as every name with a leading underscore, may
    change in any release.

    Raises
    ------
    ValueError
        An option outside its range, naming it.
    TypeError
        A non-numeric option.

    Examples
    --------
    >>> from navkit.geometry import integrate
    >>> tracker = OnOffTracker()
    >>> tracker.set_path([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]])
    >>> pose = Pose2D(0.0, 0.0, 0.0)
    >>> while not tracker.done:
    ...     pose = integrate(pose, tracker.step(pose, 0.05), 0.05)
    >>> math.hypot(pose.x - 1.0, pose.y - 1.0) <= 0.05
    True
    """

    # The private names predate the option renames; kept so that pickles load.
    __slots__ = ("_heading_tolerance", "_speed", "_turn_rate")

    def __init__(
        self,
        *,
        max_speed: float = 0.2,
        rotate_omega: float = 0.5,
        rotate_angle: float = _ROTATE_ANGLE,
        goal_tolerance: float = 0.05,
        yaw_tolerance: float = 0.01,
        drive: Literal["diff", "omni"] = "diff",
        speed: float | None = None,
        turn_rate: float | None = None,
        heading_tolerance: float | None = None,
    ) -> None:
        # The names every tracker shares (docs/guides/control.md); the old ones warn,
        # and errors name the keyword the caller wrote.
        speed_name = "max_speed" if speed is None else "speed"
        omega_name = "rotate_omega" if turn_rate is None else "turn_rate"
        angle_name = "rotate_angle" if heading_tolerance is None else "heading_tolerance"
        max_speed = renamed_keyword("speed", speed, "max_speed", max_speed, 0.2)
        rotate_omega = renamed_keyword("turn_rate", turn_rate, "rotate_omega", rotate_omega, 0.5)
        rotate_angle = renamed_keyword(
            "heading_tolerance", heading_tolerance, "rotate_angle", rotate_angle, _ROTATE_ANGLE
        )
        super().__init__(drive=drive, goal_tolerance=goal_tolerance, yaw_tolerance=yaw_tolerance)
        self._speed = bounded(max_speed, speed_name, 0.0, 100.0)
        self._turn_rate = bounded(rotate_omega, omega_name, 0.0, 100.0)
        angle = finite_float(rotate_angle, angle_name)
        if not 0.0 < angle < math.pi / 2:
            raise ValueError(f"{angle_name} must be in (0, π/2), got {angle}")
        self._heading_tolerance = angle

    def __repr__(self) -> str:
        # Every option, as the planners and estimators print theirs (eval gives a twin).
        return (
            f"{type(self).__name__}(max_speed={self._speed}, rotate_omega={self._turn_rate}, "
            f"rotate_angle={self._heading_tolerance}, goal_tolerance={self._goal_tolerance}, "
            f"yaw_tolerance={self._yaw_tolerance}, drive={self._drive!r})"
        )

    @property
    def max_speed(self) -> float:
        """Driving speed (m/s)."""
        return self._speed

    @property
    def rotate_omega(self) -> float:
        """In-place turn rate (rad/s)."""
        return self._turn_rate

    @property
    def rotate_angle(self) -> float:
        """Heading error (rad) to the waypoint from which the robot turns in place."""
        return self._heading_tolerance

    @property
    def speed(self) -> float:
        """Deprecated alias of :attr:`max_speed`.

        Examples
        --------
        >>> OnOffTracker(max_speed=0.3).max_speed  # not .speed, which warns
        0.3
        """
        _renamed_property("speed", "max_speed")
        return self._speed

    @property
    def turn_rate(self) -> float:
        """Deprecated alias of :attr:`rotate_omega`.

        Examples
        --------
        >>> OnOffTracker(rotate_omega=1.5).rotate_omega  # not .turn_rate, which warns
        1.5
        """
        _renamed_property("turn_rate", "rotate_omega")
        return self._turn_rate

    @property
    def heading_tolerance(self) -> float:
        """Deprecated alias of :attr:`rotate_angle`.

        Examples
        --------
        >>> OnOffTracker(rotate_angle=0.25).rotate_angle  # not .heading_tolerance, which warns
        0.25
        """
        _renamed_property("heading_tolerance", "rotate_angle")
        return self._heading_tolerance

    @property
    def waypoint(self) -> int:
        """Index in :attr:`path_xy` of the waypoint being approached (its length when all
        are reached)."""
        return self._state.waypoint

    def _new_state(
        self, line: Polyline | None, goal_heading: float | None, phase: Phase
    ) -> _WaypointState:
        return _WaypointState(line, goal_heading, phase)

    def _turn(self, err: float, dt: float) -> float:
        return math.copysign(min(self._turn_rate, abs(err) / dt), err)

    def _command(
        self,
        state: _WaypointState,
        line: Polyline,
        pose: Pose2D,
        dt: float,
        measured: Twist2D | None,
    ) -> Twist2D:
        pts = line.points_xy
        k = pts.shape[0]
        i = state.waypoint
        while i < k and at_goal(
            pose.x, pose.y, float(pts[i, 0]), float(pts[i, 1]), self._goal_tolerance
        ):
            i += 1
        state.waypoint = i
        if i == k:
            state.progress = line.length
            state.target = (float(pts[-1, 0]), float(pts[-1, 1]))
            return self._finish(state, pose, dt, self._turn)
        tx = float(pts[i, 0])
        ty = float(pts[i, 1])
        state.target = (tx, ty)
        state.progress = float(line.cum[i - 1]) if i > 0 else 0.0
        dx = tx - pose.x
        dy = ty - pose.y
        dist = math.hypot(dx, dy)
        speed = min(self._speed, dist / dt)
        if self._drive == "omni":
            state.phase = "track"
            vx, vy = body_velocity(dx * speed / dist, dy * speed / dist, pose.theta)
            return Twist2D(vx, vy, 0.0)
        err = wrap(math.atan2(dy, dx) - pose.theta)
        if abs(err) >= self._heading_tolerance:
            state.phase = "rotate"
            return Twist2D(0.0, 0.0, self._turn(err, dt))
        state.phase = "track"
        return Twist2D(speed, 0.0, 0.0)
