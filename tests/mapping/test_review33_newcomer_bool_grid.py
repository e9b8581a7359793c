"""A boolean occupancy mask given to ``OccupancyGrid(...)`` names ``from_occupancy`` (s37 review).

A newcomer's first grid is a boolean mask (the README's quick start builds one);
``OccupancyGrid(mask, resolution=0.1)`` answered "logodds must hold real
numbers, got dtype bool", which does not say how to make a grid of a mask.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid


def test_a_boolean_mask_names_from_occupancy() -> None:
    mask = np.zeros((4, 6), dtype=bool)
    mask[1, 2] = True
    kept = mask.copy()
    with pytest.raises(TypeError) as caught:
        OccupancyGrid(mask, resolution=0.1)
    assert str(caught.value) == (
        "logodds must hold real numbers, got dtype bool: make a grid of a boolean "
        "occupancy mask with OccupancyGrid.from_occupancy(mask, resolution=...)"
    )
    np.testing.assert_array_equal(mask, kept)
    # The constructor it names takes the same mask.
    grid = OccupancyGrid.from_occupancy(mask, resolution=0.1)
    np.testing.assert_array_equal(grid.occupied(), mask)


def test_a_real_array_is_still_log_odds() -> None:
    grid = OccupancyGrid(np.zeros((4, 6)), resolution=0.1)
    assert grid.shape == (4, 6) and not grid.occupied().any()
