"""The ON-OFF waypoint tracker (the indoor-navigation paper's controller)."""

from __future__ import annotations

import math
from typing import Literal

from navkit._shared.validation import finite_float
from navkit.control._path_following import (
    PathTracker,
    Polyline,
    body_velocity,
    bounded,
    wrap,
)
from navkit.geometry import Pose2D, Twist2D

__all__ = ["OnOffTracker"]


class OnOffTracker(PathTracker):
    """ON-OFF waypoint tracker: turn in place, or drive straight, never both.

    The path's points are waypoints taken in order. For each one, a
    differential robot (``drive="diff"``) at every step:

    * **rotate** — while its heading error to the waypoint is at least
      ``heading_tolerance`` (10°), turns in place at ``turn_rate``;
    * **track** — otherwise drives straight (``omega = 0``) at ``speed``;

    and takes the next waypoint once within ``goal_tolerance`` (0.05 m) of this
    one. After the last waypoint it turns in place at ``turn_rate`` to the goal
    heading (phase **final**, if :meth:`set_path` was given one) until within
    ``yaw_tolerance``; then :attr:`done`.

    An omnidirectional robot (``drive="omni"``) never turns on the way: it
    translates straight toward the waypoint at ``speed`` (``omega = 0``), and
    turns to the goal heading at the end.

    No command overshoots within one step: a turn is at most ``|error| / dt``,
    the speed at most ``distance / dt`` to the waypoint (both only bind when a
    step would otherwise pass the target).

    Give the path with :meth:`set_path`, then call :meth:`step` once per
    control period.

    Parameters
    ----------
    speed : float, default 0.2
        Driving speed (m/s), in (0, 100].
    turn_rate : float, default 0.5
        In-place turn rate (rad/s), in (0, 100].
    heading_tolerance : float, default 10° (0.1745 rad)
        Heading error (rad) to the waypoint below which the robot drives, in
        (0, π/2).
    goal_tolerance : float, default 0.05
        Distance (m) at which a waypoint (the last one included) is reached, in
        (0, 1e4].
    yaw_tolerance : float, default 0.01
        Heading error (rad) at which the goal heading is reached, in (0, π].
    drive : {"diff", "omni"}, default "diff"
        Differential (``vy = 0``) or omnidirectional robot.

    Notes
    -----
    Driving with a heading error just under ``β = heading_tolerance`` the robot
    spirals onto the waypoint; its distance from the line of sight it started
    on is at most ``r₀ sin β · exp(−β / tan β)`` (6.45 % of the start distance
    ``r₀`` for β = 10°). So on a segment of length ``ℓ`` the robot stays within
    ``tol + (ℓ + tol) sin β · exp(−β / tan β)`` of it, ``tol`` the goal tolerance.

    A tracker is not thread-safe: one thread at a time may call its methods
    (:meth:`set_path`, :meth:`step`); different trackers may run in different
    threads at once.

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

    __slots__ = ("_heading_tolerance", "_speed", "_turn_rate", "_waypoint")

    def __init__(
        self,
        *,
        speed: float = 0.2,
        turn_rate: float = 0.5,
        heading_tolerance: float = math.radians(10.0),
        goal_tolerance: float = 0.05,
        yaw_tolerance: float = 0.01,
        drive: Literal["diff", "omni"] = "diff",
    ) -> None:
        super().__init__(drive=drive, goal_tolerance=goal_tolerance, yaw_tolerance=yaw_tolerance)
        self._speed = bounded(speed, "speed", 0.0, 100.0)
        self._turn_rate = bounded(turn_rate, "turn_rate", 0.0, 100.0)
        tolerance = finite_float(heading_tolerance, "heading_tolerance")
        if not 0.0 < tolerance < math.pi / 2:
            raise ValueError(f"heading_tolerance must be in (0, π/2), got {tolerance}")
        self._heading_tolerance = tolerance
        self._waypoint = 0

    @property
    def speed(self) -> float:
        """Driving speed (m/s)."""
        return self._speed

    @property
    def turn_rate(self) -> float:
        """In-place turn rate (rad/s)."""
        return self._turn_rate

    @property
    def heading_tolerance(self) -> float:
        """Heading error (rad) to the waypoint below which the robot drives."""
        return self._heading_tolerance

    @property
    def waypoint(self) -> int:
        """Index in :attr:`path_xy` of the waypoint being approached (its length when all
        are reached)."""
        return self._waypoint

    def _reset(self) -> None:
        self._waypoint = 0

    def _turn(self, err: float, dt: float) -> float:
        return math.copysign(min(self._turn_rate, abs(err) / dt), err)

    def _command(
        self, line: Polyline, pose: Pose2D, dt: float, measured: Twist2D | None
    ) -> Twist2D:
        pts = line.points_xy
        k = pts.shape[0]
        i = self._waypoint
        while i < k and math.hypot(pts[i, 0] - pose.x, pts[i, 1] - pose.y) <= self._goal_tolerance:
            i += 1
        self._waypoint = i
        if i == k:
            self._progress = line.length
            self._target = (float(pts[-1, 0]), float(pts[-1, 1]))
            return self._finish(pose, dt, self._turn)
        tx = float(pts[i, 0])
        ty = float(pts[i, 1])
        self._target = (tx, ty)
        self._progress = float(line.cum[i - 1]) if i > 0 else 0.0
        dx = tx - pose.x
        dy = ty - pose.y
        dist = math.hypot(dx, dy)
        speed = min(self._speed, dist / dt)
        if self._drive == "omni":
            self._phase = "track"
            vx, vy = body_velocity(dx * speed / dist, dy * speed / dist, pose.theta)
            return Twist2D(vx, vy, 0.0)
        err = wrap(math.atan2(dy, dx) - pose.theta)
        if abs(err) >= self._heading_tolerance:
            self._phase = "rotate"
            return Twist2D(0.0, 0.0, self._turn(err, dt))
        self._phase = "track"
        return Twist2D(speed, 0.0, 0.0)
