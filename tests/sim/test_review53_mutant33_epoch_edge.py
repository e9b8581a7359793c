"""The epoch-stamp advice ends at 1e10 s, as its docstring says (review 53, MUTANT33).

4aa590d advises times since the start for times up to 1e10 s (epoch stamps
until the year 2286); its tests gave 1.78e9 s and 1e12 s, and mutants ending
the advice before 1e10 s (``<``) or at 1e11 s passed them, as did one
taking a negative query time's sign for its size (any below -1e10 s advised).
"""

from __future__ import annotations

import pytest

from navkit.sim import MovingObstacle

TRACK = [(1.0, 1.0), (1.5, 1.0)]
ADVICE = "epoch stamps? a simulation starts at t = 0"


def test_times_up_to_1e10_s_get_the_advice() -> None:
    with pytest.raises(ValueError) as caught:
        MovingObstacle(0.2, TRACK, [0.0, 1e10])
    assert ADVICE in str(caught.value)
    person = MovingObstacle(0.2, TRACK, [0.0, 1.0])
    with pytest.raises(ValueError) as caught:
        person.position_at(-1e10)
    assert ADVICE in str(caught.value)


def test_times_beyond_1e10_s_get_none() -> None:
    for worst in (1.0000001e10, 5e10):
        with pytest.raises(ValueError, match=r"times must lie within ±1e\+09 s$"):
            MovingObstacle(0.2, TRACK, [0.0, worst])
    person = MovingObstacle(0.2, TRACK, [0.0, 1.0])
    with pytest.raises(ValueError, match=r"got -1000000000000\.0$"):  # its size, not its sign
        person.position_at(-1e12)
