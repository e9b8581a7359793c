"""``sweep`` given a Scenario class, not an instance, says to build one (review 25)."""

from __future__ import annotations

import pytest

from navkit.sim import sweep
from navkit.sim.scenarios import get_scenario


def test_a_scenario_class_is_named_with_the_fix() -> None:
    cls = get_scenario("soccer")
    with pytest.raises(TypeError, match=rf"got the class {cls.__name__}: pass an instance"):
        sweep(cls, trials=1)  # type: ignore[arg-type]


def test_other_objects_keep_their_type_in_the_message() -> None:
    with pytest.raises(TypeError, match="got int"):
        sweep(3, trials=1)  # type: ignore[arg-type]
