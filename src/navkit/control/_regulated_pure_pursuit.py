"""Regulated Pure Pursuit (Nav2's ``nav2_regulated_pure_pursuit_controller`` semantics)."""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable
from typing import Any, Literal, cast

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.deprecation import renamed_keyword
from navkit._shared.dunders import slot_state
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_bool, refuse_masked
from navkit.control._goal import at_goal
from navkit.control._path_following import (
    PathState,
    PathTracker,
    Phase,
    Polyline,
    body_velocity,
    bounded,
    pursuit_curvature,
    wrap,
)
from navkit.geometry import Pose2D, Twist2D, as_twist
from navkit.mapping import OccupancyGrid

__all__ = ["RegulatedPurePursuit"]

# pursuit_curvature's straight-line zone (d² <= 1e-3 m²) and the widest heading error
# (rad) at which a robot in it drives rather than turns (see _command).
_STRAIGHT_D2 = 1e-3
_STRAIGHT_ANGLE = math.pi / 4
# Folds of a path met at one step (see _command): a bound, so that the search always ends.
_MAX_FOLDS = 64

Clearance = Callable[[float, float], float]


class _GridClearance:
    """Distance (m) from a world point's cell to the nearest occupied cell of a grid.

    Centre to centre, as Nav2 reads its costmap by cell: within resolution/√2
    of the point's own distance to that cell centre.

    The grid's :meth:`~navkit.mapping.OccupancyGrid.obstacle_distance` is
    computed once; a point outside the map, or a map with no occupied cell, is
    infinitely far from obstacles (Nav2 does not regulate on unknown space
    either).
    """

    __slots__ = ("_distance", "_grid")
    __getstate__ = slot_state  # pickle protocols 0 and 1 too

    def __init__(self, grid: OccupancyGrid) -> None:
        self._distance: FloatArray = grid.obstacle_distance()
        self._grid = grid

    def __call__(self, x: float, y: float) -> float:
        r, c = self._grid.world_to_cell(np.array([x, y]))
        rows, cols = self._distance.shape
        if 0 <= r < rows and 0 <= c < cols:
            return float(self._distance[r, c])
        return math.inf


class _PursuitState(PathState):
    """:class:`PathState` and the memory of previous steps.

    ``last``: the previous command ``(vx, vy, omega)``; ``motion_heading``: an
    omnidirectional robot's direction of travel (rad), or None; ``carrot``: the
    previous lookahead point's arc length and lookahead distance, or None.
    """

    __slots__ = ("carrot", "last", "motion_heading")

    def __init__(self, line: Polyline | None, goal_heading: float | None, phase: Phase) -> None:
        super().__init__(line, goal_heading, phase)
        self.last = (0.0, 0.0, 0.0)
        self.motion_heading: float | None = None
        self.carrot: tuple[float, float] | None = None


class RegulatedPurePursuit(PathTracker[_PursuitState]):
    """Regulated Pure Pursuit, with Nav2's semantics and default parameters.

    Each :meth:`step` (Macenski et al., 2023; Nav2's
    ``RegulatedPurePursuitController::computeVelocityCommands``):

    1. **Lookahead.** ``L = |v| × lookahead_time`` clamped to
       ``[min_lookahead, max_lookahead]``, ``v`` the measured forward speed (or
       the previous command's). The lookahead point is the first point along
       the path, from the robot's closest point on, at distance ``L`` from the
       robot (interpolated on its segment); when the whole rest of the path is
       nearer, the point ``L`` further along the path (the goal near the end).
       It never moves back along the path by more than ``L`` shrank since the
       previous step. A lookahead point no farther from the robot than its
       closest point (where the two passes of a path doubling back inside the
       circle meet) is where the robot is too: :attr:`progress` moves there
       and the lookahead point is found again from it.
    2. **Rotate to heading.** When the lookahead point lies more than
       ``rotate_angle`` off the robot's heading (the path points
       sideways or behind), a differential robot turns in place toward it at
       ``rotate_omega``, within ``max_angular_accel`` of its current turn rate
       and slow enough to stop on it (``|ω| <= sqrt(2 a |angle|)``; a robot
       still turning the other way first slows at ``max_angular_accel``, where
       Nav2 would reverse its turn at once) — phase **rotate**. Within 3.2 cm
       of the point (where the arc is a straight line) it turns from 45° off
       (π/4), whatever a wider ``rotate_angle`` and also without
       ``rotate_to_heading``: a straight run more than 60° off would end
       farther from the point (the goal) than it began.
    3. **Track.** Otherwise it drives on the arc through the lookahead point,
       curvature ``κ = 2 y / d²`` (``y`` the point's lateral offset, ``d`` its
       distance, usually ``L``), at
       ``max_speed`` regulated down:

       * by curvature: on an arc of radius ``r < slowdown_radius`` the speed
         is scaled by ``r / slowdown_radius``;
       * by proximity to obstacles, when a ``clearance`` is given: with the
         robot ``c < clearance_distance`` metres from the nearest obstacle, by
         ``clearance_gain × c / clearance_distance``;
       * the lower of the two, but at least ``min_regulated_speed``;
       * approaching the goal: when less than ``approach_distance`` of path is
         left, by (distance to the goal) / ``approach_distance``, but not below
         ``min_approach_speed``;

       then ``ω = v κ``. With ``max_omega`` set, a faster turn is scaled down
       with the speed, keeping the arc.
    4. **Final.** Within ``goal_tolerance`` of the goal (with the lookahead
       point on it) the robot turns in place to the goal heading, as in step 2,
       until within ``yaw_tolerance`` — if :meth:`set_path` was given one; then
       :attr:`done` (Nav2's goal checker).

    An omnidirectional robot (``drive="omni"``) runs the same law for its
    *direction of travel*, a heading the tracker keeps itself (it starts toward
    the first lookahead point, snaps to the lookahead point instead of rotating
    in step 2, and turns by ``v κ dt`` each step): the robot translates along
    the pure-pursuit arcs with ``omega = 0``, without turning first, and turns
    to the goal heading in step 4.

    Give the path with :meth:`set_path`, then call :meth:`step` once per
    control period.

    Parameters
    ----------
    max_speed : float, default 0.5
        Nav2 ``desired_linear_vel`` (m/s), in (0, 100].
    lookahead_time : float, default 1.5
        Nav2 ``lookahead_time`` (s), in (0, 1e4].
    min_lookahead, max_lookahead : float, default 0.3 and 0.9
        Nav2 ``min_lookahead_dist`` / ``max_lookahead_dist`` (m), in (0, 1e4],
        ``min_lookahead <= max_lookahead``; set them equal for a fixed
        lookahead (Nav2's ``lookahead_dist`` is 0.6). A lookahead point
        closer than about 3.2 cm gives curvature 0 (as in Nav2), so a
        lookahead that short never steers on an arc.
    rotate_to_heading : bool, default True
        Nav2 ``use_rotate_to_heading``: whether a differential robot turns in
        place toward a path that points away (step 2), and an omnidirectional
        one snaps its direction of travel to it. Without it a lookahead point
        behind the robot (a path starting behind it, a U-turn) is steered for
        on the arc through it, of radius ``d² / (2 |y|)``, which is a straight
        line away from it when the point is right behind: as in Nav2 (without
        reversing), the robot may never come back to the path. Within 3.2 cm of
        the lookahead point, where the tracker drives straight rather than on
        an arc, it still turns (snaps) toward a point more than 45° off (step
        2): a robot passing the goal a hair to its side would otherwise drive
        on, away from it.
    rotate_angle : float, default 0.785
        Nav2 ``rotate_to_heading_min_angle`` (rad), in (0, π].
    rotate_omega : float, default 1.8
        Nav2 ``rotate_to_heading_angular_vel`` (rad/s), in (0, 100].
    max_angular_accel : float, default 3.2
        Nav2 ``max_angular_accel`` (rad/s²) of in-place turns, in (0, 1e4].
    curvature_regulation : bool, default True
        Nav2 ``use_regulated_linear_velocity_scaling``.
    slowdown_radius : float, default 0.9
        Nav2 ``regulated_linear_scaling_min_radius`` (m), in (0, 1e4].
    min_regulated_speed : float, default 0.25
        Nav2 ``regulated_linear_scaling_min_speed`` (m/s), in [0, 100].
    clearance : OccupancyGrid or callable, optional
        Obstacle proximity for the cost regulation (Nav2
        ``use_cost_regulated_linear_velocity_scaling``, which reads the cost at
        the robot): a map, whose occupied cells are the obstacles (distances
        from the robot's cell centre to theirs, the map's
        :meth:`~navkit.mapping.OccupancyGrid.obstacle_distance`, computed
        once, when the tracker is built: cells the map gains later, e.g. by
        :func:`~navkit.mapping.integrate_scan` in place, are not seen; for a
        live map pass a function or build a new tracker), or a function
        ``clearance(x, y)`` giving the distance (m) from a world point to the
        nearest obstacle (NaN is rejected, negative counts as 0, ``inf`` as
        far). None (default): no cost regulation. The function must not call
        this tracker's :meth:`step` (refused, ``RuntimeError``) or
        :meth:`set_path` (the step then raises ``RuntimeError``).
        A map's unknown cells are not obstacles here (nor in Nav2, whose
        inflation skips unknown space by default), though
        :class:`~navkit.planning.MapPlanner` and ``World(grid=...)`` treat
        them as ones: on a robot-built map whose walls are mostly unknown
        cells (the Willow Garage map: 0.2 % occupied, 68 % unknown) pass
        ``OccupancyGrid.from_occupancy(grid.occupied() | grid.unknown(),
        resolution=grid.resolution, origin=grid.origin)`` (on the controller
        loop tutorial's route: a mean speed of 0.37 m/s instead of 0.46 with
        ``clearance=grid``, 0.48 without regulation). A robot outside the
        map is not regulated at all, as with a map with no occupied cell,
        however near the walls at its edge (Nav2 raises an error when the
        robot leaves its costmap): give a map covering where the robot
        drives, or a function.
    clearance_distance : float, default 0.6
        Nav2 ``cost_scaling_dist`` (m), in (0, 1e4].
    clearance_gain : float, default 1.0
        Nav2 ``cost_scaling_gain``, in (0, 1e6].
    approach_distance : float, default 0.6
        Nav2 ``approach_velocity_scaling_dist`` (m), in (0, 1e4].
    min_approach_speed : float, default 0.05
        Nav2 ``min_approach_linear_velocity`` (m/s), in (0, 100].
    goal_tolerance : float, default 0.25
        Nav2 goal checker ``xy_goal_tolerance`` (m), in (0, 1e4]. A goal
        tolerance below the float resolution of the goal's coordinates (one
        ulp of the finer: 9.3e-10 m at (4.6e6, 4.6e6) m, 5.8e-11 m at
        (4.6e6, 5e5) m) counts as that resolution: a pose one ulp beside the
        goal is as near as any but the goal itself.
    yaw_tolerance : float, default 0.25
        Nav2 goal checker ``yaw_goal_tolerance`` (rad), in (0, π].
    max_omega : float, optional
        Largest turn rate (rad/s) of any command, in (0, 100]; None (Nav2's
        behaviour) limits only in-place turns, to ``rotate_omega`` or, when the
        robot is measured turning faster, to within ``max_angular_accel`` of
        its measured rate.
    drive : {"diff", "omni"}, default "diff"
        Differential (``vy = 0``) or omnidirectional robot (the default of
        every path tracker; ``PotentialFieldController``'s is ``"omni"``).

    Other Parameters
    ----------------
    rotate_to_heading_angle : float, optional
        Deprecated name of `rotate_angle`.

    Notes
    -----
    Defaults are Nav2's (``nav2_regulated_pure_pursuit_controller/src/
    parameter_handler.cpp`` and the Nav2 configuration guide, "Regulated Pure
    Pursuit"; goal tolerances from ``nav2_controller::SimpleGoalChecker``).
    Differences: the lookahead is always scaled with speed (Nav2's
    ``use_velocity_scaled_lookahead_dist`` defaults to false and uses
    ``lookahead_dist``); on a path that folds back inside the lookahead circle
    Nav2 steers for the goal and its lookahead point can alternate between two
    stretches of the path for ever, which the two lookahead rules of step 1
    prevent; proximity is a distance rather than a costmap cost
    (Nav2 converts its inflation cost back into this distance); the final
    rotation happens whenever a goal heading is given; no collision check,
    reversing or cancel deceleration; no command passes its target within one
    step (``v <= distance / dt`` to the lookahead point, ``|ω| <= |angle| / dt``
    in place), which only binds at low control rates.

    The goal tolerance is met only as closely as the robot follows the
    commands (as :class:`~navkit.control.OnOffTracker`'s Notes explain): on
    exact wheels the tracker is done within 1e-9 m in a
    :class:`~navkit.sim.Simulation`, but a robot that has passed the goal by a
    hair turns in place toward it, and slipping wheels move its centre as it
    turns. A 0.3 m track at 20 Hz, ten starts 2 to 4 m away: with
    ``wheel_slip=0.05`` done at 1e-4 m and never at 1e-5 m (cycling between
    turning and driving 0.4 to 1 mm from the goal); with ``wheel_slip=0.01``,
    2 of 10 at 1e-5 m; with ``max_wheel_acceleration=20`` rad/s², done at
    1e-5 m. Give a tolerance the robot can hold (Nav2's goal checker's
    default is 0.25 m).

    Small loops are cut, as in Nav2. A loop of the path (or any detour that
    comes back near where it left) is skipped when either

    * the lookahead circle holds it as the robot reaches it: the lookahead
      point is the first point at least ``L`` away, beyond the loop, and
      :attr:`progress` follows the robot there (Nav2's ``getLookAheadPoint``
      likewise takes the first pose of the pruned plan at least ``L`` away); or
    * it never leads more than 0.25 m farther from the robot than the path's
      closest point: the closest-point search walks through it to the later
      pass of the path (Nav2's closest-pose search, a minimum over
      ``max_robot_pose_search_dist`` of path, jumps past any loop shorter
      than that).

    In practice a loop is driven round only when its width is about twice
    ``max_lookahead`` or more and well above 0.25 m: with the defaults
    (``L`` up to 0.9 m) a circular loop of radius 0.3 m is cut, with
    ``min_lookahead = max_lookahead = 0.3`` it is driven; one of radius 0.1 m is
    cut by any lookahead. To drive a small loop, lower ``max_lookahead`` or
    give its parts as successive paths.

    A tracker takes one :meth:`step` at a time: a step called while another
    is under way (another thread's, or a signal handler's) raises
    ``RuntimeError``, saying which, and changes nothing; the step under way
    goes on as alone (the check costs about 0.2 µs of a 2.5 to 6.5 µs step).
    A :meth:`set_path` and a :meth:`step` overlapping (from another thread or
    a signal handler) are safe: :meth:`set_path` installs the new path's state
    whole, and a step works on the state it read as it began, so its command is
    for the old path (the new one, had the :meth:`set_path` come first) and the
    next step follows the new path from its start (with a ``clearance``
    function, a :meth:`set_path` while the function runs makes the step raise
    ``RuntimeError`` instead, saying so: it cannot tell one the function made
    from another thread's or a signal handler's). In a ROS 2 node the path
    subscription may run in a callback group of its own; the control timer's
    must not let its callback overlap itself (mutually exclusive, the
    default), or its overlapping steps are refused. Different trackers may run
    in different threads at once (with one ``clearance`` grid, which they only
    read; a ``clearance`` callable shared by them must itself be thread-safe).

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
        A non-numeric option, or a ``clearance`` that is neither an
        OccupancyGrid nor callable.

    Examples
    --------
    >>> from navkit.geometry import integrate
    >>> tracker = RegulatedPurePursuit(goal_tolerance=0.05)
    >>> tracker.set_path([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]], goal_yaw=math.pi / 2)
    >>> pose, top_speed = Pose2D(0.0, 0.1, 0.0), 0.0
    >>> while not tracker.done:
    ...     cmd = tracker.step(pose, 0.05)
    ...     top_speed = max(top_speed, cmd.vx)
    ...     pose = integrate(pose, cmd, 0.05)
    >>> math.hypot(pose.x - 2.0, pose.y - 2.0) <= 0.05, top_speed
    (True, 0.5)
    """

    __slots__ = (
        "_approach_distance",
        "_clearance",
        "_clearance_distance",
        "_clearance_gain",
        "_curvature_regulation",
        "_lookahead_time",
        "_max_angular_accel",
        "_max_lookahead",
        "_max_omega",
        "_max_speed",
        "_min_approach_speed",
        "_min_lookahead",
        "_min_regulated_speed",
        "_rotate_omega",
        "_rotate_to_heading",
        "_rotate_to_heading_angle",  # rotate_angle: the name predates the rename (pickles)
        "_slowdown_radius",
    )

    def __init__(
        self,
        *,
        max_speed: float = 0.5,
        lookahead_time: float = 1.5,
        min_lookahead: float = 0.3,
        max_lookahead: float = 0.9,
        rotate_to_heading: bool = True,
        rotate_angle: float = 0.785,
        rotate_omega: float = 1.8,
        max_angular_accel: float = 3.2,
        curvature_regulation: bool = True,
        slowdown_radius: float = 0.9,
        min_regulated_speed: float = 0.25,
        clearance: OccupancyGrid | Clearance | None = None,
        clearance_distance: float = 0.6,
        clearance_gain: float = 1.0,
        approach_distance: float = 0.6,
        min_approach_speed: float = 0.05,
        goal_tolerance: float = 0.25,
        yaw_tolerance: float = 0.25,
        max_omega: float | None = None,
        drive: Literal["diff", "omni"] = "diff",
        rotate_to_heading_angle: float | None = None,
    ) -> None:
        # The name every tracker shares (docs/guides/control.md); the old one warns,
        # and errors name the keyword the caller wrote.
        old_used = rotate_to_heading_angle is not None
        angle_name = "rotate_to_heading_angle" if old_used else "rotate_angle"
        rotate_angle = renamed_keyword(
            "rotate_to_heading_angle", rotate_to_heading_angle, "rotate_angle", rotate_angle, 0.785
        )
        super().__init__(drive=drive, goal_tolerance=goal_tolerance, yaw_tolerance=yaw_tolerance)
        self._max_speed = bounded(max_speed, "max_speed", 0.0, 100.0)
        self._lookahead_time = bounded(lookahead_time, "lookahead_time", 0.0, 1e4)
        self._min_lookahead = bounded(min_lookahead, "min_lookahead", 0.0, 1e4)
        self._max_lookahead = bounded(max_lookahead, "max_lookahead", 0.0, 1e4)
        if self._max_lookahead < self._min_lookahead:
            raise ValueError(
                f"max_lookahead must be >= min_lookahead ({self._min_lookahead}), "
                f"got {self._max_lookahead}"
            )
        self._rotate_to_heading = as_bool(rotate_to_heading, "rotate_to_heading")
        self._rotate_to_heading_angle = bounded(rotate_angle, angle_name, 0.0, math.pi)
        self._rotate_omega = bounded(rotate_omega, "rotate_omega", 0.0, 100.0)
        self._max_angular_accel = bounded(max_angular_accel, "max_angular_accel", 0.0, 1e4)
        self._curvature_regulation = as_bool(curvature_regulation, "curvature_regulation")
        self._slowdown_radius = bounded(slowdown_radius, "slowdown_radius", 0.0, 1e4)
        self._min_regulated_speed = bounded(
            min_regulated_speed, "min_regulated_speed", 0.0, 100.0, include_lo=True
        )
        self._clearance = _as_clearance(clearance)
        self._clearance_distance = bounded(clearance_distance, "clearance_distance", 0.0, 1e4)
        self._clearance_gain = bounded(clearance_gain, "clearance_gain", 0.0, 1e6)
        self._approach_distance = bounded(approach_distance, "approach_distance", 0.0, 1e4)
        self._min_approach_speed = bounded(min_approach_speed, "min_approach_speed", 0.0, 100.0)
        self._max_omega = (
            None if max_omega is None else bounded(max_omega, "max_omega", 0.0, 100.0)
        )

    def __repr__(self) -> str:
        # Every option, as the planners and estimators print theirs; a clearance map
        # prints as the grid it was built from (eval gives a twin when there is none).
        clearance = self._clearance
        shown = clearance._grid if isinstance(clearance, _GridClearance) else clearance
        return (
            f"{type(self).__name__}(max_speed={self._max_speed}, "
            f"lookahead_time={self._lookahead_time}, min_lookahead={self._min_lookahead}, "
            f"max_lookahead={self._max_lookahead}, rotate_to_heading={self._rotate_to_heading}, "
            f"rotate_angle={self._rotate_to_heading_angle}, rotate_omega={self._rotate_omega}, "
            f"max_angular_accel={self._max_angular_accel}, "
            f"curvature_regulation={self._curvature_regulation}, "
            f"slowdown_radius={self._slowdown_radius}, "
            f"min_regulated_speed={self._min_regulated_speed}, clearance={shown!r}, "
            f"clearance_distance={self._clearance_distance}, "
            f"clearance_gain={self._clearance_gain}, "
            f"approach_distance={self._approach_distance}, "
            f"min_approach_speed={self._min_approach_speed}, "
            f"goal_tolerance={self._goal_tolerance}, yaw_tolerance={self._yaw_tolerance}, "
            f"max_omega={self._max_omega}, drive={self._drive!r})"
        )

    @property
    def max_speed(self) -> float:
        """Nav2 ``desired_linear_vel`` (m/s)."""
        return self._max_speed

    @property
    def max_omega(self) -> float | None:
        """Largest turn rate (rad/s) of any command, or None (in-place turns only)."""
        return self._max_omega

    @property
    def rotate_omega(self) -> float:
        """Turn rate (rad/s) of in-place turns."""
        return self._rotate_omega

    @property
    def rotate_angle(self) -> float:
        """Nav2 ``rotate_to_heading_min_angle`` (rad): turns in place above this heading error."""
        return self._rotate_to_heading_angle

    def _new_state(
        self, line: Polyline | None, goal_heading: float | None, phase: Phase
    ) -> _PursuitState:
        return _PursuitState(line, goal_heading, phase)

    def step(
        self,
        pose: Pose2D | ArrayLike,
        dt: float,
        *,
        velocity: Twist2D | ArrayLike | None = None,
    ) -> Twist2D:
        """One control cycle: the command to hold for the next ``dt`` seconds.

        Parameters
        ----------
        pose : Pose2D or array_like [x, y, theta]
            Robot pose in the world frame (m, m, rad; coordinates within ±1e9 m). The
            :attr:`progress` along the path never goes back: one pose that
            jumps ahead (a localisation glitch) can move it up to 2 m of path
            ahead at once, and that stretch is then skipped (most of a short
            out-and-back path, say); :meth:`set_path` starts over, and its
            first step finds the robot anywhere along the path.
        dt : float
            Control period in seconds, > 0 (a normal float: at least 2.2e-308).
        velocity : Twist2D or array_like [vx, vy, omega], optional
            Measured robot-frame velocity (m/s, m/s, rad/s; Nav2's ``speed``: it sets the
            lookahead distance and the base of the angular acceleration limit);
            None uses the previous command.

        Returns
        -------
        Twist2D
            Robot-frame command ``(vx, vy, omega)`` in m/s, m/s, rad/s;
            ``vy = 0`` for ``drive="diff"``; all zero once :attr:`done`.

        Raises
        ------
        RuntimeError
            No path yet (call :meth:`set_path` first); another step under way
            (another thread's, a signal handler's, or the ``clearance``
            function's own call of :meth:`step`, refused), this step changing
            nothing; or a :meth:`set_path` while the ``clearance`` function ran
            (the new path stays, this step does nothing).
        TypeError, ValueError
            A bad ``pose``, ``dt`` (not a normal float > 0) or ``velocity``,
            naming it, or a ``clearance`` function returning NaN; the
            tracker's state is unchanged then.

        Examples
        --------
        >>> tracker = RegulatedPurePursuit()
        >>> tracker.set_path([[0.0, 0.0], [3.0, 0.0]])
        >>> tracker.step(Pose2D(0.0, 0.0, 0.0), 0.05)  # on a straight path: max_speed
        Twist2D(vx=0.5, vy=0.0, omega=0.0)

        Facing away from the path it turns in place, the turn rate changing by at
        most ``max_angular_accel × dt`` (0.16 rad/s) from the previous command's,
        or from the measured ``velocity``'s:

        >>> tracker.step(Pose2D(0.0, 0.0, math.pi / 2), 0.05)
        Twist2D(vx=0.0, vy=0.0, omega=-0.16)
        >>> tracker.step(Pose2D(0.0, 0.0, math.pi / 2), 0.05, velocity=(0.0, 0.0, 1.0))
        Twist2D(vx=0.0, vy=0.0, omega=0.84)
        >>> tracker.phase
        'rotate'
        """
        measured = None if velocity is None else as_twist(velocity, "velocity")
        return self._run(pose, dt, measured)

    # ------------------------------------------------------------ internals
    def _rotate(self, angle: float, dt: float, omega_now: float) -> float:
        """Nav2's ``rotateToHeading``: turn rate toward ``angle`` (rad) from ``omega_now``."""
        sign = 1.0 if angle > 0.0 else -1.0
        w = sign * self._rotate_omega
        if self._max_omega is not None:
            w = sign * min(self._rotate_omega, self._max_omega)
        dw = self._max_angular_accel * dt
        w = min(max(w, omega_now - dw), omega_now + dw)
        stop = min(math.sqrt(2.0 * self._max_angular_accel * abs(angle)), abs(angle) / dt)
        if sign * w > stop:
            # Only a turn toward the target is capped to stop on it. A robot still
            # turning away keeps slowing at max_angular_accel: Nav2 sets sign * stop
            # there too, which reverses the turn in one step, past the limit.
            w = sign * stop
        if self._max_omega is not None:
            # The bound of every command, also when the robot (measured) turns faster:
            # then the command drops to it, faster than max_angular_accel allows.
            w = min(max(w, -self._max_omega), self._max_omega)
        return w

    def _command(
        self,
        state: _PursuitState,
        line: Polyline,
        pose: Pose2D,
        dt: float,
        measured: Twist2D | None,
    ) -> Twist2D:
        # Validate what can fail before any state changes.
        clearance = None
        if self._clearance is not None:
            clearance = self._clearance_at(pose)
            if self._state is not state:
                # A set_path while the function ran: by the function, or by a signal
                # handler or another thread, which cannot be told apart here. The
                # message said the function had called it, also for another thread's
                # set_path (review 38). (A step meanwhile is refused by the guard.)
                name = type(self).__name__
                raise RuntimeError(
                    f"{name}.set_path was called while this step's clearance(x, y) ran "
                    "(by that function, a signal handler or another thread): the new "
                    "path is kept and this step, begun on the old path, did nothing; "
                    "call step again"
                )
        vx_now, vy_now, w_now = (
            state.last if measured is None else (measured.vx, measured.vy, measured.omega)
        )
        speed_now = abs(vx_now) if self._drive == "diff" else math.hypot(vx_now, vy_now)
        px, py = pose.x, pose.y
        # With the point at the new progress: the fold check below needs it, and a
        # second call for it cost 0.4 µs of a 7 µs step. Points are taken as offsets
        # from the robot, subtracted first, so that the command is the same wherever
        # the problem is translated (a UTM frame lost 1e-8 rad/s to the rounding of
        # world coordinates).
        last_carrot = state.carrot
        reach = 0.0 if last_carrot is None else last_carrot[0]
        s, fx, fy = self._advance_offset(state, line, pose, reach)
        lookahead = min(max(speed_now * self._lookahead_time, self._min_lookahead),
                        self._max_lookahead)
        for _ in range(_MAX_FOLDS):
            s_exit = line.circle_exit(px, py, s, lookahead)
            # With the rest of the path inside the circle: the point the lookahead
            # distance further along it (the goal near the end; Nav2 takes the goal
            # anywhere, which makes a path folding back near its start a trap).
            s_carrot = min(s + lookahead, line.length) if s_exit is None else s_exit
            if last_carrot is not None:
                # The lookahead point moves back along the path only as far as the
                # lookahead distance shrank: on a path looping inside the circle it
                # could otherwise alternate between two stretches of it for ever.
                back = max(0.0, last_carrot[1] - lookahead)
                s_carrot = max(s_carrot, min(last_carrot[0] - back, line.length))
            cx, cy, wx, wy = line.offset_at(s_carrot, px, py)  # from the robot; the point
            dist = math.hypot(cx, cy)
            if not s < s_carrot < line.length:
                break
            if dist > math.hypot(fx, fy):
                break
            # The lookahead point is as near as the closest point: on a path doubling
            # back through the robot (an out-and-back shorter than the lookahead) the
            # robot meets it where the two passes cross, and every command after that
            # was zero, or a creep toward a point 1e-16 m away. The robot is at the
            # lookahead point's arc too: project it there and look ahead from it.
            s = s_carrot
            state.progress = s
            fx, fy = cx, cy  # offset_at(s), as computed for the lookahead point
        state.carrot = (s_carrot, lookahead)
        state.target = (wx, wy)
        gx, gy = line.end
        to_goal = math.hypot(gx - px, gy - py)
        if state.phase == "final" or (
            s_carrot >= line.length and at_goal(px, py, gx, gy, self._goal_tolerance)
        ):
            cmd = self._finish(state, pose, dt, lambda err, h: self._rotate(err, h, w_now))
            state.last = (cmd.vx, cmd.vy, cmd.omega)
            return cmd

        # The heading the pure-pursuit law steers: the robot's, or (omni) its
        # direction of travel.
        bearing = math.atan2(cy, cx)
        if self._drive == "diff":
            heading = pose.theta
        else:
            motion = state.motion_heading
            heading = bearing if motion is None else motion
        angle = wrap(bearing - heading)
        # Nearer than pursuit_curvature steers (3.2 cm) the robot drives straight, and a
        # straight run up to the point's distance moves away from it when more than 60
        # degrees off: with a wider rotate_angle and a goal tolerance of millimetres it
        # circled the goal for ever. Turning to within 45 degrees there first, each run
        # ends at most 0.77 times as far (the default 0.785 rad turns there already).
        # Whatever rotate_to_heading: there is no arc there to steer on instead, and
        # without the turn a robot passing the goal a hair to its side drove on, away
        # from it for good (the goal then right behind).
        too_wide = dist * dist <= _STRAIGHT_D2 and abs(angle) > _STRAIGHT_ANGLE
        if too_wide or (self._rotate_to_heading and abs(angle) > self._rotate_to_heading_angle):
            if self._drive == "diff":
                state.phase = "rotate"
                w = self._rotate(angle, dt, w_now)
                # The command made before the store, no call after it (Twist2D's
                # checks are calls): see the omnidirectional return below.
                out = Twist2D(0.0, 0.0, w)
                state.last = (0.0, 0.0, w)
                return out
            heading = bearing
            angle = 0.0
        state.phase = "track"
        kappa = pursuit_curvature(dist * math.cos(angle), dist * math.sin(angle))

        v = self._max_speed
        v_curv = v
        if self._curvature_regulation and kappa != 0.0:
            radius = 1.0 / abs(kappa)
            if radius < self._slowdown_radius:
                v_curv = v * radius / self._slowdown_radius
        v_cost = v
        if clearance is not None and clearance < self._clearance_distance:
            v_cost = v * self._clearance_gain * clearance / self._clearance_distance
        v = max(min(v_curv, v_cost), self._min_regulated_speed)
        if line.length - s < self._approach_distance:
            approach = max(v * to_goal / self._approach_distance, self._min_approach_speed)
            v = min(v, approach)
        # Never pass the lookahead point (the goal, at the end) within one step.
        v = min(max(v, 0.0), self._max_speed, dist / dt)
        w = v * kappa
        if self._max_omega is not None and abs(w) > self._max_omega:
            scale = self._max_omega / abs(w)
            v *= scale
            w = math.copysign(self._max_omega, w)

        if self._drive == "diff":
            out = Twist2D(v, 0.0, w)
            state.last = (v, 0.0, w)
            return out
        # Omni: translate along the chord of the arc, keep the body heading.
        turn = w * dt
        mid = heading + 0.5 * turn
        bx, by = body_velocity(v * math.cos(mid), v * math.sin(mid), pose.theta)
        # Every new value first (the command too: Twist2D's checks are calls), then
        # plain stores: a Ctrl-C landing after the stores (in the wrap or the Twist2D)
        # left the memory of this step with its command lost, and a loop that caught
        # it and stepped again limited the turn from this step's command, not the one
        # before (review 25's retry rule; review 38, REV38).
        motion = wrap(heading + turn)
        out = Twist2D(bx, by, 0.0)
        state.motion_heading = motion
        state.last = (bx, by, 0.0)
        return out

    def _refusal(self, other: tuple[Any, ...], callers: list[Any]) -> str:
        message = super()._refusal(other, callers)
        if self._clearance is not None and "in the same thread" in message:
            # The same thread: a signal handler's step, or one the clearance function
            # made (the step calls it). Not a forked child's refusal of a call under
            # way in its parent, whose thread may have had this ident.
            message += " (nor may its clearance(x, y) function call step)"
        return message

    def _clearance_at(self, pose: Pose2D) -> float:
        assert self._clearance is not None
        raw: Any = self._clearance(pose.x, pose.y)
        if issubclass(type(raw), np.ndarray) and raw.ndim == 0 and raw.dtype.kind in "fiu":
            refuse_masked(raw, "clearance(x, y)")  # .item() would read a masked value's data
            raw = raw.item()
        if isinstance(raw, (bool, np.bool_)) or not isinstance(raw, numbers.Real):
            raise TypeError(
                f"clearance(x, y) must return a real number, got {type(raw).__name__}"
            )
        try:
            value = float(raw)
        except OverflowError:  # an integer beyond float64: as far as infinity
            value = math.inf if cast(int, raw) > 0 else -math.inf
        if math.isnan(value):
            raise ValueError(f"clearance(x, y) returned NaN at ({pose.x}, {pose.y})")
        return max(value, 0.0)


def _as_clearance(value: Any) -> Clearance | None:
    """``clearance`` as a function of ``(x, y)``, or None."""
    if value is None:
        return None
    if isinstance(value, OccupancyGrid):
        return _GridClearance(value)
    if callable(value):
        fn: Clearance = value
        return fn
    raise TypeError(
        f"clearance must be an OccupancyGrid or a callable clearance(x, y), "
        f"got {type(value).__name__}"
    )

