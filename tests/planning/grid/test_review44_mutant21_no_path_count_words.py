"""A caller's cell planner's own count words are used only when they give its count (review 44).

MUTANT21: ``MapPlanner.plan`` words the count of a caller's planner's
:class:`navkit.NoPathError` as that planner's message ends ("(expanded 5
cells)") only when the number there is the error's ``expanded``; a message
whose number disagrees (a wrapper that re-raised with a total, or a stale
text) gets the bare ``expanded``. A mutant taking the words whatever their
number survived: the tests raised either navkit's own messages or no count.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner


def _walled() -> OccupancyGrid:
    occupied = np.zeros((20, 20), dtype=bool)
    occupied[:, 10] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1)


@pytest.mark.parametrize(
    ("message", "expanded", "tail"),
    [
        ("no way (expanded 5 cells)", 7, " (expanded 7)"),
        ("no way (expanded 7 cells)", 7, " (expanded 7 cells)"),
        ("no way (expanded 70 jump points)", 7, " (expanded 7)"),
        ("no way (expanded 7 jump points)", 7, " (expanded 7 jump points)"),
    ],
)
def test_a_callables_count_words_are_kept_only_with_its_count(
    message: str, expanded: int, tail: str
) -> None:
    def mine(costs: np.ndarray, start: tuple[int, int], goal: tuple[int, int]) -> None:
        raise NoPathError(message, expanded=expanded)

    with pytest.raises(NoPathError) as info:
        MapPlanner(_walled(), planner=mine).plan((0.25, 0.25), (1.75, 0.25))  # type: ignore[arg-type]
    assert str(info.value).endswith("(cell (2, 17))" + tail), info.value
    assert info.value.expanded == expanded
