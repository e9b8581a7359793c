"""Review 46 (MUTANT25): the exact distance transform's kernel keeps to its contract.

Review 46 folded ``below_checkpoints`` into ``band_distances``: called for band
0, the kernel records every band's checkpoint (the nearest occupied row below
the band, per column); called for band ``b`` it consumes row ``b`` only. Three
mutants of the new lines left every distance bit for bit SciPy's and so
passed every earlier test: the sweep of the whole grid run again for every
band (``if band >= 0``) or for band 1 too (``if band <= 1``), and a sweep
that starts one row early (``first = b * band_rows - 1``). The first makes
the transform take ``O(rows * cols)`` work per band instead of per grid (its
cost grows with ``sqrt(rows)`` times the grid); the second doubles the sweep.
Both rewrite other bands' checkpoints, which the kernel's contract says it
leaves alone; the third records a band's own last row as the row below it
(harmless only because the band's own sweep meets that row first). These
tests check the contract call by call, with the distances against SciPy.

The public face's refusal of a mask too large states the float64 result's size
(a mutant of its ``bytes_per_cell`` doubled it unnoticed).

Oracle: the checkpoints by brute force (per column, the first occupied row
after a band's last), and
:func:`scipy.ndimage.distance_transform_edt` for the distances.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from scipy import ndimage

from navkit.mapping._edt_kernels import band_distances

SENTINEL = -7


def _checkpoints(occupied: np.ndarray, band_rows: int) -> np.ndarray:
    """``below[b, c]``: the nearest occupied row below band ``b`` in column ``c``, -1 for none."""
    rows, cols = occupied.shape
    n_bands = -(-rows // band_rows)
    below = np.full((n_bands, cols), -1, dtype=np.int64)
    for b in range(n_bands):
        for c in range(cols):
            hits = np.flatnonzero(occupied[(b + 1) * band_rows :, c])
            if hits.size:
                below[b, c] = (b + 1) * band_rows + int(hits[0])
    return below


def _run_bands(occupied: np.ndarray, band_rows: int) -> np.ndarray:
    """The kernel called band by band as its caller does, its contract checked at each call."""
    rows, cols = occupied.shape
    n_bands = -(-rows // band_rows)
    want_below = _checkpoints(occupied, band_rows)
    below = np.full((n_bands, cols), SENTINEL, dtype=np.int64)
    above = np.full(cols, -1, dtype=np.int64)
    g = np.empty((band_rows, cols), dtype=np.int64)
    s = np.empty(cols, dtype=np.int64)
    t = np.empty(cols, dtype=np.int64)
    out = np.full((rows, cols), np.nan)
    for b in range(n_bands):
        r0, r1 = b * band_rows, min(rows, (b + 1) * band_rows)
        before = below.copy()
        band_distances(
            occupied, band_rows, b, above, below, rows + cols, g[: r1 - r0], s, t, out[r0:r1]
        )
        others = np.arange(n_bands) != b
        if b == 0:
            # Band 0 writes every later band's checkpoint (its own it then consumes).
            np.testing.assert_array_equal(below[1:], want_below[1:])
        else:
            # Band b reads and overwrites its own row only: the others as they were.
            np.testing.assert_array_equal(below[others], before[others])
        # Carried on: the nearest occupied row at or above the band's last row.
        for c in range(cols):
            hits = np.flatnonzero(occupied[:r1, c])
            assert above[c] == (int(hits[-1]) if hits.size else -1)
    return out


def _scipy(occupied: np.ndarray) -> np.ndarray:
    return np.asarray(ndimage.distance_transform_edt(~occupied), dtype=np.float64)


@settings(max_examples=120, deadline=None)
@given(
    rows=st.integers(1, 17),
    cols=st.integers(1, 7),
    band_rows=st.integers(1, 17),
    seed=st.integers(0, 2**32 - 1),
    density=st.sampled_from([0.05, 0.2, 0.5, 1.0]),
)
@example(rows=9, cols=3, band_rows=2, seed=0, density=0.2)
@example(rows=7, cols=2, band_rows=3, seed=3, density=0.5)
def test_each_band_keeps_to_its_checkpoints_and_is_scipys(
    rows: int, cols: int, band_rows: int, seed: int, density: float
) -> None:
    occupied = np.random.default_rng(seed).random((rows, cols)) < density
    occupied[rows // 2, 0] = True  # the kernel's precondition: an occupied cell somewhere
    kept = occupied.copy()
    got = _run_bands(occupied, band_rows)
    np.testing.assert_array_equal(got.view(np.int64), _scipy(occupied).view(np.int64))
    np.testing.assert_array_equal(occupied, kept)


@pytest.mark.parametrize("band_rows", [1, 2, 3, 4])
def test_obstacles_in_the_first_band_only_leave_the_later_checkpoints_empty(
    band_rows: int,
) -> None:
    # Columns whose only occupied cells are in band 0: a sweep run again at band b
    # would write band 0's consumed row back; every later checkpoint is -1.
    occupied = np.zeros((9, 3), dtype=bool)
    occupied[0, 0] = occupied[band_rows - 1, 1] = True
    got = _run_bands(occupied, band_rows)
    np.testing.assert_array_equal(got.view(np.int64), _scipy(occupied).view(np.int64))


@pytest.mark.parametrize(("shape", "gib"), [((2**14 + 1, 2**14), "2"), ((2**15, 2**15), "8")])
def test_a_mask_too_large_is_refused_with_the_results_size(
    shape: tuple[int, int], gib: str
) -> None:
    # The result is float64, 8 bytes a cell: 2**28 + 1 cells need 2 GiB, 2**30 need
    # 8 GiB (a broadcast view: one byte of memory).
    from navkit.mapping import distance_transform

    huge = np.broadcast_to(np.array([[True]]), shape)
    with pytest.raises(ValueError, match=rf"^mask would need .* cells \({gib} GiB of float64\)"):
        distance_transform(huge, resolution=0.1)
