"""Polyline geometry and the state every path tracker shares (private).

* :func:`as_world_path` — the one way a tracker takes a path: world points
  ``(N, 2)`` or a ``"world"`` :class:`~navkit.planning.Path2D`.
* :class:`Polyline` — a path parametrised by arc length: the point at a given
  arc length, the closest point within a window (progress along the path only
  moves forward, and the search ends where the path leaves the robot, so loops
  and crossings are followed in order), pure pursuit's
  lookahead point (first crossing of a circle around the robot).
* :func:`pursuit_curvature` — the curvature of the arc that leaves the robot
  along its heading and passes through a point.
* :class:`PathState` — what a tracker knows of its current path (the path,
  progress, phase, target, ...), in one object that :meth:`PathTracker.set_path`
  builds whole and installs with one attribute store.
* :class:`PathTracker` — the stateful skeleton of :class:`FollowTheCarrot`,
  :class:`OnOffTracker` and :class:`RegulatedPurePursuit`: ``set_path``, ``step``
  (validation, the latched ``done``), ``phase``, the common options.
"""

from __future__ import annotations

import math
import warnings
from _thread import get_ident
from abc import ABC, abstractmethod
from collections.abc import Mapping
from typing import Any, Generic, Literal, TypeVar, cast

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.angles import wrap_float as wrap
from navkit._shared.deprecation import renamed_keyword
from navkit._shared.frozen import restore_slots
from navkit._shared.locks import _in_use
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array, finite_float, positive_float
from navkit.control._path_following_kernels import (
    circle_exit,
    offset_at,
    point_at,
    project,
    project_offset,
)
from navkit.geometry import Pose2D, Twist2D, as_pose
from navkit.planning import Path2D

__all__ = [
    "MAX_COORDINATE",
    "SEARCH_AHEAD",
    "SEARCH_DETOUR",
    "ZERO_TWIST",
    "PathState",
    "PathTracker",
    "Phase",
    "Polyline",
    "as_world_path",
    "body_velocity",
    "bounded",
    "pursuit_curvature",
    "wrap",
]

MAX_COORDINATE = 1e9
"""Largest absolute world coordinate (m) a path point or a pose may have."""

SEARCH_AHEAD = 2.0
"""Arc length (m) of path searched ahead of the previous closest point at each step."""

SEARCH_DETOUR = 0.25
"""How much farther (m) from the robot than the closest point found so far the path
may lead before the search for the closest point stops. Beyond such a detour a
nearer point is a later pass of the path (the end of a closed loop shorter than
:data:`SEARCH_AHEAD`, the far side of a crossing), not where the robot is yet."""

Phase = Literal["idle", "rotate", "track", "final", "done"]

ZERO_TWIST = Twist2D(0.0, 0.0, 0.0)


def bounded(
    value: Any, name: str, lo: float, hi: float, *, include_lo: bool = False
) -> float:
    """``value`` as a float in ``(lo, hi]`` (``[lo, hi]`` with ``include_lo``), else raise."""
    out = finite_float(value, name)
    if out > hi or out < lo or (out == lo and not include_lo):
        left = "[" if include_lo else "("
        raise ValueError(f"{name} must be in {left}{lo:g}, {hi:g}], got {out}")
    return out


def as_world_path(path: Any, name: str = "path") -> FloatArray:
    """World points ``(N, 2)`` of ``path`` as a new float64 array.

    Parameters
    ----------
    path : array_like, shape (N, 2), or Path2D
        World points in metres, or a planner's path in the ``"world"`` frame.
    name : str, default "path"
        Argument name used in error messages.

    Raises
    ------
    TypeError
        Not numeric, or not array-like.
    ValueError
        A ``"grid"`` :class:`~navkit.planning.Path2D`, no point, a shape other
        than ``(N, 2)``, non-finite values or coordinates beyond ±1e9 m.

    Examples
    --------
    >>> as_world_path([[0.0, 0.0], [1.0, 0.0]])
    array([[0., 0.],
           [1., 0.]])
    """
    if isinstance(path, Path2D):
        if path.frame != "world":
            raise ValueError(
                f"{name} must be in the world frame, got a {path.frame!r} Path2D "
                "(convert it with path.to_world(grid), grid the map it was planned on, or plan "
                "with MapPlanner)"
            )
        raw: Any = path.points
    elif isinstance(path, (str, bytes, Mapping, set, frozenset)):
        raise TypeError(f"{name} must be an (N, 2) array of world points or a Path2D, "
                        f"got {type(path).__name__}")
    else:
        raw = path
    pts = np.array(as_float_array(raw, name, shape=(None, 2)), dtype=np.float64, copy=True)
    if pts.shape[0] == 0:
        raise ValueError(f"{name} must hold at least one point, got shape (0, 2)")
    if float(np.max(np.abs(pts))) > MAX_COORDINATE:
        raise ValueError(f"{name} coordinates must be within ±{MAX_COORDINATE:g} m")
    return pts


def pursuit_curvature(x: float, y: float) -> float:
    """Curvature (1/m) of the arc leaving the origin along +x through ``(x, y)``.

    ``2 y / (x² + y²)``, pure pursuit's steering law; 0 when the point is closer
    than about 3 cm (``x² + y² <= 0.001``, as in Nav2).

    Examples
    --------
    >>> pursuit_curvature(1.0, 1.0)
    1.0
    """
    d2 = x * x + y * y
    if d2 <= 1e-3:
        return 0.0
    return 2.0 * y / d2


class Polyline:
    """A path parametrised by arc length ``s`` in ``[0, length]``.

    Consecutive duplicate points are dropped (a path of identical points keeps
    one). All queries are numba kernels; ``s`` outside ``[0, length]`` is clamped.

    Parameters
    ----------
    points_xy : ndarray, shape (N, 2)
        Validated world points, N >= 1 (see :func:`as_world_path`).

    Examples
    --------
    >>> line = Polyline(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 2.0]]))
    >>> line.length, line.points_xy.shape
    (3.0, (3, 2))
    >>> line.point_at(2.0)
    (1.0, 1.0)
    >>> line.project(2.0, 1.5, 0.0, 3.0)
    (2.5, 1.0)
    """

    __slots__ = ("cum", "end", "length", "points_xy")

    def __init__(self, points_xy: FloatArray) -> None:
        pts = np.asarray(points_xy, dtype=np.float64)
        if pts.shape[0] > 1:
            step = np.hypot(*np.diff(pts, axis=0).T)
            pts = pts[np.concatenate(([True], step > 0.0))]
        pts = np.ascontiguousarray(pts)
        cum = np.zeros(pts.shape[0])
        if pts.shape[0] > 1:
            cum[1:] = np.cumsum(np.hypot(*np.diff(pts, axis=0).T))
        pts.flags.writeable = False
        cum.flags.writeable = False
        self.points_xy: FloatArray = pts
        self.cum: FloatArray = cum
        self.length = float(cum[-1])
        # point_at(length), the last point: read at every step of some trackers.
        self.end = (float(pts[-1, 0]), float(pts[-1, 1]))

    def __reduce__(self) -> tuple[type[Polyline], tuple[FloatArray]]:
        # Rebuilt from its points, so that pickles and deep copies (whose arrays
        # would come back writable) have read-only arrays again; the arc lengths
        # are recomputed bit for bit.
        return Polyline, (self.points_xy,)

    def __setstate__(self, state: Any) -> None:
        # Pickles made before __reduce__ (3bf2b94) hold the slots of then: rebuilt from
        # the points as a new line (review 51: without ``end``, added since, a tracker
        # pickled then raised AttributeError at its first step).
        slots = state[1] if isinstance(state, tuple) else state
        self.__init__(slots["points_xy"])  # type: ignore[misc]

    def point_at(self, s: float) -> tuple[float, float]:
        """The point ``(x, y)`` at arc length ``s``."""
        x, y = point_at(self.points_xy, self.cum, float(s))
        return float(x), float(y)

    def offset_at(self, s: float, x: float, y: float) -> tuple[float, float, float, float]:
        """``point_at(s)`` minus ``(x, y)``, subtracted first, and ``point_at(s)``:
        ``(dx, dy, px, py)``.

        The offset is what a tracker steers by: the same wherever the problem is
        translated (to about 1e-16 of its length), where ``point_at(s) - (x, y)``
        carries the rounding of world coordinates (1e-9 m at UTM northings).
        """
        dx, dy, px, py = offset_at(self.points_xy, self.cum, float(s), float(x), float(y))
        return float(dx), float(dy), float(px), float(py)

    def project(
        self,
        x: float,
        y: float,
        s_from: float,
        s_to: float,
        detour: float = math.inf,
        s_free: float = 0.0,
    ) -> tuple[float, float]:
        """Closest point to ``(x, y)`` among ``s`` in ``[s_from, s_to]``: ``(s, distance)``.

        With a finite ``detour`` the search stops at the first vertex from arc
        length ``s_free`` on (or the point at ``s_free``) more than ``detour``
        farther from ``(x, y)`` than the closest point found so far: the first
        such point of the path, however its segments are split.
        """
        lo = min(max(float(s_from), 0.0), self.length)
        hi = min(max(float(s_to), lo), self.length)
        s, d = project(
            float(x), float(y), self.points_xy, self.cum, lo, hi, float(s_free), float(detour)
        )
        return float(s), float(d)

    def project_offset(
        self, x: float, y: float, s_from: float, s_to: float, detour: float, s_free: float
    ) -> tuple[float, float, float]:
        """:meth:`project`'s ``s`` and ``offset_at(s, x, y)`` in one call: ``(s, dx, dy)``."""
        lo = min(max(float(s_from), 0.0), self.length)
        hi = min(max(float(s_to), lo), self.length)
        s, dx, dy = project_offset(
            float(x), float(y), self.points_xy, self.cum, lo, hi, float(s_free), float(detour)
        )
        return float(s), float(dx), float(dy)

    def circle_exit(self, x: float, y: float, s_from: float, radius: float) -> float | None:
        """First ``s >= s_from`` whose point is at least ``radius`` from ``(x, y)``.

        None when no such point exists (the circle holds the rest of the path).
        """
        lo = min(max(float(s_from), 0.0), self.length)
        s = float(circle_exit(float(x), float(y), self.points_xy, self.cum, lo, float(radius)))
        return None if s < 0.0 else s


class PathState:
    """What a tracker knows of its current path: one object per :meth:`PathTracker.set_path`.

    ``set_path`` builds it whole and installs it with one attribute store;
    ``step`` reads the tracker's state once, at its start, and reads and writes
    only that object. So a ``set_path`` landing inside a ``step`` (another
    thread, a signal handler) is not overwritten by the step's writes: that
    step's command is for the old path, and the next step follows the new one
    from its start. Trackers keeping more per-path state subclass it (each
    slot ``name`` pickles as the tracker's old attribute ``_name``).

    Parameters
    ----------
    line : Polyline or None
        The path (None before the first ``set_path``).
    goal_heading : float or None
        The goal yaw (rad), or None.
    phase : str
        The phase to start in.
    """

    __slots__ = ("goal_heading", "line", "phase", "progress", "target")

    def __init__(self, line: Polyline | None, goal_heading: float | None, phase: Phase) -> None:
        self.line = line
        self.goal_heading = goal_heading
        self.phase: Phase = phase
        self.progress = 0.0
        self.target: tuple[float, float] | None = None

    @classmethod
    def fields(cls) -> tuple[str, ...]:
        """Every slot of the class and its bases."""
        return tuple(
            name for klass in cls.__mro__ for name in getattr(klass, "__slots__", ())
        )


S = TypeVar("S", bound=PathState)


class PathTracker(ABC, Generic[S]):
    """Skeleton of a stateful path tracker; subclasses implement :meth:`_command`.

    Holds the path (:meth:`set_path`), the progress along it, the phase (all
    in one :class:`PathState`, :attr:`_state`), and turns :meth:`step` into
    validated calls of :meth:`_command` on that state. Once the goal is reached
    :attr:`done` stays set and :meth:`step` returns a zero twist until the next
    :meth:`set_path`.

    Copies and pickles hold the state's fields as the tracker's attributes
    ``_line``, ``_progress``, ... (as before the state object: pickles load
    both ways), and a copy gets a state of its own.

    One :meth:`step` at a time: a step called while another is under way
    (another thread's, or a signal handler's in the same thread) raises
    ``RuntimeError`` and changes nothing, and the step under way goes on as
    alone (the guard of :func:`navkit._shared.locks.one_caller`, written out:
    the tokens in ``_callers``, the same messages).
    """

    __slots__ = (
        "__weakref__",  # weakref.ref(obj) for callbacks and caches (review 36)
        "_callers",
        "_drive",
        "_goal_tolerance",
        "_state",
        "_yaw_tolerance",
    )

    def __getstate__(self) -> object:
        # Python's default state (pickle protocols 0 and 1 too, see slot_state) with
        # the per-path state's fields as the attributes they were before it: a copy
        # gets a state object of its own, and pickles load in older releases too.
        instance, slots = cast(
            "tuple[dict[str, Any] | None, dict[str, Any]]", object.__getstate__(self)
        )
        state = slots.pop("_state")
        for name in state.fields():
            slots["_" + name] = getattr(state, name)
        # Not in use, whatever the original is doing (pickles as before the guard).
        slots.pop("_callers", None)
        return instance, slots

    def __setstate__(self, state: Any) -> None:
        instance, slots = state if isinstance(state, tuple) else (None, state)
        slots = dict(slots)
        path = self._new_state(None, None, "idle")
        # A subclass's __getstate__ giving Python's default state (object.__getstate__,
        # slot_state) holds the state object itself: its fields are taken (into a state
        # of the copy's own), where it was replaced by an idle one and the copy had no
        # path (review 38). The attributes of before, if also there, win.
        given = slots.pop("_state", None)
        if isinstance(given, PathState):
            for name in given.fields():
                if name in path.fields():
                    setattr(path, name, getattr(given, name))
        for name in path.fields():
            if "_" + name in slots:
                setattr(path, name, slots.pop("_" + name))
        # Not in use (a copy made during a step, or a pickle of one, holds its token).
        slots["_callers"] = []
        restore_slots(self, (instance, {**slots, "_state": path}))

    def __init__(self, *, drive: Any, goal_tolerance: Any, yaw_tolerance: Any) -> None:
        # The steps under way (one at most: see _run; not copied or pickled).
        self._callers: list[tuple[int, str, object]] = []
        if not isinstance(drive, str) or drive not in ("diff", "omni"):
            raise ValueError(f"drive must be 'diff' or 'omni', got {drive!r}")
        self._drive: Literal["diff", "omni"] = "diff" if drive == "diff" else "omni"
        self._goal_tolerance = bounded(goal_tolerance, "goal_tolerance", 0.0, 1e4)
        self._yaw_tolerance = bounded(yaw_tolerance, "yaw_tolerance", 0.0, math.pi)
        self._state: S = self._new_state(None, None, "idle")

    @abstractmethod
    def _new_state(self, line: Polyline | None, goal_heading: float | None, phase: Phase) -> S:
        """A fresh per-path state of the tracker's kind (reads no option)."""

    # ----------------------------------------------------------------- state
    @property
    def drive(self) -> Literal["diff", "omni"]:
        """``"diff"`` (commands ``vy = 0``) or ``"omni"`` (holonomic)."""
        return self._drive

    @property
    def goal_tolerance(self) -> float:
        """Distance (m) from the path's last point at which the goal position is reached."""
        return self._goal_tolerance

    @property
    def yaw_tolerance(self) -> float:
        """Yaw error (rad) at which the goal yaw is reached."""
        return self._yaw_tolerance

    @property
    def done(self) -> bool:
        """True once the goal (position, and yaw if one was given) is reached."""
        return self._state.phase == "done"

    @property
    def phase(self) -> Phase:
        """What the tracker is doing.

        ``"idle"`` (no path yet), ``"rotate"`` (turning in place toward the
        path), ``"track"`` (moving along it), ``"final"`` (at the goal, turning
        in place to the goal yaw) or ``"done"``.
        """
        return self._state.phase

    @property
    def path_xy(self) -> FloatArray | None:
        """The path's points ``(K, 2)`` (read-only, consecutive duplicates dropped), or None."""
        line = self._state.line
        return None if line is None else line.points_xy

    @property
    def goal_yaw(self) -> float | None:
        """The yaw (rad, wrapped to (-π, π]) to turn to at the goal, or None (no final rotation)."""
        return self._state.goal_heading

    @property
    def goal_heading(self) -> float | None:
        """Deprecated alias of :attr:`goal_yaw`.

        Examples
        --------
        >>> from navkit.control import OnOffTracker
        >>> tracker = OnOffTracker()
        >>> tracker.set_path([[0.0, 0.0], [1.0, 0.0]], goal_yaw=1.0)
        >>> tracker.goal_yaw  # not .goal_heading, which warns
        1.0
        """
        warnings.warn(
            f"{type(self).__name__}.goal_heading is deprecated and will be removed in a "
            "future release: use goal_yaw",
            DeprecationWarning,
            stacklevel=2,
        )
        return self._state.goal_heading

    @property
    def target_xy(self) -> tuple[float, float] | None:
        """The point the last :meth:`step` steered toward (carrot, lookahead point or
        waypoint), or None before the first step of a path."""
        return self._state.target

    @property
    def progress(self) -> float:
        """How far along the path (arc length, m) the tracker has got; it never decreases.

        The arc length of the robot's closest point on the path, searched each
        step within 2 m of path ahead of the previous one, or up to the point
        the tracker last steered for (at the first step of a path, the whole
        path: a robot starting partway along it carries on from there); past
        that point, no farther than where the path first leads 0.25 m farther
        from the robot than the closest point so far (so loops and crossings are
        followed in order); for :class:`OnOffTracker`, that of the last waypoint
        reached.

        Both distances are absolute, whatever the speed, the control rate or
        the path's spacing: a search costs O(log N) on a path of N points plus
        the points within the window (a 10 km path of 10^5 poses steps as fast
        as a 20 m one). The window always reaches the point last steered for,
        which the robot does not pass within a step, so a fast robot is not
        lost; 2 m bounds how far one glitching pose moves the progress. A robot
        that leaves the path and comes back farther along (pushed, or
        re-localised) is found again at up to 2 m of path a step. The 0.25 m
        detour does not shrink with a small robot's options: a loop or
        out-and-back of the path that never leads 0.25 m farther from the robot
        than its closest point is walked through to the later pass, whatever
        ``carrot_distance`` or lookahead (a loop of 0.1 m radius is cut where the
        same path ten times larger is followed round); give such a path in
        parts. Paths scaled up are followed as the original is.
        """
        return self._state.progress

    # -------------------------------------------------------------- the path
    def set_path(
        self,
        path: Path2D | ArrayLike,
        *,
        goal_yaw: float | None = None,
        goal_heading: float | None = None,
    ) -> None:
        """Take a new path and start following it from its beginning.

        Clears :attr:`done` and the tracker's state (phase, progress, memory of
        previous commands); the options are kept. The new state is built whole
        and installed at once: a :meth:`step` running meanwhile (another thread,
        a signal handler) finishes on the old path, and the next one follows the
        new path from its start.

        Parameters
        ----------
        path : array_like, shape (N, 2), or Path2D
            World points ``(x, y)`` in metres from start to goal (N >= 1), or a
            planner's :class:`~navkit.planning.Path2D` in the ``"world"`` frame.
            Copied; consecutive duplicate points are dropped.
        goal_yaw : float, optional
            Yaw (rad, counter-clockwise from the world x axis, as ``Pose2D.theta``)
            to turn to in place once the goal position is reached. None
            (default): no final rotation, the tracker is done at the goal
            position.

        Other Parameters
        ----------------
        goal_heading : float, optional
            Deprecated name of `goal_yaw`.

        Raises
        ------
        ValueError
            A ``"grid"`` Path2D (convert it with
            :meth:`~navkit.planning.Path2D.to_world` or plan with
            :class:`~navkit.planning.MapPlanner`), no point, bad shape, NaN or
            inf, coordinates beyond ±1e9 m, a non-finite ``goal_yaw``; for
            :class:`~navkit.control.FollowTheCarrot`, a ``carrot_distance``
            too short for the path (below 2**-46 of its extent). The tracker
            keeps its previous path then.
        TypeError
            Non-numeric ``path`` or ``goal_yaw``; both ``goal_yaw`` and
            ``goal_heading`` given.

        Examples
        --------
        >>> from navkit.control import OnOffTracker
        >>> tracker = OnOffTracker()
        >>> tracker.set_path([[0.0, 0.0], [1.0, 0.0]], goal_yaw=1.0)
        >>> tracker.phase, tracker.goal_yaw
        ('track', 1.0)
        """
        # "yaw" as Pose2D.theta and yaw_tolerance ("heading" is the compass's
        # clockwise-from-north word); the old name warns, errors name what was written.
        named = "goal_yaw" if goal_heading is None else "goal_heading"
        goal_yaw = renamed_keyword("goal_heading", goal_heading, "goal_yaw", goal_yaw, None)
        pts = as_world_path(path, "path")
        heading = None if goal_yaw is None else wrap(finite_float(goal_yaw, named))
        line = Polyline(pts)
        self._check_line(line)  # before anything changes: a refused path keeps the old one
        # Built whole, then installed with one store: a step under way (which works on
        # the state it read at its start) cannot overwrite any of it.
        self._state = self._new_state(line, heading, self._start_phase())

    def _start_phase(self) -> Phase:
        """The phase a new path starts in."""
        return "track"

    def _check_line(self, line: Polyline) -> None:
        """Refuse (``ValueError``) a path the tracker's options cannot follow; any by default."""

    # ------------------------------------------------------------------ step
    def step(self, pose: Pose2D | ArrayLike, dt: float) -> Twist2D:
        """One control cycle: the command to hold for the next ``dt`` seconds.

        Parameters
        ----------
        pose : Pose2D or array_like [x, y, theta]
            Robot pose in the world frame (coordinates within ±1e9 m). The
            :attr:`progress` along the path never goes back: one pose that
            jumps ahead (a localisation glitch) can move it up to 2 m of path
            ahead at once, and that stretch is then skipped (most of a short
            out-and-back path, say); :meth:`set_path` starts over, and its
            first step finds the robot anywhere along the path.
        dt : float
            Control period in seconds, > 0 (a normal float: at least 2.2e-308).

        Returns
        -------
        Twist2D
            Robot-frame command; ``vy = 0`` for ``drive="diff"``; all zero once
            :attr:`done`.

        Raises
        ------
        RuntimeError
            No path yet (call :meth:`set_path` first), or another step under
            way (another thread's, or a signal handler's): this one changes
            nothing.
        TypeError, ValueError
            A bad ``pose`` or ``dt`` (not a normal float > 0), naming it;
            the tracker's state is unchanged then.

        Examples
        --------
        >>> from navkit.control import FollowTheCarrot
        >>> tracker = FollowTheCarrot()
        >>> tracker.set_path([[0.0, 0.0], [1.0, 0.0]])
        >>> tracker.step(Pose2D(0.0, 0.0, 0.0), 0.05)
        Twist2D(vx=0.18, vy=0.0, omega=0.0)
        >>> tracker.step([0.0, 0.0, 1.0], dt=0.05)  # facing away: turn in place
        Twist2D(vx=0.0, vy=0.0, omega=-1.5)
        """
        return self._run(pose, dt, None)

    def _run(self, pose: Pose2D | ArrayLike, dt: float, measured: Twist2D | None) -> Twist2D:
        """:meth:`step` with the measured velocity already validated."""
        p = as_pose(pose, "pose")
        if abs(p.x) > MAX_COORDINATE or abs(p.y) > MAX_COORDINATE:
            raise ValueError(f"pose coordinates must be within ±{MAX_COORDINATE:g} m")
        step = positive_float(dt, "dt")
        # One step at a time (one_caller's guard, written out: its wrapper's call cost
        # a tenth of a step). Two steps at once (two threads, a signal handler's step
        # inside the main loop's) both started from the progress before either, and
        # the later store won: progress went back (4.6 -> 4.0 m), RPP's memory of the
        # lookahead point and direction of travel mixed the two (review 38).
        callers = self._callers
        # Equal to no other token (its object): see one_caller.
        token = (get_ident(), "step", object())
        running = False
        try:
            callers.append(token)
            if callers[0] is not token:
                raise RuntimeError(self._refusal(callers[0], callers))
            running = True
            # The state is read once: the step reads and writes only this object, so a
            # set_path meanwhile (which installs a new one) is not overwritten.
            state = self._state
            line = state.line
            if line is None:
                raise RuntimeError(
                    f"{type(self).__name__} has no path: call set_path(path) first"
                )
            if state.phase == "done":
                return ZERO_TWIST
            return self._command(state, line, p, step, measured)
        finally:
            if running:
                # The step's token is the first (only refused calls' come after it, and
                # they take theirs out): deleted without a call, where no Ctrl-C lands
                # after the step's writes, and cheaper than list.remove.
                del callers[0]
            else:
                callers.remove(token)

    def _refusal(self, other: tuple[Any, ...], callers: list[Any]) -> str:
        """The message of a step refused while the step of token ``other`` runs."""
        return _in_use(type(self).__name__, "step", other, callers)

    @abstractmethod
    def _command(
        self, state: S, line: Polyline, pose: Pose2D, dt: float, measured: Twist2D | None
    ) -> Twist2D:
        """The tracker's own control law: the command for ``pose`` on ``line``
        (``state.line``; validated), reading and writing ``state`` only."""

    # --------------------------------------------------------------- helpers
    def _advance(self, state: S, line: Polyline, pose: Pose2D, reach: float = 0.0) -> float:
        """Move :attr:`progress` to the closest point within the search window.

        The window runs :data:`SEARCH_AHEAD` metres of path ahead of the previous
        closest point, or to arc length ``reach`` (where the tracker last
        steered) if that is farther; at the first step of a path, the whole
        path. Past ``reach`` the search ends after a detour of
        :data:`SEARCH_DETOUR` (a robot at the start of a short closed loop is not
        at its end); up to it, the robot may have cut across to any point,
        having been steered there.

        The whole path at the first step of a path (no target yet): a robot that
        starts partway along it (a replan that begins behind it) is found there,
        the search still ending where the path first leads a detour away from it.
        The 2 m window, a bound on how far one glitching pose moves the progress,
        made it catch up 2 m a step meanwhile, steering the robot back toward the
        path's start (100 m along: turned round for 50 steps).
        """
        # The window's end computed here rather than by a helper: one call less a step.
        progress = state.progress
        end = line.length if state.target is None else max(progress + SEARCH_AHEAD, reach)
        s, _ = line.project(pose.x, pose.y, progress, end, SEARCH_DETOUR, reach)
        state.progress = s
        return s

    def _advance_offset(
        self, state: S, line: Polyline, pose: Pose2D, reach: float
    ) -> tuple[float, float, float]:
        """:meth:`_advance`, returning the new progress's point's offset from the
        robot too: ``(s, dx, dy)`` (see :meth:`Polyline.offset_at`)."""
        progress = state.progress
        end = line.length if state.target is None else max(progress + SEARCH_AHEAD, reach)
        s, dx, dy = line.project_offset(pose.x, pose.y, progress, end, SEARCH_DETOUR, reach)
        state.progress = s
        return s, dx, dy

    def _finish(self, state: S, pose: Pose2D, dt: float, turn: Any) -> Twist2D:
        """The final phase: turn in place to the goal yaw with ``turn(error, dt)``."""
        state.phase = "final"
        goal = state.goal_heading
        if goal is None:
            state.phase = "done"
            return ZERO_TWIST
        err = wrap(goal - pose.theta)
        if abs(err) <= self._yaw_tolerance:
            state.phase = "done"
            return ZERO_TWIST
        omega: float = turn(err, dt)
        return Twist2D(0.0, 0.0, omega)


def body_velocity(wx: float, wy: float, theta: float) -> tuple[float, float]:
    """A world-frame velocity ``(wx, wy)`` in the frame of a robot heading ``theta``."""
    c = math.cos(theta)
    s = math.sin(theta)
    return c * wx + s * wy, -s * wx + c * wy

