"""Player rows with one NaN coordinate are refused, naming the argument and row (session 30).

A row of NaN marks a player not seen; ``[1.0, nan]`` was taken as one too (the
controller skips any row holding a NaN), hiding a broken position upstream.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.behaviours import BehaviourTarget, GameState, attack, support

NAN = math.nan


def _state(**players: Any) -> GameState:
    return GameState(robot_xy=(0.0, 0.0), ball_xy=(1.0, 0.0), own_goal_xy=(-4.5, 0.0),
                     opponent_goal_xy=(4.5, 0.0), **players)  # fmt: skip


@pytest.mark.parametrize("name", ["teammates_xy", "opponents_xy"])
@pytest.mark.parametrize("row", [[1.0, NAN], [NAN, -2.0]])
def test_a_half_nan_player_is_refused_naming_argument_and_row(name: str, row: list[float]) -> None:
    given_rows = np.array([[2.0, 1.0], [NAN, NAN], row])
    before = given_rows.copy()
    with pytest.raises(ValueError, match=rf"^{name}\[2\] is \[.*nan.*\]: .*both NaN") as info:
        _state(**{name: given_rows})
    assert "unseen" in str(info.value)
    np.testing.assert_array_equal(given_rows, before)  # the caller's array untouched


def test_the_first_half_nan_row_is_named() -> None:
    with pytest.raises(ValueError, match=r"^opponents_xy\[1\] is \[nan, 3\.0\]"):
        _state(opponents_xy=[[0.0, 0.0], [NAN, 3.0], [4.0, NAN]])


def test_a_behaviour_target_refuses_a_half_nan_obstacle() -> None:
    with pytest.raises(ValueError, match=r"^obstacles_xy\[0\] is \[1\.0, nan\]"):
        BehaviourTarget((1.0, 0.0), [[1.0, NAN]])


def test_unseen_players_and_float32_rows_still_work() -> None:
    state = _state(teammates_xy=np.array([[NAN, NAN]], dtype=np.float32),
                   opponents_xy=[[2.0, 1.0], [NAN, NAN]])  # fmt: skip
    assert np.isnan(attack(state).obstacles_xy[1]).all()
    assert support(state).obstacles_xy.shape == (4, 2)


@given(rows=st.lists(st.tuples(st.sampled_from([0.5, NAN]), st.sampled_from([-1.0, NAN])),
                     max_size=4))  # fmt: skip
def test_accepted_exactly_when_every_row_is_whole_or_all_nan(
    rows: list[tuple[float, float]],
) -> None:
    whole = all(math.isnan(x) == math.isnan(y) for x, y in rows)
    try:
        state = _state(opponents_xy=np.array(rows, dtype=np.float64).reshape(-1, 2))
    except ValueError as exc:
        assert not whole and str(exc).startswith("opponents_xy[")
    else:
        assert whole and state.opponents_xy.shape == (len(rows), 2)
