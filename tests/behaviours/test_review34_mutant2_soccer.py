"""GameState rules and record contracts that no earlier test pinned down.

Found by mutation testing (session 38): ``ry - by`` replaced by ``ry + by`` in the
has_ball distance and ``y - by`` by ``y + by`` in the opponents' distances survived
(every earlier case put the ball on the x axis); so did dropping the copy of an
``ndarray`` subclass's point, ``GameState.__setstate__`` and ``eq=False``.
The oracles here are distances computed independently with NumPy.
"""

from __future__ import annotations

import copy
import pickle
from typing import Any

import numpy as np

from navkit.behaviours import BehaviourTarget, GameState

GOALS: dict[str, Any] = {"own_goal_xy": (-4.5, 0.0), "opponent_goal_xy": (4.5, 0.0)}


def _random_points(rng: np.random.Generator, n: int) -> np.ndarray:
    return rng.uniform(-3.0, 3.0, size=(n, 2))


def test_has_ball_is_the_euclidean_distance_off_the_x_axis() -> None:
    # Robot and ball 0.1 m apart, both 1 m above the x axis: within the radius.
    near = GameState(robot_xy=(0.0, 1.0), ball_xy=(0.0, 1.1), **GOALS)
    assert near.has_ball is True
    rng = np.random.default_rng(34)
    checked = 0
    for robot, ball in zip(_random_points(rng, 400), _random_points(rng, 400), strict=True):
        radius = float(rng.uniform(0.1, 3.0))
        d = float(np.linalg.norm(robot - ball))
        if abs(d - radius) < 1e-9:
            continue  # the boundary is pinned by test_review9_soccer_mutation_gaps
        state = GameState(robot_xy=robot, ball_xy=ball, possession_radius=radius, **GOALS)
        assert state.has_ball is (d <= radius)
        checked += 1
    assert checked > 350


def test_the_ball_holder_is_the_nearest_opponent_within_the_radius() -> None:
    rng = np.random.default_rng(3401)
    holders = 0
    for _ in range(300):
        ball = rng.uniform(-3.0, 3.0, size=2)
        # Opponents scattered around the ball, some within the radius.
        opponents = ball + rng.uniform(-1.0, 1.0, size=(int(rng.integers(1, 6)), 2))
        radius = float(rng.uniform(0.2, 1.0))
        # The robot far away: it does not hold the ball.
        state = GameState(
            robot_xy=ball + 10.0,
            ball_xy=ball,
            opponents_xy=opponents,
            possession_radius=radius,
            **GOALS,
        )
        d = np.linalg.norm(opponents - ball, axis=1)
        if np.any(np.abs(d - radius) < 1e-9) or np.unique(d).size < d.size:
            continue
        expected = int(np.argmin(d)) if d.min() <= radius else None
        assert state.opponent_with_ball == expected
        holders += expected is not None
    assert holders > 50


class _Tagged(np.ndarray):
    """An ndarray subclass (as a user's units-tagged array): not the fast path's ndarray."""


def test_points_given_as_an_ndarray_subclass_are_copied() -> None:
    robot = np.array([1.0, 2.0]).view(_Tagged)
    ball = np.array([1.5, 2.0]).view(_Tagged)
    state = GameState(robot_xy=robot, ball_xy=ball, **GOALS)
    target = BehaviourTarget(ball, np.empty((0, 2)))
    robot[0] = 99.0
    ball[1] = -99.0
    assert state.robot_xy.tolist() == [1.0, 2.0]
    assert state.ball_xy.tolist() == [1.5, 2.0]
    assert target.goal_xy.tolist() == [1.5, 2.0]
    # The caller's arrays are still writable (inputs are never modified).
    assert robot.flags.writeable and ball.flags.writeable


class _Linked(GameState):
    """A user's subclass keeping a reference back to the record (a parent link)."""

    __slots__ = ("me",)


def test_a_copied_subclass_refers_back_to_the_new_record() -> None:
    state = _Linked(robot_xy=(0.0, 0.0), ball_xy=(1.0, 1.0), **GOALS)
    object.__setattr__(state, "me", state)
    # (A shallow copy shares the link with the original, as for any Python object.)
    for twin in (copy.deepcopy(state), pickle.loads(pickle.dumps(state))):
        assert type(twin) is _Linked
        assert twin.me is twin
        assert twin.ball_xy.tolist() == [1.0, 1.0]
        assert not twin.ball_xy.flags.writeable


def test_records_compare_by_identity_and_hash() -> None:
    # Records of arrays: a field-wise == would ask NumPy for the truth of an array.
    state = GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 1.0), **GOALS)
    target = BehaviourTarget((1.0, 1.0), [[2.0, 1.0]])
    for record in (state, target):
        twin = copy.deepcopy(record)
        assert record == record
        assert record != twin
        assert len({record, twin}) == 2
