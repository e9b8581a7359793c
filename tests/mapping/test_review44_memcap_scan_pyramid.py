"""A scan matcher's coarser levels take a quarter of the finer level's bytes (review 44).

``downsample`` copied the grid into a zero-padded array and reduced its 2 x 2
blocks: 6 bytes a finest cell at the peak of ``ScanMatcher.pyramid`` (1.5 GiB
for a map of ``OccupancyGrid.MAX_CELLS`` cells), which ``match`` builds for
every grid it is given. The maximum is now taken over the four strided views
into the coarser grid's own array (kept by the grid, not copied): 1.3 bytes a
finest cell for four levels. The levels are the same.
"""

from __future__ import annotations

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid, ScanMatcher
from navkit.mapping._scan_matcher import downsample


def _padded_blocks(logodds: np.ndarray) -> np.ndarray:
    """Each 2 x 2 block's largest log-odds, cells beyond an odd edge 0 (unknown)."""
    rows, cols = logodds.shape
    padded = np.zeros((rows + rows % 2, cols + cols % 2), dtype=np.float32)
    padded[:rows, :cols] = logodds
    return padded.reshape(padded.shape[0] // 2, 2, padded.shape[1] // 2, 2).max(axis=(1, 3))


@settings(max_examples=80, deadline=None)
@given(
    logodds=hnp.arrays(
        np.float32,
        hnp.array_shapes(min_dims=2, max_dims=2, min_side=1, max_side=9),
        elements=st.floats(-50.0, 50.0, width=32),
    ),
    shift=st.sampled_from([0.0, -60.0, 60.0]),
)
@example(logodds=np.full((3, 5), -2.0, dtype=np.float32), shift=0.0)
def test_each_coarse_cell_is_its_blocks_largest_log_odds(logodds: np.ndarray, shift: float) -> None:
    grid = OccupancyGrid(logodds + np.float32(shift), resolution=0.1, origin=(1.0, 2.0, 0.5))
    coarse = downsample(grid)
    assert coarse.resolution == 0.2 and coarse.origin == grid.origin
    assert np.array_equal(coarse.logodds, _padded_blocks(grid.logodds))


def test_a_pyramid_takes_little_more_than_its_coarser_levels() -> None:
    n = 2048
    grid = OccupancyGrid.from_probabilities(
        np.random.default_rng(9).random((n, n)), resolution=0.05
    )
    peak, levels = peak_bytes(lambda: ScanMatcher(levels=4).pyramid(grid))
    assert [g.shape for g in levels] == [(n, n), (n // 2, n // 2), (n // 4, n // 4), (n // 8,) * 2]
    kept = sum(g.logodds.nbytes for g in levels[1:])  # a third of the finest, about
    # 6 bytes a finest cell before (the padded copy and its reduction), 1.3 now.
    assert peak < kept + n * n + (1 << 20), f"{peak / (n * n):.2f} bytes a finest cell"
