"""navkit.errors: the exception classes check their own arguments (issue 12)."""

from __future__ import annotations

import numpy as np
import pytest

from navkit.errors import FilterError, NavkitError, NoPathError


def test_no_path_error_takes_a_non_negative_integer_count() -> None:
    assert NoPathError("no path", expanded=np.int64(7)).expanded == 7
    assert NoPathError("no path").expanded == 0
    for bad in (True, 1.5, 1e-300, float("inf"), b"1", 1 + 0j, "3", None):
        with pytest.raises(TypeError, match="expanded must be an integer"):
            NoPathError("no path", bad)  # type: ignore[arg-type]
    for bad_int in (-1, 2**63, 10**400):
        with pytest.raises(ValueError, match=r"expanded must be in \[0, 2\*\*63 - 1\]"):
            NoPathError("no path", bad_int)
    with pytest.raises(TypeError, match="message must be a str"):
        NoPathError(42)  # type: ignore[arg-type]


def test_filter_error_is_a_navkit_error() -> None:
    assert issubclass(FilterError, NavkitError) and issubclass(NoPathError, NavkitError)
