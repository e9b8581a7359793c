"""LocalGrid.from_points snaps a halfway ``half_width`` up, also when the division rounds.

The documented rule: ``half_width`` is snapped to the nearest multiple of
``resolution``, halfway rounding up. ``0.15 / 0.1`` is ``1.4999999999999998`` in
float64, so 0.15 m at 0.1 m cells used to snap down to one cell (a 3 × 3 grid)
while 0.25 m snapped up to three (7 × 7).
"""

from __future__ import annotations

from decimal import Decimal

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping import LaserScan, LocalGrid

RESOLUTIONS = ["0.1", "0.05", "0.01", "0.03", "0.2", "0.3", "0.07", "0.025", "0.001"]


def _half_width(resolution: str, cells: int, extra: str) -> float:
    """``(cells + extra) * resolution`` as the decimal a user would type, as a float."""
    return float(Decimal(resolution) * (Decimal(cells) + Decimal(extra)))


@pytest.mark.parametrize(
    ("half_width", "size"), [(0.05, 3), (0.15, 5), (0.25, 7), (0.35, 9), (0.45, 11), (0.3, 7)]
)
def test_paper_resolution_halfway_rounds_up(half_width: float, size: int) -> None:
    grid = LocalGrid.from_points([], half_width=half_width, resolution=0.1)
    assert grid.size == size
    assert grid.half_width == pytest.approx((size - 1) / 2 * 0.1, abs=1e-12)


@settings(max_examples=60, deadline=None)
@given(
    resolution=st.sampled_from(RESOLUTIONS),
    cells=st.integers(min_value=0, max_value=400),
    extra=st.sampled_from([("0", 0), ("0.49", 0), ("0.5", 1), ("0.51", 1), ("0.999", 1)]),
)
def test_snapped_cells_follow_the_decimal_half_width(
    resolution: str, cells: int, extra: tuple[str, int]
) -> None:
    fraction, carry = extra
    half_width = _half_width(resolution, cells, fraction)
    grid = LocalGrid.from_points([], half_width=half_width, resolution=float(resolution))
    assert grid.size == 2 * (cells + carry) + 1


def test_scan_local_grid_uses_the_same_snapping() -> None:
    scan = LaserScan(
        np.array([0.2]), angle_min=0.0, angle_increment=0.1, range_min=0.05, range_max=3.5
    )
    grid = scan.to_local_grid(half_width=0.15, resolution=0.1)
    assert grid.size == 5
    # The return 0.2 m ahead lies in the last column of the robot's row.
    assert bool(grid.occupied[2, 4])
