"""Review 47 mutation review: the float converters' rarer ways to a misaligned buffer.

ALIGN's tests hand the converters float64 arrays whose dtype is NumPy's own
``float64`` (the inlined test). Two other ways reach ``np.asarray(...,
dtype=float64)`` without a conversion, which keeps the buffer as it is: an
ndarray whose dtype equals float64 without being it (a dtype with metadata),
and a buffer that is not an ndarray (a ``memoryview``, an
``__array_interface__`` object). Dropping :func:`aligned` from either path
survived every test (mutants a04, a05).
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from misaligned_arrays import misaligned
from navkit._shared.validation import as_float_array, as_points

VALUES = np.array([[1.0, 2.5], [-3.0, 4.0]])


class _Interface:
    """An object exposing another array's buffer by ``__array_interface__`` alone."""

    def __init__(self, arr: np.ndarray) -> None:
        self._arr = arr  # keeps the buffer alive
        self.__array_interface__ = arr.__array_interface__


def _with_metadata(a: np.ndarray) -> np.ndarray:
    odd = misaligned(a)
    return odd.view(np.dtype(np.float64, metadata={"unit": "m"}))


@pytest.mark.parametrize(
    "make",
    [_with_metadata, lambda a: memoryview(misaligned(a)), lambda a: _Interface(misaligned(a))],
    ids=["metadata-dtype", "memoryview", "array-interface"],
)
def test_the_float_converters_copy_a_misaligned_buffer_reached_without_conversion(
    make: Any,
) -> None:
    odd = make(VALUES)
    source = np.asarray(odd)
    assert source.dtype == np.float64 and not source.flags.aligned
    before = source.copy()
    for got in (as_float_array(odd, "values"), as_points(odd, "points")):
        assert got.dtype == np.float64
        assert got.flags.aligned and got.flags.c_contiguous
        np.testing.assert_array_equal(got, VALUES)
    np.testing.assert_array_equal(np.asarray(odd), before)  # the input is not modified
