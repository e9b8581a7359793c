"""``LocalGrid``'s documented tolerances: 1e-9 cells of a half, 1e-9 relative (review 43).

Mutants of ``navkit.mapping._local_grid`` that the suite let pass:
``from_points`` without its "within 1e-9 cells of a half counts as a half"
(only the float-rounding slack kept), and the constructor's consistency check of
``half_width`` against the shape loosened from ``rel_tol=1e-9`` to 1e-3. The
suite's half widths were exact decimal halves (0.15 m, 0.25 m) and its
inconsistent ones a whole cell off. Oracle: the documented rules.
Checked: each test fails on its mutant, passes on HEAD.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import LocalGrid


@pytest.mark.parametrize("res", [0.1, 0.5, 1.0])
def test_a_half_width_within_1e9_cells_of_a_half_rounds_up(res: float) -> None:
    # 2.5 cells less 5e-10: counts as 2.5, so k = 3 (side 7); less 2e-9: k = 2 (side 5).
    assert LocalGrid.from_points([], half_width=(2.5 - 5e-10) * res, resolution=res).size == 7
    assert LocalGrid.from_points([], half_width=(2.5 - 2e-9) * res, resolution=res).size == 5


@pytest.mark.parametrize("off", [1e-6, -1e-6, 1e-4])
def test_a_half_width_off_by_more_than_1e9_relative_is_refused(off: float) -> None:
    occupied = np.zeros((5, 5), dtype=bool)
    LocalGrid(occupied, resolution=0.1, half_width=0.2 * (1 + 1e-12))  # within tolerance
    with pytest.raises(ValueError, match="half_width must be"):
        LocalGrid(occupied, resolution=0.1, half_width=0.2 * (1 + off))
