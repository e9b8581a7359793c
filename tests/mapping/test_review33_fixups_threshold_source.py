"""Review 33 (FIXUPS): ``unknown()`` names where a threshold it refuses came from.

``grid.unknown(occupied_thresh=0.0)`` said "free_thresh (0.196) must be smaller
than occupied_thresh (0.0); are the two swapped?", where 0.196 is the grid's
own ``free_thresh``, not a value the caller passed. Checked: against
``_grid.py`` of HEAD the first two tests fail (the old message); the last pins
the message for two thresholds both given (as before).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid


def _grid() -> OccupancyGrid:
    return OccupancyGrid.from_probabilities([[0.1, 0.3, 0.5]], resolution=1.0)


def test_only_occupied_given_names_the_grids_own_free_thresh() -> None:
    grid = _grid()
    with pytest.raises(ValueError) as info:
        grid.unknown(occupied_thresh=0.0)
    assert str(info.value) == (
        f"occupied_thresh (0.0) must be larger than free_thresh ({grid.free_thresh}: the "
        "grid's own, as free_thresh was not given)"
    )


def test_only_free_given_names_the_grids_own_occupied_thresh() -> None:
    grid = _grid()
    with pytest.raises(ValueError) as info:
        grid.unknown(free_thresh=0.9)
    assert str(info.value) == (
        f"free_thresh (0.9) must be smaller than occupied_thresh ({grid.occupied_thresh}: "
        "the grid's own, as occupied_thresh was not given)"
    )


def test_two_thresholds_given_keep_the_swapped_hint() -> None:
    message = (
        r"^free_thresh \(0\.2\) must be smaller than occupied_thresh \(0\.1\); "
        r"are the two swapped\?$"
    )
    with pytest.raises(ValueError, match=message):
        _grid().unknown(occupied_thresh=0.1, free_thresh=0.2)
    with pytest.raises(ValueError, match=message):
        OccupancyGrid(np.zeros((1, 1)), resolution=1.0, occupied_thresh=0.1, free_thresh=0.2)
