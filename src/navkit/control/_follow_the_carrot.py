"""Follow-the-carrot path tracking (the differential-drive delivery robot's tracker)."""

from __future__ import annotations

import math
from typing import Literal

import numpy as np

from navkit._shared.deprecation import renamed_keyword
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

__all__ = ["FollowTheCarrot"]

# Folds of a path through the robot passed at one step (see _command), as
# RegulatedPurePursuit's: a bound, so that the search always ends.
_MAX_FOLDS = 64

# The shortest carrot distance a path takes, relative to its extent (its length or
# its largest coordinate): 2**6 float steps at that magnitude, so that the carrot,
# computed by arc length and interpolation, is never the robot's own closest point.
_CARROT_RESOLUTION = 2.0**-46

# The spacing of float64 headings just below π (4.4e-16 rad): a turn of less in one
# step may leave the heading where it was (see FollowTheCarrot._final_turn).
_HEADING_RESOLUTION = math.ulp(math.pi)


class _CarrotState(PathState):
    """:class:`PathState` and the arc length of the last carrot (``carrot_s``)."""

    __slots__ = ("carrot_s",)

    def __init__(self, line: Polyline | None, goal_heading: float | None, phase: Phase) -> None:
        super().__init__(line, goal_heading, phase)
        self.carrot_s = 0.0


class FollowTheCarrot(PathTracker[_CarrotState]):
    """Follow-the-carrot path tracker in three phases.

    The carrot is the point ``carrot_distance`` further along the path (by arc
    length) than the robot's closest point on it, the path's last point once
    fewer than ``carrot_distance`` metres are left. A differential robot
    (``drive="diff"``):

    1. **rotate** — turns in place toward the carrot until its heading error is
       at most ``align_tolerance`` (at the start, and again whenever the error
       exceeds ``rotate_angle``, e.g. at a sharp corner);
    2. **track** — drives at ``max_speed`` while turning at
       ``heading_gain × error`` (limited to ``max_omega``) toward the carrot;
    3. **final** — once within ``goal_tolerance`` of the goal (the carrot on
       it, so the start of a closed path does not count), turns in place to
       the goal heading (if :meth:`set_path` was given one) until within
       ``yaw_tolerance``; then :attr:`done`.

    An omnidirectional robot (``drive="omni"``) skips phase 1: it translates
    straight toward the carrot at ``max_speed`` without turning (``omega = 0``)
    and turns to the goal heading in phase 3.

    In-place turns command ``heading_gain × error`` limited to ``max_omega``.
    No command overshoots within one step: the turn rate is at most
    ``|error| / dt`` and the speed at most ``distance / dt`` to the carrot.

    Give the path with :meth:`set_path` (every navkit tracker takes its path
    that way, so one tracker follows successive replans), then call
    :meth:`step` once per control period.

    Parameters
    ----------
    carrot_distance : float, default 0.3
        Arc length (m) from the robot's closest path point to the carrot, in
        (0, 1e4]. :meth:`set_path` refuses a path whose extent (its length or
        its largest coordinate, whichever is larger) exceeds ``2**46`` carrot
        distances (7e13: 1.4e-5 m for coordinates of 1e9 m): a carrot that
        near rounds onto the robot's own closest point, and the robot, steered
        to where it stands, never moves.
    max_speed : float, default 0.18
        Forward speed (m/s) while tracking, in (0, 100].
    max_omega : float, default 1.5
        Largest turn rate (rad/s), in (0, 100].
    goal_tolerance : float, default 0.05
        Distance (m) to the path's last point at which the goal position is
        reached, in (0, 1e4].
    yaw_tolerance : float, default 0.01
        Heading error (rad) at which the goal heading is reached, in (0, π].
        A tolerance near the resolution of float64 headings (4.4e-16 rad at
        ±π) is met too: once the proportional turn of one step would be
        smaller than that, the rest of the error is turned in that step.
    heading_gain : float, default 3.0
        Turn rate per radian of heading error (1/s), in (0, 1e6]. With the
        default speed and carrot distance the lateral error is overdamped
        (poles −0.8 and −2.2 s⁻¹ of ``s² + k s + k v / d``).
    rotate_angle : float, default π/4
        Heading error (rad) to the carrot above which a differential robot stops
        and turns in place, in (0, π]. Below π/2 the robot cannot orbit the
        goal: it always closes in on it while driving.
    align_tolerance : float, default 0.1
        Heading error (rad) at which an in-place turn toward the path ends, in
        (0, ``rotate_angle``].
    drive : {"diff", "omni"}, default "diff"
        Differential (``vy = 0``) or omnidirectional robot (the default of
        every path tracker; ``PotentialFieldController``'s is ``"omni"``).

    Other Parameters
    ----------------
    align_angle : float, optional
        Deprecated name of `rotate_angle`.

    Notes
    -----
    The delivery robot paper's settings are the defaults: carrot distance
    0.3 m, 0.18 m/s, 1.5 rad/s, goal tolerance 0.05 m, yaw tolerance 0.01 rad.
    On a circle of radius ``R`` the carrot, ``d`` ahead by arc length, is a
    chord's end, and the robot settles inside the circle by at most
    ``R (1 − cos(d / R))`` (4.5 cm for ``R = 1`` m, ``d = 0.3`` m; 2.6 cm with
    the default gain and speed). With a lower ``heading_gain × R / max_speed``
    it settles nearer the circle, or just outside it (0.5 cm with
    ``max_speed=0.5``).

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
        An option outside its range, naming it; from :meth:`set_path`, a
        ``carrot_distance`` too short for the path, naming it.
    TypeError
        A non-numeric option.

    Examples
    --------
    >>> from navkit.geometry import integrate
    >>> tracker = FollowTheCarrot()
    >>> tracker.set_path([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]], goal_yaw=math.pi / 2)
    >>> pose = Pose2D(0.0, 0.05, 0.0)
    >>> while not tracker.done:
    ...     pose = integrate(pose, tracker.step(pose, 0.05), 0.05)
    >>> math.hypot(pose.x - 1.0, pose.y - 1.0) <= 0.05, abs(pose.theta - math.pi / 2) <= 0.01
    (True, True)
    """

    # _align_angle holds rotate_angle: the private name predates the rename (pickles).
    __slots__ = (
        "_align_angle",
        "_align_tolerance",
        "_carrot_distance",
        "_heading_gain",
        "_max_omega",
        "_max_speed",
    )

    def __init__(
        self,
        *,
        carrot_distance: float = 0.3,
        max_speed: float = 0.18,
        max_omega: float = 1.5,
        goal_tolerance: float = 0.05,
        yaw_tolerance: float = 0.01,
        heading_gain: float = 3.0,
        rotate_angle: float = math.pi / 4,
        align_tolerance: float = 0.1,
        drive: Literal["diff", "omni"] = "diff",
        align_angle: float | None = None,
    ) -> None:
        # The name every tracker shares (docs/guides/control.md); the old one warns,
        # and errors name the keyword the caller wrote.
        angle_name = "rotate_angle" if align_angle is None else "align_angle"
        rotate_angle = renamed_keyword(
            "align_angle", align_angle, "rotate_angle", rotate_angle, math.pi / 4
        )
        super().__init__(drive=drive, goal_tolerance=goal_tolerance, yaw_tolerance=yaw_tolerance)
        self._carrot_distance = bounded(carrot_distance, "carrot_distance", 0.0, 1e4)
        self._max_speed = bounded(max_speed, "max_speed", 0.0, 100.0)
        self._max_omega = bounded(max_omega, "max_omega", 0.0, 100.0)
        self._heading_gain = bounded(heading_gain, "heading_gain", 0.0, 1e6)
        self._align_angle = bounded(rotate_angle, angle_name, 0.0, math.pi)
        self._align_tolerance = bounded(
            align_tolerance, "align_tolerance", 0.0, self._align_angle
        )

    def __repr__(self) -> str:
        # Every option, as the planners and estimators print theirs (eval gives a twin).
        return (
            f"{type(self).__name__}(carrot_distance={self._carrot_distance}, "
            f"max_speed={self._max_speed}, max_omega={self._max_omega}, "
            f"goal_tolerance={self._goal_tolerance}, yaw_tolerance={self._yaw_tolerance}, "
            f"heading_gain={self._heading_gain}, rotate_angle={self._align_angle}, "
            f"align_tolerance={self._align_tolerance}, drive={self._drive!r})"
        )

    @property
    def carrot_distance(self) -> float:
        """Arc length (m) from the robot's closest path point to the carrot."""
        return self._carrot_distance

    @property
    def max_speed(self) -> float:
        """Forward speed (m/s) while tracking."""
        return self._max_speed

    @property
    def max_omega(self) -> float:
        """Largest turn rate (rad/s)."""
        return self._max_omega

    @property
    def rotate_angle(self) -> float:
        """Heading error (rad) to the carrot above which a differential robot turns in place."""
        return self._align_angle

    def _check_line(self, line: Polyline) -> None:
        # A carrot below the float resolution of the path's arc lengths and points
        # is the robot's own closest point: a command of zero, at every step.
        extent = max(line.length, float(np.max(np.abs(line.points_xy))))
        if self._carrot_distance < extent * _CARROT_RESOLUTION:
            raise ValueError(
                f"carrot_distance {self._carrot_distance} m is too short for this path: "
                f"below 2**-46 ({extent * _CARROT_RESOLUTION:.3g} m) of its extent "
                f"{extent:g} m (its length or largest coordinate), the carrot would round "
                "onto the robot's own closest point and the robot would not move; use a "
                "longer carrot_distance"
            )

    def _new_state(
        self, line: Polyline | None, goal_heading: float | None, phase: Phase
    ) -> _CarrotState:
        return _CarrotState(line, goal_heading, phase)

    def _start_phase(self) -> Phase:
        # A differential robot first turns to face the path (phase 1).
        return "rotate" if self._drive == "diff" else "track"

    def _turn(self, err: float, dt: float) -> float:
        rate = min(self._heading_gain * abs(err), self._max_omega, abs(err) / dt)
        return math.copysign(rate, err)

    def _final_turn(self, err: float, dt: float) -> float:
        omega = self._turn(err, dt)
        if abs(omega) * dt < _HEADING_RESOLUTION:
            # A proportional turn this small is lost when added to a heading near ±π:
            # with a yaw_tolerance near that resolution the robot stopped turning
            # short of it and never finished (review 38). The last bit is turned at
            # once, which lands on the goal yaw itself.
            omega = math.copysign(min(self._max_omega, abs(err) / dt), err)
        return omega

    def _command(
        self,
        state: _CarrotState,
        line: Polyline,
        pose: Pose2D,
        dt: float,
        measured: Twist2D | None,
    ) -> Twist2D:
        # The search for the closest point reaches the last carrot, as documented for
        # progress: with a carrot more than SEARCH_AHEAD ahead, a robot that drove to
        # it would otherwise project behind it, onto the same carrot, and stop there.
        s = self._advance(state, line, pose, state.carrot_s)
        # The carrot as an offset from the robot, subtracted first (and as a point):
        # the command is the same wherever the problem is translated, where the
        # carrot's world coordinates lost 1e-8 rad/s to rounding in a UTM frame.
        dx, dy, cx, cy = line.offset_at(s + self._carrot_distance, pose.x, pose.y)
        folds = 0
        while (
            ((dx == 0.0 and dy == 0.0) or (cx == pose.x and cy == pose.y))
            and s < s + self._carrot_distance < line.length
            and folds < _MAX_FOLDS
        ):
            # The robot stands on the carrot, on a path doubling back through it
            # (closest at s and at the carrot's arc too): its command would be zero
            # at every step. It is at the carrot's arc too: project it there. Bounded,
            # and s must grow: a carrot distance below half an ulp of s left it where
            # it was, and the step never returned. The next step goes on from there.
            s += self._carrot_distance
            state.progress = s
            folds += 1
            dx, dy, cx, cy = line.offset_at(s + self._carrot_distance, pose.x, pose.y)
        state.carrot_s = min(s + self._carrot_distance, line.length)
        gx, gy = line.point_at(line.length)
        near_end = s + self._carrot_distance >= line.length
        if state.phase == "final" or (
            near_end and at_goal(pose.x, pose.y, gx, gy, self._goal_tolerance)
        ):
            state.target = (gx, gy)
            return self._finish(state, pose, dt, self._final_turn)
        state.target = (cx, cy)
        dist = math.hypot(dx, dy)
        speed = min(self._max_speed, dist / dt)
        if self._drive == "omni":
            state.phase = "track"
            if dist == 0.0:
                return Twist2D(0.0, 0.0, 0.0)
            vx, vy = body_velocity(dx * speed / dist, dy * speed / dist, pose.theta)
            return Twist2D(vx, vy, 0.0)
        err = wrap(math.atan2(dy, dx) - pose.theta) if dist > 0.0 else 0.0
        if state.phase == "rotate":
            if abs(err) > self._align_tolerance:
                return Twist2D(0.0, 0.0, self._turn(err, dt))
            state.phase = "track"
        elif abs(err) > self._align_angle:
            state.phase = "rotate"
            return Twist2D(0.0, 0.0, self._turn(err, dt))
        return Twist2D(speed, 0.0, self._turn(err, dt))
