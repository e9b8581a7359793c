"""Metamorphic properties of ``navkit.mapping.distance_transform`` (review 46, HYPO7).

The session's tests compare the transform with SciPy's; these need no
reference implementation. A distance of an exact transform depends only on
the integer offsets to the mask's cells, so it is the same bits when the
mask is transposed or flipped (the result transposed or flipped), never
grows when cells are added to the mask, scales with the resolution as one
product, equals the minimum over the mask's cells of a brute-force
``sqrt(dr**2 + dc**2) * resolution``, and is the same for any memory layout
of the mask. Each holds with every band size and with bands of columns (the
kernel's own seams), forced small here.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import navkit.mapping._obstacle_distance as distance_module
from edt_oracle import float_bits
from navkit.mapping import distance_transform

_SHAPES = st.tuples(st.integers(1, 24), st.integers(1, 24))
# Sparse, dense and in-between masks: a lone cell decides much of a sparse one.
_DENSITY = st.sampled_from([0.0, 0.02, 0.1, 0.5, 0.95])


@st.composite
def _masks(draw: st.DrawFn, shapes: st.SearchStrategy[tuple[int, int]] = _SHAPES) -> np.ndarray:
    shape = draw(shapes)
    density = draw(_DENSITY)
    seed = draw(st.integers(0, 2**32 - 1))
    mask = np.random.default_rng(seed).random(shape) < density
    for cell in draw(st.lists(st.tuples(st.integers(0, 23), st.integers(0, 23)), max_size=3)):
        mask[cell[0] % shape[0], cell[1] % shape[1]] = True
    return mask


_BANDS = st.tuples(st.one_of(st.none(), st.integers(1, 9)), st.booleans())


@contextlib.contextmanager
def _bands(band: int | None, wide: bool) -> Iterator[None]:
    """Bands of ``band`` rows (None: the real size); with ``wide``, bands of columns when wider."""
    with pytest.MonkeyPatch.context() as mp:
        if band is not None:
            mp.setattr(distance_module, "_band_rows", lambda rows, cols: band)
        if wide:
            mp.setattr(distance_module, "_BAND_CELLS", 0)
        yield


def _brute_force(mask: np.ndarray, resolution: float) -> np.ndarray:
    cells = np.argwhere(mask)
    if not len(cells):
        return np.full(mask.shape, np.inf)
    rows, cols = np.indices(mask.shape)
    dr = rows[..., None] - cells[:, 0]
    dc = cols[..., None] - cells[:, 1]
    # Integer squared offsets: exact, so the float sqrt is the transform's own.
    squared = (dr * dr + dc * dc).min(axis=-1)
    return np.sqrt(squared.astype(np.float64)) * resolution


_RESOLUTIONS = st.sampled_from([1.0, 0.05, 0.1, 1e-6, 0.3333333333333333, 7.25, 1e6])


@settings(max_examples=150, deadline=None)
@given(mask=_masks(), bands=_BANDS, resolution=_RESOLUTIONS)
def test_the_transform_is_the_brute_force_minimum(
    mask: np.ndarray, bands: tuple[int | None, bool], resolution: float
) -> None:
    kept = mask.copy()
    with _bands(*bands):
        got = distance_transform(mask, resolution=resolution)
    assert np.array_equal(float_bits(got), float_bits(_brute_force(mask, resolution)))
    assert np.array_equal(mask, kept)


_SYMMETRIES = {
    "transpose": lambda a: a.T,
    "flip rows": lambda a: a[::-1],
    "flip cols": lambda a: a[:, ::-1],
    "rotate": lambda a: np.rot90(a),
    "anti-transpose": lambda a: np.rot90(a, 2).T,
}


@settings(max_examples=150, deadline=None)
@given(
    mask=_masks(),
    bands=_BANDS,
    symmetry=st.sampled_from(sorted(_SYMMETRIES)),
    resolution=_RESOLUTIONS,
)
def test_the_transform_commutes_with_the_grids_symmetries(
    mask: np.ndarray, bands: tuple[int | None, bool], symmetry: str, resolution: float
) -> None:
    move = _SYMMETRIES[symmetry]
    with _bands(*bands):
        plain = distance_transform(mask, resolution=resolution)
        # The moved mask is a view (negative or swapped strides): the layout varies too.
        moved = distance_transform(move(mask), resolution=resolution)
        copied = distance_transform(np.ascontiguousarray(move(mask)), resolution=resolution)
    assert np.array_equal(float_bits(moved), float_bits(move(plain)))
    assert np.array_equal(float_bits(copied), float_bits(moved))


@settings(max_examples=150, deadline=None)
@given(mask=_masks(), more=st.data(), bands=_BANDS)
def test_adding_cells_to_the_mask_never_lengthens_a_distance(
    mask: np.ndarray, more: st.DataObject, bands: tuple[int | None, bool]
) -> None:
    added = more.draw(arrays(np.bool_, mask.shape)) | mask
    with _bands(*bands):
        before = distance_transform(mask, resolution=0.1)
        after = distance_transform(added, resolution=0.1)
    assert (after <= before).all()
    assert (after[added] == 0.0).all()
    assert (after[~added] > 0.0).all()
    # Where the new cells are farther than the old nearest, nothing changes.
    far = before <= distance_transform(added & ~mask, resolution=0.1) if added.any() else None
    if far is not None:
        assert np.array_equal(float_bits(after[far]), float_bits(before[far]))


@settings(max_examples=100, deadline=None)
@given(mask=_masks(), bands=_BANDS, resolution=_RESOLUTIONS)
def test_the_resolution_is_one_product(
    mask: np.ndarray, bands: tuple[int | None, bool], resolution: float
) -> None:
    with _bands(*bands):
        cells = distance_transform(mask, resolution=1.0)
        metres = distance_transform(mask, resolution=resolution)
    assert np.array_equal(float_bits(metres), float_bits(cells * resolution))
    # In cells the distances are square roots of integers: their squares round back.
    finite = cells[np.isfinite(cells)]
    assert np.array_equal(np.sqrt(np.rint(finite * finite)), finite)


@settings(max_examples=60, deadline=None)
@given(
    mask=_masks(st.tuples(st.integers(1, 12), st.integers(1, 12))),
    pad=st.tuples(*[st.integers(0, 3)] * 4),
    bands=_BANDS,
)
def test_false_cells_around_a_mask_change_none_of_its_distances(
    mask: np.ndarray, pad: tuple[int, int, int, int], bands: tuple[int | None, bool]
) -> None:
    # A mask inside a bigger all-False one: its window's distances are the mask's own.
    top, bottom, left, right = pad
    big = np.zeros((mask.shape[0] + top + bottom, mask.shape[1] + left + right), dtype=bool)
    window = (slice(top, top + mask.shape[0]), slice(left, left + mask.shape[1]))
    big[window] = mask
    with _bands(*bands):
        alone = distance_transform(mask, resolution=0.5)
        padded = distance_transform(big, resolution=0.5)
        viewed = distance_transform(big[window], resolution=0.5)
    assert np.array_equal(float_bits(padded[window]), float_bits(alone))
    assert np.array_equal(float_bits(viewed), float_bits(alone))
