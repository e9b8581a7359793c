"""Soccer game behaviours: which point attracts and which points repel.

The wheeled soccer robot's three behaviours do not change the potential-field
controller, only its inputs. Each function maps a :class:`GameState` to a
:class:`BehaviourTarget` ``(goal, obstacles)`` that any planner or controller can
consume (e.g. :class:`navkit.control.PotentialFieldController`). They live in the
planning layer because choosing the goal and the obstacle set is planning, and
nothing here depends on how the robot is then driven.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.validation import as_float_array, as_points, positive_float

__all__ = ["BehaviourTarget", "GameState", "attack", "defend", "support"]

FloatArray = NDArray[np.float64]


class BehaviourTarget(NamedTuple):
    """What a behaviour asks for: a goal and the points that repel.

    Attributes
    ----------
    goal : ndarray, shape (2,)
        Point ``(x, y)`` (m) to be attracted to.
    obstacles : ndarray, shape (M, 2)
        Points ``(x, y)`` (m) that repel; rows of NaN are players that are not
        currently seen (the controller skips them).
    """

    goal: FloatArray
    obstacles: FloatArray


def _point(value: ArrayLike, name: str) -> FloatArray:
    out = np.array(as_float_array(value, name, shape=(2,)), copy=True)
    out.setflags(write=False)
    return out


def _players(value: ArrayLike, name: str) -> FloatArray:
    out = np.array(as_points(value, name, finite=False), copy=True)
    if np.isinf(out).any():
        raise ValueError(f"{name} must be finite (NaN rows mark unseen players)")
    out.setflags(write=False)
    return out


@dataclass(frozen=True, eq=False, init=False)
class GameState:
    """Positions in one frame (usually the field frame), in metres.

    Parameters
    ----------
    robot : array_like, shape (2,)
        This robot's position.
    ball : array_like, shape (2,)
        Ball position.
    teammates : array_like, shape (K, 2)
        The other robots of this team (may be empty; NaN rows: not seen).
    opponents : array_like, shape (L, 2)
        The opposing robots (may be empty; NaN rows: not seen).
    own_goal, opponent_goal : array_like, shape (2,)
        Centres of the goal this team defends and of the one it attacks.
    has_ball : bool, optional
        Whether this robot holds the ball; inferred when omitted as
        ``‖robot - ball‖ <= possession_radius``.
    opponent_with_ball : int, optional
        Index into ``opponents`` of the opponent holding the ball; inferred when
        omitted as the nearest seen opponent within ``possession_radius`` (none
        if there is none or this robot holds the ball).
    possession_radius : float, default 0.25
        Distance (m) within which a player holds the ball, > 0.

    Examples
    --------
    >>> state = GameState(robot=(0.0, 0.0), ball=(1.0, 0.0), teammates=[[-2.0, 1.0]],
    ...                   opponents=[[1.1, 0.0], [3.0, -1.0]], own_goal=(-4.5, 0.0),
    ...                   opponent_goal=(4.5, 0.0))
    >>> state.has_ball, state.opponent_with_ball
    (False, 0)
    """

    robot: FloatArray
    ball: FloatArray
    teammates: FloatArray
    opponents: FloatArray
    own_goal: FloatArray
    opponent_goal: FloatArray
    has_ball: bool
    opponent_with_ball: int | None
    possession_radius: float

    def __init__(
        self,
        robot: ArrayLike,
        ball: ArrayLike,
        teammates: ArrayLike,
        opponents: ArrayLike,
        own_goal: ArrayLike,
        opponent_goal: ArrayLike,
        has_ball: bool | None = None,
        opponent_with_ball: int | None = None,
        possession_radius: float = 0.25,
    ) -> None:
        setter = object.__setattr__
        setter(self, "robot", _point(robot, "robot"))
        setter(self, "ball", _point(ball, "ball"))
        setter(self, "own_goal", _point(own_goal, "own_goal"))
        setter(self, "opponent_goal", _point(opponent_goal, "opponent_goal"))
        setter(self, "teammates", _players(teammates, "teammates"))
        setter(self, "opponents", _players(opponents, "opponents"))
        radius = positive_float(possession_radius, "possession_radius")
        setter(self, "possession_radius", radius)
        if has_ball is None:
            has_ball = float(np.hypot(*(self.robot - self.ball))) <= radius
        elif not isinstance(has_ball, (bool, np.bool_)):
            raise TypeError(f"has_ball must be a bool or None, got {type(has_ball).__name__}")
        setter(self, "has_ball", bool(has_ball))
        holder = opponent_with_ball
        if holder is None:
            holder = self._nearest_holder(radius)
        elif isinstance(holder, bool) or not isinstance(holder, (int, np.integer)):
            raise TypeError(f"opponent_with_ball must be an int or None, got {holder!r}")
        elif not 0 <= int(holder) < self.opponents.shape[0]:
            raise ValueError(
                f"opponent_with_ball {holder} is not an index into {self.opponents.shape[0]} "
                "opponents"
            )
        setter(self, "opponent_with_ball", None if holder is None else int(holder))

    def _nearest_holder(self, radius: float) -> int | None:
        if self.has_ball or self.opponents.shape[0] == 0:
            return None
        dist = np.hypot(*(self.opponents - self.ball).T)
        dist = np.where(np.isnan(dist), np.inf, dist)
        k = int(np.argmin(dist))
        return k if dist[k] <= radius else None


def _check(state: GameState) -> GameState:
    if not isinstance(state, GameState):
        raise TypeError(f"state must be a GameState, got {type(state).__name__}")
    return state


def attack(state: GameState) -> BehaviourTarget:
    """Attack: go for the ball, or for the opponents' goal when holding it; opponents repel.

    Examples
    --------
    >>> state = GameState((0.0, 0.0), (1.0, 0.0), [], [[2.0, 1.0]], (-4.5, 0.0), (4.5, 0.0))
    >>> attack(state).goal
    array([1., 0.])
    >>> attack(state).obstacles
    array([[2., 1.]])
    """
    s = _check(state)
    goal = s.opponent_goal if s.has_ball else s.ball
    return BehaviourTarget(goal.copy(), s.opponents.copy())


def support(state: GameState) -> BehaviourTarget:
    """Support: go half way from the ball to the own goal; all players and the own goal repel.

    Examples
    --------
    >>> state = GameState((0.0, 0.0), (1.0, 0.0), [[-1.0, 2.0]], [[2.0, 1.0]],
    ...                   (-4.5, 0.0), (4.5, 0.0))
    >>> target = support(state)
    >>> target.goal
    array([-1.75,  0.  ])
    >>> target.obstacles
    array([[-1. ,  2. ],
           [ 2. ,  1. ],
           [-4.5,  0. ]])
    """
    s = _check(state)
    goal = 0.5 * (s.ball + s.own_goal)
    obstacles = np.concatenate((s.teammates, s.opponents, s.own_goal[None, :]), axis=0)
    return BehaviourTarget(goal, obstacles)


def defend(state: GameState) -> BehaviourTarget:
    """Defence: go for the ball; the opponents not holding it repel.

    The opponent holding the ball does not repel, so the robot can close in to
    take it.

    Examples
    --------
    >>> state = GameState((0.0, 0.0), (1.0, 0.0), [], [[1.1, 0.0], [2.0, 1.0]],
    ...                   (-4.5, 0.0), (4.5, 0.0))
    >>> defend(state).obstacles
    array([[2., 1.]])
    """
    s = _check(state)
    keep = np.ones(s.opponents.shape[0], dtype=bool)
    if s.opponent_with_ball is not None:
        keep[s.opponent_with_ball] = False
    return BehaviourTarget(s.ball.copy(), s.opponents[keep])
