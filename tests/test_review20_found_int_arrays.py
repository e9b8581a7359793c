"""0-d integer arrays pass wherever Python ints do (review 20, FOUND item 1).

``np.array(3)`` is what a reduction or an indexing of an integer array gives;
the shared integer check (``bounded_int``) takes it, and so must the checks
written apart from it: ``NoPathError(expanded=...)`` and ``FusionStatus(...)``.
Bools stay refused, and so do 0-d float arrays (``bounded_int``'s policy: a
float is no integer even when whole).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.errors import NoPathError
from navkit.estimation import FusionStatus

INT_DTYPES = ("int8", "int16", "int32", "int64", "uint8", "uint16", "uint32", "uint64")


@given(st.sampled_from(INT_DTYPES), st.integers(0, 127))
def test_no_path_error_takes_a_0d_integer_array(dtype: str, n: int) -> None:
    count = np.array(n, dtype=dtype)
    before = count.copy()
    err = NoPathError("no path", expanded=count)  # type: ignore[arg-type]
    assert err.expanded == n and type(err.expanded) is int
    assert str(err) == "no path"
    np.testing.assert_array_equal(count, before)


def test_no_path_error_still_refuses_bools_floats_and_negatives() -> None:
    for bad in (np.array(True), np.array(3.0), np.array([3]), np.True_, True):
        with pytest.raises(TypeError, match="expanded must be an integer"):
            NoPathError("no path", bad)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"expanded must be in \[0, 2\*\*63 - 1\], got -1"):
        NoPathError("no path", np.array(-1))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"2\*\*63 - 1\], got 18446744073709551615"):
        NoPathError("no path", np.array(2**64 - 1, dtype=np.uint64))  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="expanded has masked entries"):
        NoPathError("no path", np.ma.array(3, mask=True))  # type: ignore[arg-type]


@given(st.sampled_from(INT_DTYPES), st.sampled_from(list(FusionStatus)))
def test_fusion_status_takes_a_0d_integer_array(dtype: str, member: FusionStatus) -> None:
    assert FusionStatus(np.array(int(member), dtype=dtype)) is member


def test_fusion_status_still_refuses_bools_and_floats() -> None:
    for bad in (np.array(True), np.array(1.0), np.array([1]), np.True_, True, 1.0):
        with pytest.raises(TypeError, match="FusionStatus takes an integer code"):
            FusionStatus(bad)
    with pytest.raises(ValueError):
        FusionStatus(np.array(99))
    assert FusionStatus(np.int64(1)) is FusionStatus.GATED  # unchanged
