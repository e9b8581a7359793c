"""A huge grid is shrunk for drawing a band of rows at a time (review 44).

``plot_grid`` (and every picture with a map: ``plot_scene``, ``animate_trace``)
made the whole grid's float64 grey levels and a padded copy before shrinking
them to at most 2048 cells a side: 16.5 bytes a cell, 4 GiB for a map of
``OccupancyGrid.MAX_CELLS`` (2**28) cells. It now shrinks a band of about
2**20 cells at a time from the grid's two views (1 byte a cell each): the
same image, 2.75 bytes a cell.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import navkit.plot._grid as plot_grid_module
from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid
from navkit.plot import plot_grid

matplotlib = pytest.importorskip("matplotlib")


def _whole_then_shrunk(grid: OccupancyGrid, limit: int) -> np.ndarray:
    """The image as it was made: every cell's grey, padded with white, darkest of each block."""
    shades = np.full(grid.shape, plot_grid_module.UNKNOWN_GREY)
    shades[grid.free()] = plot_grid_module.FREE_GREY
    shades[grid.occupied()] = plot_grid_module.OCCUPIED_GREY
    k = -(-max(shades.shape) // limit)
    rows = -(-shades.shape[0] // k) * k
    cols = -(-shades.shape[1] // k) * k
    padded = np.full((rows, cols), plot_grid_module.FREE_GREY)
    padded[: shades.shape[0], : shades.shape[1]] = shades
    return padded.reshape(rows // k, k, cols // k, k).min(axis=(1, 3))


@settings(max_examples=60, deadline=None)
@given(
    rows=st.integers(1, 40),
    cols=st.integers(1, 40),
    limit=st.integers(1, 12),
    band=st.integers(1, 200),
    seed=st.integers(0, 2**32 - 1),
)
@example(rows=40, cols=1, limit=3, band=1, seed=0)
def test_any_band_gives_the_image_of_the_whole_grid(
    rows: int, cols: int, limit: int, band: int, seed: int
) -> None:
    p = np.random.default_rng(seed).choice([0.0, 0.5, 1.0, 0.3, 0.8], size=(rows, cols))
    grid = OccupancyGrid.from_probabilities(p, resolution=0.1)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(plot_grid_module, "MAX_IMAGE_CELLS", limit)
        mp.setattr(plot_grid_module, "_BAND_CELLS", band)
        shades = plot_grid_module.grid_shades(grid)
    assert np.array_equal(shades, _whole_then_shrunk(grid, limit))


def test_plotting_a_huge_grid_takes_its_views_and_a_band() -> None:
    import matplotlib.pyplot as plt

    rows, cols = 6145, 4100  # shrunk by 4: a 1537 x 1025 image
    p = np.random.default_rng(2).choice([0.0, 0.5, 1.0], size=(rows, cols))
    grid = OccupancyGrid.from_probabilities(p, resolution=0.05)
    del p
    fig, ax = plt.subplots()
    try:
        peak, _ = peak_bytes(lambda: plot_grid(grid, ax=ax))
    finally:
        plt.close(fig)
    cells = rows * cols
    # The two views (2), the image (0.33) and a band (8 MiB); 16.5 bytes a cell before.
    assert peak < 3 * cells + (24 << 20), f"{peak / cells:.2f} bytes a cell"
