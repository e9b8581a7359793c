"""``sample_field`` and ``SampledField``: spacing tolerance, far windows, last centre (review 32).

Three mutants of ``_sampling.py`` survived the sampling tests:

- the axis spacing tolerance ``1e-9 * resolution`` as ``1e-9 / resolution``
  (the docstring's "1e-9 of a cell" taken in the wrong unit: at 0.01 m cells
  an axis 1e-8 of a cell off was accepted, at 100 m one 1e-11 off refused);
- ``abs`` dropped from the count's rounding slack (``|lo| + |hi|``), which then
  went negative for a window at negative coordinates and gained a cell;
- the coordinate limit checked on the first cell centre instead of the last.

Oracles: the documented tolerance (1e-9 of a cell), the cell count of a window
that is an exact multiple of the resolution in decimal (0.1 m at 0.01 m: 10
cells, as the code's comment has it for (1e6 + 0.2, 1e6 + 0.3)), and the
documented ±1e9 m bound on every cell centre. Checked: each test fails on its
mutant and passes on HEAD.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.planning.reactive import ParaboloidAttraction, SampledField, sample_field


def _axes(resolution: float, error: float) -> tuple[np.ndarray, np.ndarray]:
    return np.arange(4) * resolution * (1.0 + error), np.arange(3) * resolution


def test_the_spacing_tolerance_is_1e_9_of_a_cell_at_any_resolution() -> None:
    zeros, forces = np.zeros((3, 4)), np.zeros((3, 4, 2))
    x, y = _axes(0.01, 1e-8)  # 1e-8 of a cell off: refused
    with pytest.raises(ValueError, match=r"^x must be evenly spaced by resolution = 0\.01$"):
        SampledField(x, y, zeros, forces, resolution=0.01)
    x, y = _axes(100.0, 1e-11)  # 1e-11 of a cell off: within the tolerance
    field = SampledField(x, y, zeros, forces, resolution=100.0)
    assert field.shape == (3, 4)


@pytest.mark.parametrize("xlim", [(1e6 + 0.2, 1e6 + 0.3), (-1e6 - 0.3, -1e6 - 0.2), (-0.3, -0.2)])
def test_a_window_of_ten_cells_has_ten_cells_at_any_offset(
    xlim: tuple[float, float],
) -> None:
    field = ParaboloidAttraction(goal_xy=(0.0, 0.0))
    sampled = sample_field(field, xlim=xlim, ylim=(0.0, 0.05), resolution=0.01)
    assert sampled.shape == (5, 10)


def test_a_last_cell_centre_beyond_the_coordinate_limit_is_refused() -> None:
    field = ParaboloidAttraction(goal_xy=(0.0, 0.0))
    # Two cells of 0.4 m over [1e9 - 0.5, 1e9]: the second centre is 1e9 + 0.1 m.
    with pytest.raises(ValueError, match=r"^xlim: the last cell centre, 1e\+09 m, lies beyond"):
        sample_field(field, xlim=(1e9 - 0.5, 1e9), ylim=(0.0, 0.1), resolution=0.4)
