"""Float32 resolutions under their decimal: radii past k cells reach them (review 52, MUTANT32).

PRECISION takes radii in cells of the decimal a float32 resolution stands for
where the float32 lies above it (0.05), and keeps the float32's own cells
where it lies below (0.03 is 0.0299999993 as a float32): there, a radius just
beyond k of those cells reaches the cells k away, which lie within it. Its
tests gave radii of k decimal cells, reached either way: mutants dividing by
the decimal there (in ``reach_cells`` and in the costmap's inscribed radius)
passed them, and left such cells out. The costmap's reach,
``ceil(inflation_radius / resolution)`` cells as Nav2's, was tested with whole
cells only, where a floor passed too: 2.5 cells reach the cells 3 away.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import costmap

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from centred_obstacle import centred_grid, disc

N = 21
C = N // 2
#: Below their decimals as float32s: 0.03 -> 0.029999999329447746, 0.7 -> 0.699999988079071.
BELOW = [float(np.float32(0.03)), float(np.float32(0.7))]


@pytest.mark.parametrize("resolution", BELOW)
def test_a_radius_just_beyond_k_cells_inflates_the_cells_k_away(resolution: float) -> None:
    assert resolution < float(np.format_float_scientific(np.float32(resolution), unique=True))
    grid = centred_grid(N, resolution)
    for k in (1, 2, 3, 5, 8):
        radius = k * resolution * (1.0 + 1e-8)
        np.testing.assert_array_equal(grid.inflate(radius), disc(N, k), err_msg=f"k={k}")


@pytest.mark.parametrize("resolution", BELOW)
def test_the_costmap_inscribes_the_cells_k_away(resolution: float) -> None:
    for k in (1, 2, 3, 5):
        radius = k * resolution * (1.0 + 1e-8)
        cost = costmap(
            centred_grid(N, resolution), robot_radius=radius, inflation_radius=2 * radius
        )
        np.testing.assert_array_equal(cost >= 253, disc(N, k), err_msg=f"k={k}")


@pytest.mark.parametrize("resolution", [0.05, float(np.float32(0.05)), BELOW[0]])
def test_the_inflation_reaches_the_ceiling_of_its_radius_in_cells(resolution: float) -> None:
    cost = costmap(
        centred_grid(N, resolution), robot_radius=resolution, inflation_radius=2.5 * resolution
    )
    row = cost[C, C : C + 5].tolist()
    assert row[:2] == [254, 253]
    assert 0 < row[3] < row[2] < 253  # 3 cells away: within ceil(2.5)
    assert row[4] == 0
