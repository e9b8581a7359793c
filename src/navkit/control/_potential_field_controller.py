"""The soccer robot's artificial-potential-field motion controller."""

from __future__ import annotations

import functools
import math
from _thread import get_ident
from typing import Any, Literal, cast

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.dunders import slot_state
from navkit._shared.frozen import restore_slots
from navkit._shared.locks import _in_use
from navkit._shared.metres import metres_text
from navkit._shared.text import as_text
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array, as_point, as_points
from navkit.control._goal import at_goal
from navkit.control._ranges import MAX_COORDINATE, MAX_GAIN, MIN_GAIN, in_range, position, quantity
from navkit.control._velocity_limits import _limit_change
from navkit.geometry import Pose2D, Twist2D, angle_diff, as_pose, as_twist
from navkit.mapping import LaserScan
from navkit.planning import (
    AttractiveField,
    BlendedAttraction,
    KhatibRepulsion,
    PiecewiseAttraction,
    PotentialField,
    repulsive_force_from_scan,
)

__all__ = ["PotentialFieldController"]


def _pose(value: Any, name: str) -> Pose2D:
    """:func:`as_pose`, with a fast path for a tuple of three finite floats.

    The soccer players pass their target that way every step; ``as_pose`` would build
    an array to check it. Anything else (a NaN or an infinity included) goes
    through ``as_pose``, which raises.
    """
    if type(value) is tuple and len(value) == 3:
        x, y, theta = value
        if (
            type(x) is float and type(y) is float and type(theta) is float
            and math.isfinite(x) and math.isfinite(y) and math.isfinite(theta)
        ):  # fmt: skip
            return Pose2D(x, y, theta)
    return as_pose(value, name)


def _mount(value: Pose2D | ArrayLike | None) -> Pose2D | None:
    """The ``mount`` of :meth:`PotentialFieldController.step`, checked (None stays None)."""
    if value is None:
        return None
    mount = as_pose(value, "mount")
    position(mount.x, mount.y, "mount")
    return mount


def _check_reachable(goal_tolerance: float, attraction: AttractiveField) -> None:
    """Refuse (``ValueError``) a ``goal_tolerance`` the attraction never lets a robot meet.

    Checked for navkit's :class:`~navkit.planning.BlendedAttraction` and
    :class:`~navkit.planning.PiecewiseAttraction` (and subclasses keeping their
    force): a robot in free space comes to rest where their pull vanishes, at
    :func:`_resting_distance` from the goal or farther, and a tolerance not
    beyond it was never met: the robot settled short of the goal, never done and
    reported stalled there (``goal_tolerance=0.001`` with the default blend: 3.75
    mm off for ever, stalled after the timeout). Other fields pull up to the
    goal itself.
    """
    rest = _resting_distance(attraction)
    if goal_tolerance <= rest:
        kind = type(attraction).__name__
        why = (
            "nearer, the blend pushes outward: sigma(0) > 0 leaves a trace of the cone's tip"
            if isinstance(attraction, BlendedAttraction)
            else "nearer, within its goal_radius, it does not pull"
        )
        raise ValueError(
            f"goal_tolerance must exceed {_above(rest)} m: the attraction ({kind} "
            f"with these parameters) brings the robot to rest that far from the goal "
            f"({why}), so it would never be done; got {goal_tolerance!r}"
        )


def _above(rest: float) -> str:
    """``rest`` (m) as text, rounded up where rounding it to the nanometre went below it.

    Every tolerance beyond the named bound is then accepted (review 47: with
    ``width=0.12`` the rest 0.000892502496 m was named 0.000892502, and 0.0008925021
    was refused); exact (``repr``) where no rounding lies at or above it.
    """
    text = metres_text(rest)
    if float(text) >= rest or not math.isfinite(rest):
        return text
    up = metres_text(math.ceil(rest * 1e9) / 1e9)
    return up if float(up) > rest else repr(math.nextafter(rest, math.inf))


def _resting_distance(attraction: AttractiveField) -> float:
    """The least distance (m) from the goal at which ``attraction`` holds a robot at rest.

    0 for a field pulling toward the goal everywhere near it, and for fields
    other than :class:`~navkit.planning.BlendedAttraction` and
    :class:`~navkit.planning.PiecewiseAttraction` (a field of the user's own is
    not examined). The blend's equilibria lie on its ellipse's axes (only there
    is the paraboloid's gradient radial): the nearer of the two axes' first
    zeros of the radial force that holds a robot nudged off its axis (see
    :func:`_holds`), from below (a point where the force still pushes outward).
    """
    kind = type(attraction)
    if kind.force is not PotentialField.force:
        return 0.0
    if kind._force is PiecewiseAttraction._force:
        return cast(PiecewiseAttraction, attraction).goal_radius
    if kind._force is not BlendedAttraction._force:
        return 0.0
    if getattr(kind, "_terms", None) is not BlendedAttraction._terms:
        # A subclass with terms of its own has a force of its own: not examined
        # (review 47: one pulling up to the goal was judged as the plain blend).
        return 0.0
    field = cast(BlendedAttraction, attraction)
    return _blended_rest(
        field.k_att, field.c, field.a, field.b, field.threshold_radius, field.width,
        field.m, field.u_trans,
    )  # fmt: skip


@functools.lru_cache(maxsize=64)
def _blended_rest(
    k_att: float, c: float, a: float, b: float, threshold_radius: float, width: float,
    m: float, u_trans: float,
) -> float:  # fmt: skip
    """:func:`_resting_distance` of a blend of these parameters (every controller of
    the soccer scenario's players has the same: computed once, 0.5 ms)."""
    field = BlendedAttraction(
        np.zeros(2), k_att=k_att, c=c, a=a, b=b, threshold_radius=threshold_radius,
        width=width, m=m, u_trans=u_trans,
    )  # fmt: skip
    # Far out the paraboloid's terms overflow and near the goal σ underflows, as they
    # may in the field's own use: not the caller's np.seterr's business here.
    with np.errstate(all="ignore"):
        rests = [_first_rest(field, 0), _first_rest(field, 1)]
        held = [rest for axis, rest in enumerate(rests) if _holds(field, rest, axis)]
    return min(held or rests)


def _holds(field: BlendedAttraction, rest: float, axis: int) -> bool:
    """Whether the rest ``rest`` m along ``axis`` holds a robot pushed off the axis.

    Off the axis of the stiffer paraboloid the outward push of the cone's tip beats
    the paraboloid's weaker pull across it: the robot slides round to the other
    axis's rest (``a = 0.5, b = 2``: from 0.9 mm on the x axis to 17.4 mm on the y
    axis), which is then the nearest it comes to rest.
    """
    if not 0.0 < rest < math.inf:
        return True
    pts = np.zeros((1, 2))
    pts[0, axis] = rest
    pts[0, 1 - axis] = 1e-3 * rest
    return bool(field._force(pts)[0, 1 - axis] <= 0.0)


def _first_rest(field: BlendedAttraction, axis: int) -> float:
    """The last distance (m) along the positive ``axis`` (0: x, 1: y) from the goal (the
    origin) before the field's force first points inward; 0 if it does at once
    (1e-12 m), infinity if never (within 2e9 m, the farthest a robot is from a goal)."""
    d = np.geomspace(1e-12, 2e9, 512)
    pts = np.zeros((d.size, 2))
    pts[:, axis] = d
    inward = np.flatnonzero(field._force(pts)[:, axis] <= 0.0)
    if inward.size == 0:
        return math.inf
    k = int(inward[0])
    if k == 0:
        return 0.0
    lo, hi = float(d[k - 1]), float(d[k])
    # Each round narrows the bracket 64-fold: 2e-16 of it after nine rounds.
    for _ in range(9):
        grid = np.linspace(lo, hi, 65)
        pts = np.zeros((grid.size, 2))
        pts[:, axis] = grid
        j = int(np.flatnonzero(field._force(pts)[:, axis] <= 0.0)[0])
        lo, hi = float(grid[j - 1]), float(grid[j])
    return lo


class _Pid:
    """Heading PID gains and law; the integrator and last error are the controller's.

    They live in the controller's own slots, replaced at every step, so that a
    (shallow) copy of the controller never shares them with the original.
    """

    # _carried: the run state of a pickle made before it moved to the controller,
    # until the controller's __setstate__ takes it (unset otherwise).
    __slots__ = ("_carried", "integral_limit", "kd", "ki", "kp")
    __getstate__ = slot_state  # pickle protocols 0 and 1 too

    _carried: tuple[float, float | None]

    def __init__(self, kp: float, ki: float, kd: float, integral_limit: float) -> None:
        self.kp = kp
        self.ki = ki
        self.kd = kd
        self.integral_limit = integral_limit

    def __setstate__(self, state: Any) -> None:
        instance, slots = state if isinstance(state, tuple) else (None, state)
        slots = dict(slots)
        if "integral" in slots:
            # Pickles made before the integrator and last error moved to the
            # controller (3bf2b94) hold them here (review 51: such a controller
            # raised AttributeError as it loaded).
            slots["_carried"] = (slots.pop("integral"), slots.pop("last_error", None))
        restore_slots(self, (instance, slots))

    def update(
        self, integral: float, last_error: float | None, error: float, dt: float
    ) -> tuple[float, float]:
        """The new integral and the output for ``error`` after ``last_error``."""
        integral = min(max(integral + error * dt, -self.integral_limit), self.integral_limit)
        deriv = 0.0 if last_error is None else angle_diff(error, last_error) / dt
        return integral, self.kp * error + self.ki * integral + self.kd * deriv


#: The options, once plain attributes of these names (still in old pickles), and
#: the slots they are stored in now.
_RENAMED = {
    name: f"_{name}"
    for name in (
        "attraction", "drive", "goal_tolerance", "influence_radius", "k_rep", "max_accel",
        "max_decel", "max_omega", "max_speed", "stall_radius", "stall_timeout",
    )
}  # fmt: skip
# ``mode`` became ``drive`` (8c31a76), the same values: a pickle made before holds it so
# (review 52: such a controller was refused as it loaded, naming 'mode').
_RENAMED["mode"] = "_drive"
# ``d0`` became ``influence_radius`` (0123de4), the same value: a controller pickled
# before holds it so (review 53: such a pickle was refused, naming 'd0').
_RENAMED["d0"] = "_influence_radius"

#: Relative slack of the stall clock. It adds each step's dt, and k steps of a
#: decimal period sum below k periods (ten of 0.1 s: 0.9999999999999999), which
#: reported a stall one step after ``stall_timeout``. Sums of up to 10^6 steps
#: round by less than 3e-10 of themselves; 1e-9 of the timeout is far shorter
#: than a step.
_STALL_RTOL = 1e-9


class PotentialFieldController:
    """Artificial-potential-field motion controller (the soccer robot's algorithm).

    Each :meth:`step`:

    1. evaluates the attraction toward ``target_pose``'s position at the robot and
       scales it to the translational speed: a force longer than ``max_speed``
       is normalised to ``max_speed``, a shorter one is kept (so the paraboloid
       part of a :class:`~navkit.planning.BlendedAttraction` slows the robot as it
       arrives);
    2. adds the Khatib repulsion of every valid obstacle (rows with NaN or inf
       are invalid and skipped) or of every valid beam of a laser scan (should
       it overflow, the robot being numerically on an obstacle, the velocity is
       ``max_speed`` along the infinite components), each pushing the robot's
       reference point (its pose's ``(x, y)``): a scan from a sensor mounted
       off it, or turned, is placed with the sensor's ``mount`` (see
       :meth:`step`);
    3. takes the sum as the desired world-frame velocity, clipped to ``max_speed``,
       and limits its change from the previous velocity with
       :func:`limit_velocity_change` (``max_accel`` / ``max_decel``); the
       command never exceeds ``max_speed``: from a measured ``velocity`` above
       it (an odometry spike, say) it drops to ``max_speed`` at once, faster
       than ``max_decel`` allows;
    4. drives the heading with a PID: to ``target_pose.theta`` for an
       omnidirectional robot, to the direction of motion for a differential drive
       (to ``target_pose.theta`` within ``goal_tolerance`` of the goal, where the
       robot is :attr:`done`, and where the desired velocity is below a
       thousandth of ``max_speed``). At the goal the field's direction is no
       heading to steer by: a :class:`~navkit.planning.BlendedAttraction` pushes
       the robot out to its minimum (3.75 mm off the goal with the defaults,
       where ``σ(0) > 0`` leaves a trace of the cone's tip) at 7 mm/s along the
       robot's offset, however small, and a :class:`~navkit.planning.ConicAttraction`
       pulls at full strength up to the goal itself.

    The controller is stateful (previous velocity, PID integrator and last error,
    stall timer); call :meth:`reset` between runs. A new ``target_pose`` is no
    new run (the target may move every step): that state carries on, so a
    controller given a new goal accelerates from its previous velocity, and one
    :attr:`stalled` before it stays stalled while the robot stays within
    ``stall_radius`` of where it stalled, away from the new goal; after
    :meth:`reset` it steps as a new controller, bit for bit. It is an ordinary class with
    ``__slots__`` rather than a frozen dataclass because every step changes that state.
    Its options are read-only properties, checked once here (as the path
    trackers'): build a new controller to change one.

    Local minima: the robot is reported :attr:`stalled` when it has stayed within
    ``stall_radius`` of one spot for ``stall_timeout`` seconds while farther than
    ``goal_tolerance`` from the goal (this catches both a standstill and a small
    oscillation where attraction and repulsion cancel). An oscillation wider
    than ``stall_radius`` (a robot jittering a few centimetres to and fro in
    front of an obstacle, with scan points as obstacles) is not caught: raise
    ``stall_radius`` to the widest jitter that still means "stuck".

    Parameters
    ----------
    attraction : AttractiveField, optional
        Attractive field whose parameters are used; its goal is replaced by the
        target's position every step. Default: ``BlendedAttraction`` with its
        default parameters (no spurious minimum; it settles 3.75 mm from the goal).
    k_rep : float, default 0.05
        Khatib repulsion gain, in [1e-12, 1e12].
    influence_radius : float, default 0.6
        Khatib's ``d0`` (m), in [1e-6, 1e6]: obstacles farther than this do not
        repel.
    max_speed : float, default 0.5
        Maximum translational speed (m/s), in [1e-6, 1e6].
    max_accel, max_decel : float, default 1.0 and 2.0
        Translational acceleration and deceleration limits (m/s²), in [1e-6, 1e6].
    max_omega : float, default 2.0
        Maximum turn rate (rad/s), in [1e-6, 1e6].
    kp, ki, kd : float, default 3.0, 0.0, 0.1
        Heading PID gains, in [0, 1e12]; the output is a turn rate in rad/s.
    integral_limit : float, default 1.0
        Anti-windup bound on the heading integral (rad·s), in [1e-6, 1e6].
    drive : {"omni", "diff"}, default "omni"
        ``"omni"``: output ``(vx, vy, ω)`` in the robot frame. ``"diff"``: a
        differential drive, ``vy = 0`` and ``vx >= 0`` the desired velocity's
        component along the heading, but at most ``max_omega`` times the radius
        ``d² / (2 |y|)`` of the arc that leaves along the heading through the
        goal (``y`` its lateral offset, ``d`` its distance): turning at
        ``max_omega`` the robot stays on or inside that arc, where a faster one
        would circle a goal beside it (with the default ``max_omega`` and
        attraction the bound never binds). The default is the soccer robot paper's
        omnidirectional robot; the path trackers (``FollowTheCarrot``,
        ``OnOffTracker``, ``RegulatedPurePursuit``) default to ``"diff"``, so
        pass ``drive`` when swapping one for the other.
    goal_tolerance : float, default 0.05
        Distance (m) within which the goal counts as reached, in [1e-6, 1e6]:
        the robot is then :attr:`done`, never :attr:`stalled`, and a
        differential drive turns to ``target_pose.theta`` (moving only along
        its heading) rather than to the field's direction. Such a robot
        stops anywhere within it, as the path trackers do (about half of it
        from the goal when the target heading is across the approach): make
        it the accuracy wanted. It must exceed the distance from the goal at
        which the attraction brings the robot to rest, which no robot in
        free space comes nearer than (``ValueError`` otherwise, naming that
        distance): 3.75 mm for the default ``BlendedAttraction`` (computed
        from the blend's parameters: σ(0) > 0 pushes outward nearer the
        goal), the ``goal_radius`` of a ``PiecewiseAttraction``; a field of
        your own is not checked. The approach to that distance slows
        exponentially (the paraboloid's pull shrinks with it): a tolerance
        within a millimetre of it takes seconds more to reach, and a robot
        that stays within ``stall_radius`` meanwhile for ``stall_timeout`` is
        reported :attr:`stalled` on the way (the default blend from 5 cm off:
        for tolerances below 4.7 mm). A ``ConicAttraction`` pulls at full
        strength up to the goal, so an omnidirectional robot keeps passing
        through it, up to about a centimetre to and fro (with the default
        speeds and 20 Hz): :attr:`done` then comes and goes for tolerances
        below that; so does a blend whose tip pulls inward (``threshold_radius``
        below about half the ``width``: no rest off the goal), by millimetres.
        A differential drive steers by the field only where it asks for more
        than a thousandth of ``max_speed`` (see ``drive``): it may stop off
        its line anywhere the field is slower than that (a default
        ``ParaboloidAttraction``: up to 0.25 mm from the goal, where
        tolerances of a micrometre were not met).
    stall_radius : float, default 0.05
        Radius (m) the robot must leave to count as moving, in [1e-6, 1e6].
    stall_timeout : float, default 2.0
        Time (s) without leaving ``stall_radius`` before :attr:`stalled` is set,
        in [1e-6, 1e6].

    Notes
    -----
    Positions (poses, goals, obstacles) have ``|x|, |y| <= 1e9`` m (the range of
    navkit.planning's fields); the control period ``dt`` of :meth:`step` is in
    [1e-6, 1e6] s. Within these ranges every command is finite.

    A controller takes one :meth:`step` at a time (its PID and stall memories
    change at every step): a step called while another is under way (another
    thread's, or a signal handler's) raises ``RuntimeError``, saying which, and
    changes nothing; the step under way goes on as alone. A :meth:`reset`
    while a step runs wins: that step's command is for the state before it, and
    the next step starts from rest. Different controllers may run in different
    threads at once, also on scans of different scanners.

    Raises
    ------
    TypeError, ValueError
        A parameter of the wrong type or outside its range, naming it; a
        ``goal_tolerance`` not beyond the distance at which the attraction
        brings the robot to rest (see ``goal_tolerance``).

    Notes
    -----
    Subclasses may add attributes (their own ``__slots__`` or an instance
    ``__dict__``) and methods, and override the public methods, calling the
    base's through ``super()``. The base's methods, ``__init__`` included,
    call none of the public ones: an override of :meth:`reset` may clear
    state the subclass's ``__init__`` sets up after ``super().__init__()``. Copies
    and pickles rebuild a subclass as itself, with what it adds (its
    ``__init__`` is not called), and ``repr`` names it. Names with a leading
    underscore are private and may change in any release. The attraction
    may be a field of your own (see :class:`~navkit.planning.PotentialField`).

    Examples
    --------
    >>> from navkit.geometry import integrate
    >>> ctl = PotentialFieldController(max_speed=0.5)
    >>> pose = Pose2D(0.0, 0.0, 0.0)
    >>> target = Pose2D(2.0, 0.0, 0.0)
    >>> for _ in range(200):
    ...     cmd = ctl.step(pose, target, 0.05)
    ...     pose = integrate(pose, cmd, 0.05)
    >>> round(pose.x, 2), ctl.stalled
    (2.0, False)

    The default blend brings the robot to rest 3.75 mm from the goal, so a
    tighter tolerance would never be met:

    >>> PotentialFieldController(goal_tolerance=0.001)
    Traceback (most recent call last):
    ...
    ValueError: goal_tolerance must exceed 0.003751495 m: the attraction (BlendedAttraction ...
    """

    __slots__ = (
        "__weakref__",  # weakref.ref(obj) for callbacks and caches (review 36)
        "_anchor",
        "_attraction",
        "_callers",
        "_drive",
        "_goal_tolerance",
        "_influence_radius",
        "_integral",
        "_k_rep",
        "_last_error",
        "_max_accel",
        "_max_decel",
        "_max_omega",
        "_max_speed",
        "_pid",
        "_stall_radius",
        "_stall_timeout",
        "_still_for",
        "_velocity",
    )

    def __getstate__(self) -> object:
        # Python's default state (pickle protocols 0 and 1 too, see slot_state), not
        # in use whatever the original is doing (pickles as before the guard).
        instance, slots = cast("tuple[dict[str, Any] | None, dict[str, Any]]", slot_state(self))
        slots.pop("_callers", None)
        return instance, slots

    def __init__(
        self,
        attraction: AttractiveField | None = None,
        *,
        k_rep: float = 0.05,
        influence_radius: float = 0.6,
        max_speed: float = 0.5,
        max_accel: float = 1.0,
        max_decel: float = 2.0,
        max_omega: float = 2.0,
        kp: float = 3.0,
        ki: float = 0.0,
        kd: float = 0.1,
        integral_limit: float = 1.0,
        drive: Literal["omni", "diff"] = "omni",
        goal_tolerance: float = 0.05,
        stall_radius: float = 0.05,
        stall_timeout: float = 2.0,
    ) -> None:
        # The steps under way (one at most: see step; not copied or pickled).
        self._callers: list[tuple[int, str, object]] = []
        if attraction is None:
            attraction = BlendedAttraction(np.zeros(2))
        if not isinstance(attraction, AttractiveField):
            raise TypeError(
                f"attraction must be an AttractiveField, got {type(attraction).__name__}"
            )
        if not isinstance(drive, str):
            raise TypeError(f"drive must be 'omni' or 'diff', got {type(drive).__name__}")
        drive = cast(Literal["omni", "diff"], as_text(drive, "drive"))  # checked as stored
        if drive not in ("omni", "diff"):
            raise ValueError(f"drive must be 'omni' or 'diff', got {drive!r}")
        self._attraction = attraction
        self._k_rep = in_range(k_rep, "k_rep", MIN_GAIN, MAX_GAIN)
        self._influence_radius = quantity(influence_radius, "influence_radius", "m")
        # The repulsion is built every step: let it check the two parameters once here.
        KhatibRepulsion(
            np.empty((0, 2)), k_rep=self._k_rep, influence_radius=self._influence_radius
        )
        self._max_speed = quantity(max_speed, "max_speed", "m/s")
        self._max_accel = quantity(max_accel, "max_accel", "m/s²")
        self._max_decel = quantity(max_decel, "max_decel", "m/s²")
        self._max_omega = quantity(max_omega, "max_omega", "rad/s")
        self._drive: Literal["omni", "diff"] = drive
        self._goal_tolerance = quantity(goal_tolerance, "goal_tolerance", "m")
        _check_reachable(self._goal_tolerance, attraction)
        self._stall_radius = quantity(stall_radius, "stall_radius", "m")
        self._stall_timeout = quantity(stall_timeout, "stall_timeout", "s")
        self._pid = _Pid(
            in_range(kp, "kp", 0.0, MAX_GAIN),
            in_range(ki, "ki", 0.0, MAX_GAIN),
            in_range(kd, "kd", 0.0, MAX_GAIN),
            quantity(integral_limit, "integral_limit", "rad·s"),
        )
        # Not reset(): a subclass's override may clear state its own __init__ has
        # not set up yet, when this runs.
        self._clear()

    def reset(self) -> None:
        """Forget the previous velocity, the PID state and the stall timer.

        Call it between runs: the next :meth:`step` starts from rest (its
        acceleration limits measured from a zero velocity) with no stall time,
        also when the reset comes while a step runs (another thread, a signal
        handler): that step's command is for the state before.

        Examples
        --------
        >>> ctl = PotentialFieldController(stall_timeout=0.5)
        >>> for _ in range(8):  # the robot does not move: stalled after 0.5 s
        ...     cmd = ctl.step((0.0, 0.0, 0.0), (2.0, 0.0, 0.0), 0.1)
        >>> ctl.stalled, ctl.previous_velocity
        (True, array([0.5, 0. ]))
        >>> ctl.reset()
        >>> ctl.stalled, ctl.stall_time, ctl.previous_velocity
        (False, 0.0, array([0., 0.]))
        >>> ctl.step((0.0, 0.0, 0.0), (2.0, 0.0, 0.0), 0.1)  # from rest again
        Twist2D(vx=0.1, vy=0.0, omega=0.0)
        """
        self._clear()

    def _clear(self) -> None:
        """Set the run state to rest (what :meth:`reset` does, for ``__init__`` too)."""
        # The new velocity first, then plain stores with no call between them: a step
        # landing at the call finishes on the state before, and this reset wins. The
        # velocity is a new object: a step under way sees it and drops its stores
        # (see step), so a reset landing in a step is not overwritten either.
        velocity: FloatArray = np.zeros(2)
        self._velocity: FloatArray = velocity
        self._integral = 0.0
        self._last_error: float | None = None
        self._anchor: FloatArray | None = None
        self._still_for = 0.0

    def __setstate__(self, state: tuple[dict[str, Any] | None, dict[str, Any]]) -> None:
        """Restore from a pickle or a copy, also one made when the options were attributes."""
        # Pickles from before the options became properties hold them under their
        # public names: setting those would hit the properties, which have no setter.
        restore_slots(self, state, renamed=_RENAMED)
        pid = self._pid
        carried = getattr(pid, "_carried", None)
        if carried is not None:
            # A pickle made before the PID's run state moved here (see _Pid). Then a
            # shallow copy shared its original's _Pid: the other controllers of the
            # same pickle take the state from it too, so it keeps it, and this one
            # gets a _Pid of its own (review 51, FRESH: the second of [ctl,
            # copy.copy(ctl)] loaded without its integrator).
            self._pid = _Pid(pid.kp, pid.ki, pid.kd, pid.integral_limit)
            self._integral, self._last_error = carried
        # Not in use (a copy made during a step, or a pickle of one, holds its token).
        self._callers = []

    # The options are read-only (as the path trackers'): they are validated once,
    # in __init__, and every step relies on their ranges.
    def __repr__(self) -> str:
        # Every option, as the planners and estimators print theirs (eval gives a twin).
        pid = self._pid
        return (
            f"{type(self).__name__}(attraction={self._attraction!r}, k_rep={self._k_rep}, "
            f"influence_radius={self._influence_radius}, max_speed={self._max_speed}, "
            f"max_accel={self._max_accel}, max_decel={self._max_decel}, "
            f"max_omega={self._max_omega}, kp={pid.kp}, ki={pid.ki}, kd={pid.kd}, "
            f"integral_limit={pid.integral_limit}, drive={self._drive!r}, "
            f"goal_tolerance={self._goal_tolerance}, stall_radius={self._stall_radius}, "
            f"stall_timeout={self._stall_timeout})"
        )

    @property
    def attraction(self) -> AttractiveField:
        """The attractive field whose parameters are used (its goal is replaced every step)."""
        return self._attraction

    @property
    def k_rep(self) -> float:
        """Khatib repulsion gain."""
        return self._k_rep

    @property
    def influence_radius(self) -> float:
        """Khatib's ``d0`` (m): obstacles farther than this do not repel."""
        return self._influence_radius

    @property
    def max_speed(self) -> float:
        """Maximum translational speed (m/s)."""
        return self._max_speed

    @property
    def max_accel(self) -> float:
        """Translational acceleration limit (m/s²)."""
        return self._max_accel

    @property
    def max_decel(self) -> float:
        """Translational deceleration limit (m/s²)."""
        return self._max_decel

    @property
    def max_omega(self) -> float:
        """Maximum turn rate (rad/s)."""
        return self._max_omega

    @property
    def drive(self) -> Literal["omni", "diff"]:
        """``"omni"`` (holonomic) or ``"diff"`` (differential drive, ``vy = 0``)."""
        return self._drive

    @property
    def goal_tolerance(self) -> float:
        """Distance (m) within which the goal counts as reached (:attr:`done`)."""
        return self._goal_tolerance

    @property
    def stall_radius(self) -> float:
        """Radius (m) the robot must leave to count as moving."""
        return self._stall_radius

    @property
    def stall_timeout(self) -> float:
        """Time (s) without leaving ``stall_radius`` before :attr:`stalled` is set."""
        return self._stall_timeout

    @property
    def stalled(self) -> bool:
        """True when the robot is stuck away from the goal (a local minimum)."""
        return self._still_for >= self._stall_timeout * (1.0 - _STALL_RTOL)

    @property
    def done(self) -> bool:
        """True when the last :meth:`step` found the robot at its target's position.

        That is within ``goal_tolerance`` of ``target_pose``'s ``(x, y)``, the
        trackers' name for a reached goal. Unlike theirs it is not latched (the
        target may move from one step to the next: each step decides again) and
        says nothing of the heading, which every step keeps driving to
        ``target_pose.theta`` (the trackers' final turn); nor does it stop the
        steps: the attraction still moves the robot to where it settles (3.75 mm
        from the goal with the default :class:`~navkit.planning.BlendedAttraction`).
        False before the first step and after :meth:`reset`; never together with
        :attr:`stalled`. Within ``goal_tolerance`` is the trackers' test too
        (the same function: exact at the boundary, where two ``hypot``
        implementations could disagree by an ulp).

        Examples
        --------
        >>> ctl = PotentialFieldController(drive="diff")
        >>> ctl.done
        False
        >>> ctl.step((2.0, 1e-9, 0.0), (2.0, 0.0, 0.0), 0.1)  # at the goal: no turn
        Twist2D(vx=0.0, vy=0.0, omega=0.0)
        >>> ctl.done
        True
        >>> _ = ctl.step((1.0, 0.0, 0.0), (2.0, 0.0, 0.0), 0.1)
        >>> ctl.done
        False
        """
        # A step within goal_tolerance stores no stall anchor, every other step one;
        # reset clears both the anchor and the last heading error (no step yet).
        return self._anchor is None and self._last_error is not None

    @property
    def stall_time(self) -> float:
        """Seconds the robot has spent within ``stall_radius`` of one spot, away from the goal."""
        return self._still_for

    @property
    def previous_velocity(self) -> FloatArray:
        """Last commanded translational velocity in the world frame (m/s), shape (2,)."""
        out: FloatArray = self._velocity.copy()
        return out

    def desired_velocity(
        self,
        pose: Pose2D | ArrayLike,
        goal_xy: ArrayLike,
        *,
        obstacles: ArrayLike | LaserScan | None = None,
        mount: Pose2D | ArrayLike | None = None,
    ) -> FloatArray:
        """Unlimited field velocity (world frame, clipped to ``max_speed``) at ``pose``.

        Steps 1–3 of the algorithm without the acceleration limits; the
        controller's state is neither read nor changed.

        Parameters
        ----------
        pose : Pose2D or array_like [x, y, theta]
            Robot pose in the world frame.
        goal_xy : array_like, shape (2,)
            Goal ``(x, y)`` in metres, world frame.
        obstacles : array_like (M, 2), LaserScan or None, optional
            As in :meth:`step`.
        mount : Pose2D or array_like [x, y, theta], optional
            As in :meth:`step`: the pose of the scanner in the robot frame.

        Returns
        -------
        ndarray, shape (2,)
            Velocity ``(vx, vy)`` in the world frame (m/s).

        Raises
        ------
        TypeError, ValueError
            An argument that is not what is documented, naming it.

        Examples
        --------
        >>> ctl = PotentialFieldController(max_speed=0.5)
        >>> ctl.desired_velocity([0.0, 0.0, 0.0], (2.0, 0.0))
        array([0.5, 0. ])

        A scan from a LiDAR 0.3 m ahead of the robot's centre (``Lidar(mount=...)``
        in :mod:`navkit.sim`) sees a wall 0.45 m ahead of the sensor, 0.75 m
        from the centre: beyond the 0.6 m ``influence_radius``, so the robot
        goes at full speed. The mount gives what the wall's world points give;
        the scan taken for one in the robot frame puts the wall 0.45 m away,
        which slows the robot:

        >>> scan = LaserScan([0.45], angle_min=0.0, angle_increment=0.1,
        ...                  range_min=0.1, range_max=5.0)
        >>> mount = Pose2D(0.3, 0.0, 0.0)
        >>> ctl.desired_velocity((0.0, 0.0, 0.0), (2.0, 0.0), obstacles=scan, mount=mount)
        array([0.5, 0. ])
        >>> ctl.desired_velocity((0.0, 0.0, 0.0), (2.0, 0.0),
        ...                      obstacles=scan.to_points(Pose2D(0.0, 0.0, 0.0) @ mount))
        array([0.5, 0. ])
        >>> ctl.desired_velocity((0.0, 0.0, 0.0), (2.0, 0.0), obstacles=scan).round(3)  # wrong
        array([0.363, 0.   ])
        """
        p = as_pose(pose, "pose")
        position(p.x, p.y, "pose")
        goal = as_point(goal_xy, "goal_xy")
        position(float(goal[0]), float(goal[1]), "goal_xy")
        return self._desired(p, goal, obstacles, _mount(mount))

    def _desired(
        self,
        pose: Pose2D,
        goal: FloatArray,
        obstacles: ArrayLike | LaserScan | None,
        mount: Pose2D | None = None,
    ) -> FloatArray:
        """:meth:`desired_velocity` on a validated pose, goal and mount."""
        try:
            return self._desired_velocity(pose, goal, obstacles, mount)
        except FloatingPointError:
            # Only under a caller's np.seterr(under="raise"): a field's squared offset
            # of 1e-200 m underflows. The work is pure: done again for NumPy's default
            # answer (a try costs the step nothing, an np.errstate a microsecond).
            with np.errstate(under="ignore"):
                return self._desired_velocity(pose, goal, obstacles, mount)

    def _desired_velocity(
        self,
        pose: Pose2D,
        goal: FloatArray,
        obstacles: ArrayLike | LaserScan | None,
        mount: Pose2D | None = None,
    ) -> FloatArray:
        """:meth:`_desired`'s work."""
        here = np.array([[pose.x, pose.y]])
        attraction = self._attraction
        kind = type(attraction)
        if kind.with_goal is AttractiveField.with_goal and kind.force is PotentialField.force:
            # The goal and the pose were checked (same ranges as the fields'): no
            # second check of either, which cost more than the field's formula.
            f_att = attraction._with_checked_goal(goal)._force(here)[0]
        else:  # a subclass's own with_goal or force may do more: call them
            # Checked: a NaN would pass the clip below and come out as a silent stop.
            raw = attraction.with_goal(goal).force(here)
            f_att = as_float_array(raw, f"{kind.__name__}.force", shape=(1, 2))[0]
        ax, ay = f_att.tolist()
        if not abs(ax) + abs(ay) < 1e300:
            # A user's field whose finite pull is longer than float64 holds (np.hypot
            # would warn and give inf, scaling the pull to zero): its direction at
            # max_speed, as any pull beyond it.
            unit = f_att / max(abs(ax), abs(ay))
            f_att = unit * (self._max_speed / float(np.hypot(unit[0], unit[1])))
        norm = float(np.hypot(f_att[0], f_att[1]))
        if norm > self._max_speed:
            f_att = f_att * (self._max_speed / norm)
        v: FloatArray = f_att + self._repulsion(pose, here, obstacles, mount)
        vx, vy = v.tolist()
        if not (math.isfinite(vx) and math.isfinite(vy)):
            # Not reached with navkit's own fields (the repulsion saturates below 1e-9 m:
            # finite, as the pull clipped above); kept so that an infinite or NaN sum
            # never becomes the command: full speed along infinite components, else 0.
            v = np.where(np.isinf(v), np.sign(v), 0.0)
        speed = float(np.hypot(v[0], v[1]))
        if speed > self._max_speed:
            v = v * (self._max_speed / speed)
        return v

    def _repulsion(
        self,
        pose: Pose2D,
        here: FloatArray,
        obstacles: ArrayLike | LaserScan | None,
        mount: Pose2D | None = None,
    ) -> FloatArray:
        if obstacles is None:
            return np.zeros(2)
        if isinstance(obstacles, LaserScan):
            # The force on the robot's reference point, in the robot frame: from the
            # beams' end points placed with the mount (repulsive_force_from_scan).
            fx, fy = repulsive_force_from_scan(
                obstacles, k_rep=self._k_rep, influence_radius=self._influence_radius,
                mount=mount,
            )  # fmt: skip
            c, s = math.cos(pose.theta), math.sin(pose.theta)
            return np.array([c * fx - s * fy, s * fx + c * fy])
        pts = as_points(obstacles, "obstacles", finite=False)
        # Usually every row is valid: one reduction checks that (a NaN makes the
        # maximum NaN, an infinity exceeds the bound) and no mask is needed.
        valid = pts
        if pts.size and not float(np.max(np.abs(pts))) <= MAX_COORDINATE:
            valid = pts[np.all(np.isfinite(pts), axis=1)]
            if valid.size and float(np.max(np.abs(valid))) > MAX_COORDINATE:
                raise ValueError(
                    f"obstacles: positions must have |x|, |y| <= {MAX_COORDINATE:g} m "
                    "(rows with NaN or inf are skipped)"
                )
        # Checked above (and the parameters in __init__): built without a second check.
        field = KhatibRepulsion._checked(valid, self._k_rep, self._influence_radius)
        # Nothing within reach pushes (exactly zero, as the field's own sum gives):
        # the offsets and distances are those the field forms, so the test is exact.
        d = np.hypot(pose.x - field.obstacles_xy[:, 0], pose.y - field.obstacles_xy[:, 1])
        near = d <= field._reach()
        if not near.any():
            return np.zeros(2)
        if not near.all():
            # Only the points within reach: the field, built for many queries, makes
            # a k-d tree of every point beyond 2**18 of them, which one query of a
            # step paid for in full (1e6 points: 609 ms a step, 41 ms like this;
            # review 27). The sum is over the same pairs in the same order.
            field = KhatibRepulsion._checked(
                field.obstacles_xy[near], self._k_rep, self._influence_radius
            )
        out: FloatArray = field._force(here)[0]
        return out

    def step(
        self,
        pose: Pose2D | ArrayLike,
        target_pose: Pose2D | ArrayLike,
        dt: float,
        *,
        obstacles: ArrayLike | LaserScan | None = None,
        velocity: Twist2D | ArrayLike | None = None,
        mount: Pose2D | ArrayLike | None = None,
    ) -> Twist2D:
        """One control cycle: the velocity command for the next ``dt`` seconds.

        Parameters
        ----------
        pose : Pose2D or array_like [x, y, theta]
            Robot pose in the world frame (m, m, rad).
        target_pose : Pose2D or array_like [x, y, theta]
            Goal position (attraction; m) and the target heading (rad): always for an
            ``"omni"`` drive, for a ``"diff"`` drive within ``goal_tolerance`` of
            the goal or where the desired velocity is below a thousandth of
            ``max_speed``.
        dt : float
            Control period in seconds, in [1e-6, 1e6]; positional or keyword, so a
            control loop calls this as it calls a path tracker's ``step(pose, dt)``.
        obstacles : array_like (M, 2), LaserScan or None, optional
            Obstacle points ``(x, y)`` in m in the world frame (rows with
            NaN/inf are skipped), or a scan in its sensor's frame (the robot
            frame unless ``mount`` says where the sensor sits), or nothing.
        velocity : Twist2D or array_like [vx, vy, omega], optional
            Current robot-frame velocity (m/s, m/s, rad/s; e.g. from odometry, finite; one whose
            world-frame components overflow float64, near 1e308 m/s, is
            refused), the base of the acceleration limits (the command stays
            within ``max_speed`` even when this is faster); ``None`` uses the
            previous command.
        mount : Pose2D or array_like [x, y, theta], optional
            Pose of the scanner that took ``obstacles`` in the robot frame (m,
            m, rad; ``|x|, |y| <= 1e9``), as :class:`navkit.sim.Lidar`'s
            ``mount`` or a ``base_link -> laser`` transform: each beam's end
            point is ``pose ⊕ mount ⊕ (r cos θ, r sin θ)``, as if the scan's
            world points (``scan.to_points(pose @ mount)``) were passed (see
            :func:`~navkit.planning.repulsive_force_from_scan`). None (the
            default): the scan is in the robot frame. Checked, but not used,
            with world points or no obstacles.

        Returns
        -------
        Twist2D
            Command in the robot frame: ``(vx, vy, ω)`` in m/s, m/s, rad/s;
            ``vy = 0`` for a ``"diff"`` drive.

        Raises
        ------
        TypeError, ValueError
            An argument that is not what is documented, naming it; the
            controller's state is unchanged then.
        RuntimeError
            Another step under way (another thread's, or a signal handler's):
            this one changes nothing.

        Examples
        --------
        From rest the speed grows by at most ``max_accel × dt`` (0.1 m/s here);
        an obstacle 0.3 m ahead then pushes harder than the goal pulls, and the
        command reverses by at most ``max_decel × dt`` (0.2 m/s):

        >>> ctl = PotentialFieldController(max_speed=0.5, max_accel=1.0, max_decel=2.0)
        >>> ctl.step(Pose2D(0.0, 0.0, 0.0), Pose2D(2.0, 0.0, 0.0), 0.1)
        Twist2D(vx=0.1, vy=0.0, omega=0.0)
        >>> ctl.step(Pose2D(0.0, 0.0, 0.0), Pose2D(2.0, 0.0, 0.0), 0.1, obstacles=[[0.3, 0.0]])
        Twist2D(vx=-0.1, vy=0.0, omega=0.0)

        A differential drive first turns (at ``max_omega``) toward a goal on its left:

        >>> diff = PotentialFieldController(drive="diff")
        >>> diff.step((0.0, 0.0, 0.0), (0.0, 2.0, 0.0), 0.1)
        Twist2D(vx=0.0, vy=0.0, omega=2.0)

        A scan from a LiDAR mounted on the robot (``navkit.sim.Lidar(mount=...)``,
        whose scans are in its own frame) takes that ``mount``; here one facing
        backwards sees a wall 0.2 m behind the robot, which pushes it forwards:

        >>> behind = LaserScan([0.2], angle_min=0.0, angle_increment=0.1,
        ...                    range_min=0.1, range_max=5.0)
        >>> ctl = PotentialFieldController(max_speed=0.5)
        >>> ctl.step((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), 0.1, obstacles=behind,
        ...          mount=(0.0, 0.0, math.pi))
        Twist2D(vx=0.1, vy=0.0, omega=0.0)
        """
        pose = as_pose(pose, "pose")
        position(pose.x, pose.y, "pose")
        target_pose = _pose(target_pose, "target_pose")
        position(target_pose.x, target_pose.y, "target_pose")
        measured = None if velocity is None else as_twist(velocity, "velocity")
        step = quantity(dt, "dt", "s")
        sensor = None if mount is None else _mount(mount)
        # One step at a time (one_caller's guard, written out): two steps at once (two
        # threads, a signal handler's step inside the main loop's) both started from
        # the state before either, and the later stores won: the other step was lost
        # (its time from the stall clock, its command from the velocity limits' base;
        # review 38).
        callers = self._callers
        # Equal to no other token (its object): see one_caller.
        token = (get_ident(), "step", object())
        running = False
        try:
            callers.append(token)
            if callers[0] is not token:
                raise RuntimeError(_in_use(type(self).__name__, "step", callers[0], callers))
            running = True
            return self._step(pose, target_pose, step, obstacles, measured, sensor)
        finally:
            if running:
                # The step's token is the first (only refused calls' come after it, and
                # they take theirs out): deleted without a call, so that no Ctrl-C can
                # land after the step's stores (a loop catching it would step twice).
                del callers[0]
            else:
                callers.remove(token)

    def _step(
        self,
        pose: Pose2D,
        target_pose: Pose2D,
        step: float,
        obstacles: ArrayLike | LaserScan | None,
        measured: Twist2D | None,
        mount: Pose2D | None = None,
    ) -> Twist2D:
        """:meth:`step` on validated arguments, inside its guard."""
        # The state read at once (no call between the reads, where a signal handler's
        # reset could land): the command is for the state before a reset meanwhile
        # (another thread's, a signal handler's), which installs a new velocity; this
        # step's stores are then dropped, and the reset is not overwritten.
        current = self._velocity
        integral0, last_error, anchor, still_for = (
            self._integral,
            self._last_error,
            self._anchor,
            self._still_for,
        )
        c, s = math.cos(pose.theta), math.sin(pose.theta)
        if measured is None:
            prev = current
        else:
            vx_w = c * measured.vx - s * measured.vy
            vy_w = s * measured.vx + c * measured.vy
            # Beyond ±1e308 m/s the world-frame velocity (or its forward part) overflows.
            if not abs(vx_w) + abs(vy_w) < math.inf:
                raise ValueError("velocity: the velocity overflows float64 (values far too large)")
            prev = np.array([vx_w, vy_w])
        goal = np.array([target_pose.x, target_pose.y])
        want = self._desired(pose, goal, obstacles, mount)
        # np.hypot on the float differences, as array arithmetic on the goal would give.
        # The trackers' test, exact at the boundary (np.hypot here and math.hypot
        # there could disagree by an ulp on whether the goal was reached).
        arrived = at_goal(pose.x, pose.y, target_pose.x, target_pose.y, self._goal_tolerance)
        # A measured speed beyond about 1e154 m/s overflows the norm of the change
        # (handled, but NumPy warns): only then is the limit run under np.errstate,
        # which would cost an ordinary step more than the limit itself.
        huge = measured is not None and not abs(measured.vx) + abs(measured.vy) < 1e150

        if self._drive == "omni":
            v = _limited(prev, want, self._max_accel, self._max_decel, step, huge)
            # A measured velocity above max_speed (an odometry spike, say) would keep the
            # command above it for as long as max_decel takes: max_speed bounds every
            # command, as max_omega does RegulatedPurePursuit's.
            speed = math.hypot(float(v[0]), float(v[1]))
            if speed > self._max_speed:
                v = v * (self._max_speed / speed)
            heading = target_pose.theta
            vx, vy = c * v[0] + s * v[1], -s * v[0] + c * v[1]
        else:
            # Without a measurement, the previous command's forward speed: its world
            # velocity points along the heading it was commanded at, and projected on
            # the current heading it would shrink with every turn, a drop max_decel
            # never limited.
            fwd_prev = math.hypot(prev[0], prev[1]) if measured is None else max(0.0, measured.vx)
            fwd_want = max(0.0, c * want[0] + s * want[1])
            # No faster than max_omega times the radius of the arc that leaves along
            # the heading through the goal (pure pursuit's d² / (2 |y|), the goal's
            # offset subtracted first): a robot that turns slowly otherwise drove
            # past the goal on wider circles than its turn allowed and orbited it,
            # spiralling in for minutes (max_omega=0.1: 6 cm off after 400 s) and
            # reported stalled on the way. Turning at max_omega it stays on or
            # inside that arc, whose heading error to the goal only shrinks.
            gdx, gdy = target_pose.x - pose.x, target_pose.y - pose.y
            lateral = abs(c * gdy - s * gdx)
            if lateral > 0.0:
                arc_speed = self._max_omega * (gdx * gdx + gdy * gdy) / (2.0 * lateral)
                fwd_want = min(fwd_want, arc_speed)
            fwd = float(
                _limited(
                    np.array([fwd_prev]),
                    np.array([fwd_want]),
                    self._max_accel,
                    self._max_decel,
                    step,
                    huge,
                )[0]
            )
            fwd = min(fwd, self._max_speed)  # the bound of every command, as above
            # Below a thousandth of max_speed the field's direction is noise near the goal.
            moving = math.hypot(want[0], want[1]) > 1e-3 * self._max_speed
            # At the goal the field's direction is nothing to steer by: the blend's pull
            # points along the robot's offset however small it is (7 mm/s outward to
            # its minimum 3.75 mm off, with the defaults), so a robot 1e-9 m off the
            # goal turned round at max_omega to drive those millimetres (review 46).
            steer = moving and not arrived
            heading = math.atan2(want[1], want[0]) if steer else target_pose.theta
            v = np.array([c * fwd, s * fwd])
            vx, vy = fwd, 0.0
        error = angle_diff(heading, pose.theta)
        integral, omega = self._pid.update(integral0, last_error, error, step)
        omega = min(max(omega, -self._max_omega), self._max_omega)
        anchor, still_for = _stall_after(pose, step, anchor, still_for, arrived, self._stall_radius)
        out = Twist2D(float(vx), float(vy), float(omega))
        # Every new value first, then plain stores with no call between them, where
        # a Ctrl-C could land: an interrupted step leaves the state as it was, and
        # a loop that catches the interrupt and steps again integrates once.
        if self._velocity is not current:
            # A reset came while this step ran: the next step starts from rest, as the
            # reset said (its stores were overwritten by this step's; review 38).
            return out
        self._integral = integral
        self._last_error = error
        self._velocity = v
        self._anchor = anchor
        self._still_for = still_for
        return out


def _stall_after(
    pose: Pose2D,
    dt: float,
    anchor: FloatArray | None,
    still_for: float,
    arrived: bool,
    stall_radius: float,
) -> tuple[FloatArray | None, float]:
    """The stall anchor and time after a step of ``dt`` at ``pose`` from ``anchor`` and
    ``still_for`` (the controller's, read as its step began); ``arrived``: the pose is
    within ``goal_tolerance`` of the goal (no anchor then: see ``done``)."""
    if arrived:
        return None, 0.0
    # Float by float what array arithmetic gives (np.hypot on the same
    # differences), without building arrays for two coordinates.
    x, y = pose.x, pose.y
    if anchor is None:
        far = True
    else:
        ax, ay = anchor.tolist()
        far = float(np.hypot(x - ax, y - ay)) > stall_radius
    if far:
        return np.array([x, y]), 0.0
    return anchor, still_for + dt


def _limited(
    prev: FloatArray,
    want: FloatArray,
    max_accel: float,
    max_decel: float,
    dt: float,
    huge: bool,
) -> FloatArray:
    """``_limit_change`` of the controller's step, without NumPy's overflow warnings if ``huge``."""
    if huge:
        with np.errstate(over="ignore", invalid="ignore"):
            return _limit_change(prev, want, max_accel, max_decel, dt, "velocity")
    return _limit_change(prev, want, max_accel, max_decel, dt, "velocity")
