"""IndoorNav refuses a comparison tour at the mapping tour's own speed (a duplicate case)."""

from __future__ import annotations

import pytest

from navkit.sim.scenarios import IndoorNav
from navkit.sim.scenarios._indoor_nav_mapping import MAPPING_SPEED


def test_compare_speed_equal_to_the_mapping_speed_is_refused() -> None:
    # It used to add a second "(the map used)" case that summarize merged away.
    with pytest.raises(ValueError, match="compare_speed must differ"):
        IndoorNav(compare_speed=MAPPING_SPEED)


@pytest.mark.parametrize("speed", [0.05, 0.19999, 0.20001, 1.0])
def test_other_speeds_make_distinct_cases(speed: float) -> None:
    cases = [case for case, _ in IndoorNav(compare_speed=speed).cases(1)]
    assert len(set(cases)) == len(cases)
    assert cases[-1].endswith("(for comparison)")
