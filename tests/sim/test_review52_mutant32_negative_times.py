"""A negative query time gets the epoch-stamp advice by its magnitude (review 52, MUTANT32).

PRECISION's advice for times out of range ("epoch stamps? a simulation starts
at t = 0") is given for magnitudes up to 1e10 s. Its tests used positive
times only: a mutant passing the signed time passed them, and gave the
advice for -1e12 s (no epoch) where it must not.
"""

from __future__ import annotations

import pytest

from navkit.sim import MovingObstacle

TRACK = [(1.0, 1.0), (1.5, 1.0)]
ADVICE = "epoch stamps? a simulation starts at t = 0"


def test_a_far_negative_time_gets_no_epoch_advice() -> None:
    person = MovingObstacle(0.2, TRACK, [0.0, 1.0])
    with pytest.raises(ValueError, match=r"t must lie within ±1e\+09 s, got -1000000000000\.0$"):
        person.position_at(-1e12)


def test_a_negative_epoch_sized_time_gets_it() -> None:
    person = MovingObstacle(0.2, TRACK, [0.0, 1.0])
    with pytest.raises(ValueError) as info:
        person.position_at(-1.78e9)
    assert ADVICE in str(info.value)
