"""The sim's messages say "1 cell", "1 column", "1 item", "1 seed" (review 31, FNF).

Before: "rows[0] has 1 cells for 2 columns", "paths[0] must be a (label, value)
pair, got 1 items", "seeds holds 1 seeds for trials=2", and IndoorNav(targets=1)'s
case "wheel odometry vs EKF fusion, 1 targets". They are written by the
shared ``counted`` now. Checked against the source before the fix: each case
failed there.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from navkit.sim import Scene, Table, sweep

CASES: list[tuple[Callable[[], Any], str]] = [
    (lambda: Table("t", ("a",), (("x", "y"),)), "rows[0] has 2 cells for 1 column"),
    (lambda: Table("t", ("a", "b"), (("x",),)), "rows[0] has 1 cell for 2 columns"),
    (lambda: Scene("t", paths=[("only",)]), "paths[0] must be a (label, value) pair, got 1 item"),
    (
        lambda: sweep("omni-apf", trials=2, seeds=[1]),
        "seeds holds 1 seed for trials=2: give one per trial index",
    ),
]


@pytest.mark.parametrize(("make", "message"), CASES, ids=["column", "cell", "item", "seed"])
def test_one_thing_is_singular(make: Callable[[], Any], message: str) -> None:
    with pytest.raises(ValueError) as info:
        make()
    assert str(info.value) == message


def test_indoor_nav_with_one_target_says_target() -> None:
    from navkit.sim.scenarios import IndoorNav

    label = IndoorNav(targets=1).cases(1)[0][0]
    assert label.endswith("EKF fusion, 1 target"), label
