"""Review 19 (FRESH2): ``distance_field`` keeps its documented peak on grids with a short side.

The field is returned as a view of its padded work buffer (numpy 2.5's shrinking
``resize`` copies), or as a copy where the border is most of what a view would keep
alive. The copy is made while the padded field is alive: 8 more bytes a cell of peak.
With a 2 % threshold every uniform grid with a side under about 100 cells (a 200 x 200
map, a 90 x 5000 corridor) was copied and peaked at 16 bytes a cell, not the 9 the
notes give; a copy is now left for sides of a few cells.
"""

from __future__ import annotations

import numpy as np
import pytest

from memory_peak import peak_bytes
from navkit.planning import distance_field


@pytest.mark.parametrize("shape", [(60, 3000), (200, 200), (3000, 60)])
def test_uniform_grid_with_a_short_side_peaks_near_nine_bytes_a_cell(
    shape: tuple[int, int],
) -> None:
    costs = np.ones(shape)
    peak, field = peak_bytes(lambda: distance_field(costs, (0, 0)))
    rows, cols = shape
    padded = (rows + 2) * (cols + 2) / costs.size
    assert peak / costs.size < 9.0 * padded + 2.0  # + the queue; a copy would add 8
    assert field.shape == shape and field.flags.c_contiguous and field.flags.writeable
    assert field[0, 0] == 0.0 and field[-1, -1] == pytest.approx(
        distance_field(costs.copy(order="F"), (0, 0))[-1, -1]
    )


@pytest.mark.parametrize("shape", [(1, 50_000), (3, 20_000), (20_000, 2), (1, 1), (5, 5)])
def test_grids_with_a_side_of_a_few_cells_get_a_copy_of_their_own(
    shape: tuple[int, int],
) -> None:
    costs = np.ones(shape)
    field = distance_field(costs, (0, 0))
    assert field.base is None  # the padded buffer (most of it border) is not kept alive
    assert field.shape == shape and field.flags.writeable
    rows, cols = np.indices(shape)
    # One finite cost: the 8-connected distance is exact (octile metric).
    expected = np.maximum(rows, cols) + (np.sqrt(2.0) - 1.0) * np.minimum(rows, cols)
    np.testing.assert_allclose(field, expected, rtol=1e-12)


def test_a_view_result_is_independent_of_later_calls() -> None:
    costs = np.ones((40, 40))
    first = distance_field(costs, (0, 0))
    kept = first.copy()
    second = distance_field(costs, (39, 39))
    second[:] = -1.0  # writing into one result leaves another alone
    np.testing.assert_array_equal(first, kept)
