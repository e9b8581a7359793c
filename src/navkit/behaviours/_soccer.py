"""Soccer game behaviours: which point attracts and which points repel.

The wheeled soccer robot's three behaviours do not change the potential-field
controller, only its inputs. Each function maps a :class:`GameState` to a
:class:`BehaviourTarget` ``(goal_xy, obstacles_xy)`` that any planner or
controller can consume (e.g. :class:`navkit.control.PotentialFieldController`).
Nothing here depends on how the robot is then driven.
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Sequence
from dataclasses import dataclass, field, fields
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_bool, as_point, as_points, bounded_int, finite_float
from navkit.geometry import Pose2D

if TYPE_CHECKING:
    from typing import Self

__all__ = ["BehaviourTarget", "GameState", "attack", "defend", "support"]

#: Documented range of ``possession_radius``, m.
_MIN_RADIUS = 1e-6
_MAX_RADIUS = 1e6


def _point(value: ArrayLike, name: str) -> FloatArray:
    # Fast path (7x quicker; a simulated game builds a state a step): a float64 (2,)
    # array of finite values needs no conversion. Anything else, and a NaN or an
    # infinity, goes through as_point, which raises.
    if type(value) is np.ndarray and value.dtype == np.float64 and value.shape == (2,):
        x, y = value.tolist()
        if x - x == 0.0 and y - y == 0.0:
            out = np.array(value, copy=True)
            out.setflags(write=False)
            return out
    if isinstance(value, Pose2D):
        raise TypeError(f"{name} must be a point (x, y), got a Pose2D: pass (pose.x, pose.y)")
    # A pose [x, y, theta] given whole is named as everywhere else (as_point).
    out = np.array(as_point(value, name), copy=True)
    out.setflags(write=False)
    return out


def _players(value: ArrayLike, name: str) -> FloatArray:
    if isinstance(value, (list, tuple)) and any(isinstance(v, Pose2D) for v in value):
        raise TypeError(
            f"{name} must be points (x, y), got Pose2D items: "
            "pass [(p.x, p.y) for p in poses]"
        )
    # Rows of poses (N, 3), or one pose (3,), are named by as_points itself.
    out = np.array(as_points(value, name, finite=False), copy=True)
    if np.isinf(out).any():
        raise ValueError(f"{name} must be finite (NaN rows mark unseen players)")
    nan = np.isnan(out)
    if nan.any():
        # A row with one NaN coordinate is no unseen player but a broken position
        # (a tracker's or a conversion's fault): the controller would skip it as unseen.
        half = nan.any(axis=1) & ~nan.all(axis=1)
        if half.any():
            row = int(np.argmax(half))
            raise ValueError(
                f"{name}[{row}] is {out[row].tolist()}: a row is a seen player (finite x "
                "and y) or an unseen one (both NaN), not half of each"
            )
    out.setflags(write=False)
    return out


def _restore(record: Any, state: Sequence[Any]) -> None:
    """``__setstate__`` of the records, for pickles made before their ``__reduce__``.

    Those hold the field values as a list; pickle hands the arrays back
    writable, so they are made read-only again.
    """
    restore_read_only(record, state, [f.name for f in fields(record)])


def _no_players() -> FloatArray:
    return np.empty((0, 2), dtype=np.float64)


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False, init=False)
class BehaviourTarget:
    """What a behaviour asks for: a goal and the points that repel.

    Parameters
    ----------
    goal_xy : array_like, shape (2,)
        Point ``(x, y)`` (m) to be attracted to; finite.
    obstacles_xy : array_like, shape (M, 2)
        Points ``(x, y)`` (m) that repel; rows of NaN are players that are not
        currently seen (the controller skips them). ``M = 0`` is valid.
        Infinities are refused, and so is a row with one NaN coordinate (a
        position half known is a fault upstream, not an unseen player).

    Notes
    -----
    Both arrays are stored as read-only copies (the caller's arrays are never
    made read-only or modified). A target pickled when this class was a
    ``NamedTuple`` (5e5f83f, 30 November 2026, and before) loads with its
    values, checked as here (protocol 2 and above; protocols 0 and 1 pickled
    it as a tuple, which cannot load as this record: TypeError).

    Raises
    ------
    TypeError, ValueError
        An argument of the wrong type, shape or values, naming it.

    Examples
    --------
    >>> target = BehaviourTarget((1.0, 0.0), [[2.0, 1.0], [np.nan, np.nan]])
    >>> target.goal_xy, target.obstacles_xy.shape
    (array([1., 0.]), (2, 2))
    """

    goal_xy: FloatArray
    obstacles_xy: FloatArray

    __reduce__ = reduce_record
    __setstate__ = _restore

    def __init__(self, goal_xy: ArrayLike, obstacles_xy: ArrayLike) -> None:
        if hasattr(self, "goal_xy"):
            return  # built by __new__ (below), from these same arguments
        object.__setattr__(self, "goal_xy", _point(goal_xy, "goal_xy"))
        object.__setattr__(self, "obstacles_xy", _players(obstacles_xy, "obstacles_xy"))

    def __new__(cls, *values: Any, **named: Any) -> Self:
        # At 5e5f83f (30 November 2026) BehaviourTarget was a NamedTuple: its pickles
        # call BehaviourTarget.__new__(BehaviourTarget, goal, obstacles) and nothing
        # else, and loaded with no field set. So a BehaviourTarget is built here, the
        # values checked as __init__ checks them (which then finds it built: checked
        # once); a subclass is left to its own __init__ (or this one, inherited).
        target = object.__new__(cls)
        if cls is BehaviourTarget and (values or named):
            target.__init__(*values, **named)  # type: ignore[misc]
        return target

    # inspect.signature(BehaviourTarget) reads __new__ first: it shows __init__'s.
    __new__.__signature__ = inspect.signature(__init__)  # type: ignore[attr-defined]

    def __post_init__(self) -> None:
        # A dataclass subclass's generated __init__ sets the fields as given, then this.
        object.__setattr__(self, "goal_xy", _point(self.goal_xy, "goal_xy"))
        object.__setattr__(self, "obstacles_xy", _players(self.obstacles_xy, "obstacles_xy"))

    @classmethod
    def _of(cls, goal_xy: FloatArray, obstacles_xy: FloatArray) -> BehaviourTarget:
        """A target from a GameState's arrays (checked when it was built), unchecked.

        The behaviours' constructor: the public one would check them again.
        """
        target: BehaviourTarget = object.__new__(cls)
        for name, value in (("goal_xy", goal_xy), ("obstacles_xy", obstacles_xy)):
            out = np.array(value, copy=True)
            out.setflags(write=False)
            object.__setattr__(target, name, out)
        return target


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False, kw_only=True)
class GameState:
    """Positions in one frame (usually the field frame), in metres.

    Every argument is keyword-only (nine positions are too easy to swap). The
    arrays are stored as read-only copies (the caller's arrays are never made
    read-only or modified); ``has_ball`` and ``opponent_with_ball``, when
    omitted, are inferred on construction, so after it ``has_ball`` is always a
    bool. Positions are any finite numbers (NaN rows only for unseen players:
    both coordinates NaN; a row with one NaN is refused, naming it).
    ``dataclasses.replace`` passes the values inferred for the old positions on
    as given ones: pass ``has_ball=None, opponent_with_ball=None`` with new
    positions to have them inferred again.

    Parameters
    ----------
    robot_xy : array_like, shape (2,)
        This robot's position.
    ball_xy : array_like, shape (2,)
        Ball position.
    teammates_xy : array_like, shape (K, 2), default no teammates
        The other robots of this team (NaN rows: not seen).
    opponents_xy : array_like, shape (L, 2), default no opponents
        The opposing robots (NaN rows: not seen).
    own_goal_xy, opponent_goal_xy : array_like, shape (2,)
        Centres of the goal this team defends and of the one it attacks.
    has_ball : bool, optional
        Whether this robot holds the ball (a ``bool``); inferred when omitted as
        ``‖robot_xy - ball_xy‖ <= possession_radius``.
    opponent_with_ball : int, optional
        Index into ``opponents_xy`` of the opponent holding the ball; inferred
        when omitted as the nearest seen opponent within ``possession_radius``
        (``‖opponent - ball_xy‖ <= possession_radius``, computed as for
        ``has_ball``: an opponent exactly at the radius holds it), the lowest
        index among opponents equally near; None if there is none, if there
        are no opponents, or if this robot holds the ball. A given index is
        taken as given, also one of an unseen (NaN) row or when ``has_ball``
        is true (a contested ball).
    possession_radius : float, default 0.25
        Distance (m) within which a player holds the ball, in [1e-6, 1e6].

    Raises
    ------
    TypeError, ValueError
        An argument of the wrong type, shape or range, naming it.

    Examples
    --------
    >>> state = GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0), teammates_xy=[[-2.0, 1.0]],
    ...                   opponents_xy=[[1.1, 0.0], [3.0, -1.0]], own_goal_xy=(-4.5, 0.0),
    ...                   opponent_goal_xy=(4.5, 0.0))
    >>> state.has_ball, state.opponent_with_ball
    (False, 0)
    """

    robot_xy: FloatArray
    ball_xy: FloatArray
    teammates_xy: FloatArray = field(default_factory=_no_players)
    opponents_xy: FloatArray = field(default_factory=_no_players)
    own_goal_xy: FloatArray
    opponent_goal_xy: FloatArray
    # As ``__post_init__`` leaves it: always a bool (None, the default, asks for it
    # to be inferred; the declared ``__init__`` below takes it).
    has_ball: bool = None  # type: ignore[assignment]
    opponent_with_ball: int | None = None
    possession_radius: float = 0.25

    __reduce__ = reduce_record
    __setstate__ = _restore
    # Fields renamed since a release (issue 11), for pickles made before (see
    # navkit._shared.frozen.restore_read_only). Not annotated: it would be a field.
    _renamed_fields = MappingProxyType({
        "robot": "robot_xy", "ball": "ball_xy", "teammates": "teammates_xy",
        "opponents": "opponents_xy", "own_goal": "own_goal_xy",
        "opponent_goal": "opponent_goal_xy",
    })  # fmt: skip

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            *,
            robot_xy: ArrayLike,
            ball_xy: ArrayLike,
            teammates_xy: ArrayLike = ...,
            opponents_xy: ArrayLike = ...,
            own_goal_xy: ArrayLike,
            opponent_goal_xy: ArrayLike,
            has_ball: bool | None = ...,
            opponent_with_ball: int | None = ...,
            possession_radius: float = ...,
        ) -> None: ...

    def __post_init__(self) -> None:
        setter = object.__setattr__
        setter(self, "robot_xy", _point(self.robot_xy, "robot_xy"))
        setter(self, "ball_xy", _point(self.ball_xy, "ball_xy"))
        setter(self, "own_goal_xy", _point(self.own_goal_xy, "own_goal_xy"))
        setter(self, "opponent_goal_xy", _point(self.opponent_goal_xy, "opponent_goal_xy"))
        setter(self, "teammates_xy", _players(self.teammates_xy, "teammates_xy"))
        setter(self, "opponents_xy", _players(self.opponents_xy, "opponents_xy"))
        radius = finite_float(self.possession_radius, "possession_radius")
        if not _MIN_RADIUS <= radius <= _MAX_RADIUS:
            raise ValueError(
                f"possession_radius must be in [{_MIN_RADIUS:g}, {_MAX_RADIUS:g}] m, got {radius!r}"
            )
        setter(self, "possession_radius", radius)
        given: object = self.has_ball  # None before inference, whatever the field says
        if given is None:
            # Python floats: a distance beyond the float range is inf, without a warning.
            rx, ry = self.robot_xy.tolist()
            bx, by = self.ball_xy.tolist()
            has_ball = math.hypot(rx - bx, ry - by) <= radius
        else:
            has_ball = as_bool(given, "has_ball")
        setter(self, "has_ball", has_ball)
        holder = self.opponent_with_ball
        n_opponents = self.opponents_xy.shape[0]
        if holder is None:
            holder = self._nearest_holder(radius)
        else:
            holder = bounded_int(holder, "opponent_with_ball", or_none=True)
            if not 0 <= holder < n_opponents:
                raise ValueError(
                    f"opponent_with_ball {holder} is not an index into {n_opponents} opponents"
                )
        setter(self, "opponent_with_ball", holder)

    def _nearest_holder(self, radius: float) -> int | None:
        if self.has_ball:
            return None
        # math.hypot, as for has_ball: NumPy's hypot differs from it in the last bit
        # for about 1 offset in 170, so a robot and an opponent at the same distance
        # could be judged apart at the radius. (An unseen row's NaN is never <=.)
        bx, by = self.ball_xy.tolist()
        holder, nearest = None, radius
        for k, (x, y) in enumerate(self.opponents_xy.tolist()):
            d = math.hypot(x - bx, y - by)
            if d < nearest or (holder is None and d == nearest):
                holder, nearest = k, d
        return holder


def _check(state: GameState) -> GameState:
    if not isinstance(state, GameState):
        raise TypeError(f"state must be a GameState, got {type(state).__name__}")
    return state


def attack(state: GameState) -> BehaviourTarget:
    """Attack: go for the ball, or for the opponents' goal when holding it; opponents repel.

    Parameters
    ----------
    state : GameState
        Positions of the robot, the ball, the players and the goals (m).

    Returns
    -------
    BehaviourTarget
        ``goal_xy`` the ball (the opponents' goal when ``state.has_ball``);
        ``obstacles_xy`` every opponent (NaN rows kept: unseen players).

    Raises
    ------
    TypeError
        If ``state`` is not a :class:`GameState`.

    Examples
    --------
    >>> state = GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0), opponents_xy=[[2.0, 1.0]],
    ...                   own_goal_xy=(-4.5, 0.0), opponent_goal_xy=(4.5, 0.0))
    >>> attack(state).goal_xy
    array([1., 0.])
    >>> attack(state).obstacles_xy
    array([[2., 1.]])
    """
    s = _check(state)
    goal = s.opponent_goal_xy if s.has_ball else s.ball_xy
    return BehaviourTarget._of(goal, s.opponents_xy)


def support(state: GameState) -> BehaviourTarget:
    """Support: go half way from the ball to the own goal; all players and the own goal repel.

    Parameters
    ----------
    state : GameState
        Positions of the robot, the ball, the players and the goals (m).

    Returns
    -------
    BehaviourTarget
        ``goal_xy`` the midpoint of the ball and the own goal;
        ``obstacles_xy`` the teammates, then the opponents, then the own goal
        (shape ``(K + L + 1, 2)``).

    Raises
    ------
    TypeError
        If ``state`` is not a :class:`GameState`.

    Examples
    --------
    >>> state = GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0), teammates_xy=[[-1.0, 2.0]],
    ...                   opponents_xy=[[2.0, 1.0]], own_goal_xy=(-4.5, 0.0),
    ...                   opponent_goal_xy=(4.5, 0.0))
    >>> target = support(state)
    >>> target.goal_xy
    array([-1.75,  0.  ])
    >>> target.obstacles_xy
    array([[-1. ,  2. ],
           [ 2. ,  1. ],
           [-4.5,  0. ]])
    """
    s = _check(state)
    # 0.5*(a + b) is the correctly rounded midpoint: the sum rounds only where its
    # half is normal (halving it is then exact), and is exact where halving rounds.
    # Only where a + b overflows are the halves added, which cannot overflow.
    # Halving first lost sub-normal halves' last bit: the midpoint of 5e-324 and
    # 5e-324 came out 0.
    with np.errstate(over="ignore"):
        total = s.ball_xy + s.own_goal_xy
    goal = np.where(np.isfinite(total), 0.5 * total, 0.5 * s.ball_xy + 0.5 * s.own_goal_xy)
    obstacles = np.concatenate((s.teammates_xy, s.opponents_xy, s.own_goal_xy[None, :]), axis=0)
    return BehaviourTarget._of(goal, obstacles)


def defend(state: GameState) -> BehaviourTarget:
    """Defence: go for the ball; the opponents not holding it repel.

    The opponent holding the ball does not repel, so the robot can close in to
    take it.

    Parameters
    ----------
    state : GameState
        Positions of the robot, the ball, the players and the goals (m).

    Returns
    -------
    BehaviourTarget
        ``goal_xy`` the ball; ``obstacles_xy`` the opponents except
        ``state.opponent_with_ball``.

    Raises
    ------
    TypeError
        If ``state`` is not a :class:`GameState`.

    Examples
    --------
    >>> state = GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0),
    ...                   opponents_xy=[[1.1, 0.0], [2.0, 1.0]], own_goal_xy=(-4.5, 0.0),
    ...                   opponent_goal_xy=(4.5, 0.0))
    >>> defend(state).obstacles_xy
    array([[2., 1.]])
    """
    s = _check(state)
    keep = np.ones(s.opponents_xy.shape[0], dtype=bool)
    if s.opponent_with_ball is not None:
        keep[s.opponent_with_ball] = False
    return BehaviourTarget._of(s.ball_xy, s.opponents_xy[keep])
