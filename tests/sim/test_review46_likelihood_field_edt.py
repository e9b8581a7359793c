"""The diff-astar localiser's likelihood field takes navkit's banded transform (review 46).

``LikelihoodField.from_grid`` ran SciPy's whole-grid
``distance_transform_edt`` twice (to the blocked cells, and inside them to the
free ones): 50 bytes a cell at its peak. It now calls
:func:`navkit.mapping.distance_transform`, the public face of the transform
behind ``inflate``, bit for bit SciPy's distances times the resolution, so
the field (and every scenario result built on it) is unchanged. Oracle: the
former SciPy code, kept here.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from scipy import ndimage

from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid
from navkit.sim.scenarios._diff_astar_localizer import LikelihoodField


def _scipy_field(grid: OccupancyGrid, clip: float) -> np.ndarray:
    """The field as from_grid computed it with SciPy until review 46."""
    blocked = ~grid.free()
    if not blocked.any():
        return np.full(grid.shape, clip)
    half = 0.5 * grid.resolution
    outside = np.asarray(ndimage.distance_transform_edt(~blocked), dtype=np.float64)
    dist = outside * grid.resolution - half
    if (~blocked).any():
        inside = np.asarray(ndimage.distance_transform_edt(blocked), dtype=np.float64)
        dist[blocked] = half - inside[blocked] * grid.resolution
    return np.clip(dist, -clip, clip)


def _grid(rows: int, cols: int, seed: int, density: float, resolution: float) -> OccupancyGrid:
    rng = np.random.default_rng(seed)
    occupied = rng.random((rows, cols)) < density
    unknown = (rng.random((rows, cols)) < density / 2) & ~occupied
    return OccupancyGrid.from_occupancy(occupied, resolution=resolution, unknown=unknown)


@settings(max_examples=150, deadline=None)
@given(
    rows=st.integers(1, 30),
    cols=st.integers(1, 30),
    seed=st.integers(0, 2**32 - 1),
    density=st.sampled_from([0.0, 0.02, 0.2, 0.6, 1.0]),
    resolution=st.sampled_from([0.01, 0.05, 0.1, 0.3]),
    clip=st.sampled_from([0.05, 0.5, 1e9]),
)
@example(rows=1, cols=12, seed=0, density=0.2, resolution=0.05, clip=1e9)
@example(rows=12, cols=1, seed=0, density=0.2, resolution=0.05, clip=1e9)
def test_the_field_is_scipys_bit_for_bit(
    rows: int, cols: int, seed: int, density: float, resolution: float, clip: float
) -> None:
    grid = _grid(rows, cols, seed, density, resolution)
    before = grid.logodds.copy()
    got = LikelihoodField.from_grid(grid, clip=clip).values
    want = _scipy_field(grid, clip)
    np.testing.assert_array_equal(got.view(np.int64), want.view(np.int64))
    np.testing.assert_array_equal(grid.logodds, before)


def test_the_field_does_not_run_scipys_transform() -> None:
    grid = _grid(20, 30, 4, 0.05, 0.05)

    def refuse(*args: object, **kwargs: object) -> None:
        raise AssertionError("SciPy's whole-grid transform ran")

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(ndimage, "distance_transform_edt", refuse)
        got = LikelihoodField.from_grid(grid, clip=1e9).values
    np.testing.assert_array_equal(got, _scipy_field(grid, 1e9))


def test_peak_memory_is_two_fields_and_a_band() -> None:
    # 2048 x 2048 cells: SciPy's two transforms peaked at 50 bytes a cell; now the
    # blocked and free masks (1 + 1), the outside distances (8), the inside ones (8)
    # and one band of 1024 rows of int64 column distances (16 MiB, 4 bytes a cell).
    rows = cols = 2048
    grid = _grid(rows, cols, 3, 0.02, 0.05)
    peak, field = peak_bytes(lambda: LikelihoodField.from_grid(grid))
    assert field.values.shape == (rows, cols)
    assert peak <= 18 * rows * cols + (16 << 20) + (2 << 20), peak / (rows * cols)
