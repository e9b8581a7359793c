"""Ray casting clears every scratch mark it reads, the last cell's too (review 32, mutants).

``integrate_beams`` takes a caller's scratch buffer "whose contents do not
matter": it clears the marks of the scan's window (the grid cells any beam
can reach, row-major) before the two passes. A mutant clearing one mark fewer
(``range(n - 1)``) survived the suite: the buffers the callers pass are fresh
from ``np.empty`` and mostly zero already. Left set, the last mark (the
window's top-right cell) makes the hit pass take that cell as updated and
skip it. Oracle: the sensor model itself, a beam along the grid's top row to
its last cell: the end cell takes ``hit`` once, the cells before it ``miss``
once, nothing else changes, whatever the buffer held.
Checked: the test fails on that mutant of ``_raycast_kernels.py`` and passes
on HEAD.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping._raycast_kernels import integrate_beams

_HIT = 0.85
_MISS = -0.4


@pytest.mark.parametrize("exact", [False, True])
@pytest.mark.parametrize("fill", [1, 2, 255])
def test_a_dirty_scratch_buffer_changes_nothing(exact: bool, fill: int) -> None:
    n = 4
    logodds = np.zeros((n, n), dtype=np.float32)
    # Along the top row from the centre of cell (3, 0) to that of cell (3, 3), the
    # last cell of the window (the whole grid: the beam's reach passes its edges).
    ranges = np.array([float(n - 1)])
    scratch = np.full(n * n, fill, dtype=np.uint8)
    updated = integrate_beams(
        logodds, 0.0, 0.0, 0.0, 1.0, 0.5, n - 0.5, 0.0, ranges, 0.0, 0.0,
        0.0, 100.0, _HIT, _MISS, -10.0, 10.0, exact, scratch,
    )  # fmt: skip
    expected = np.zeros((n, n), dtype=np.float32)
    expected[n - 1, : n - 1] = _MISS
    expected[n - 1, n - 1] = _HIT
    np.testing.assert_array_equal(logodds, expected)
    assert updated == n
