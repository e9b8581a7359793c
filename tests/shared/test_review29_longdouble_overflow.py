"""A long double beyond float64's range is refused as not finite, never with a warning.

Review 29 (found by the fresh-eyes review of user potential fields): converting
such a value to float64 made NumPy warn "overflow encountered in cast", which
under ``-W error`` (and pytest's ``filterwarnings = error``) escaped as a
``RuntimeWarning`` instead of the ``ValueError`` naming the argument.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit._shared.validation import as_float_array

pytestmark = pytest.mark.skipif(
    np.finfo(np.longdouble).max <= np.finfo(np.float64).max,
    reason="long double is float64 on this platform",
)

HUGE = np.longdouble(np.finfo(np.float64).max) * 16


@pytest.mark.parametrize(
    "value",
    [
        np.array([1.0, HUGE]),
        np.array([[-HUGE, 0.0]]),
        [1.0, HUGE],
        [[np.longdouble(0.5), -HUGE]],
    ],
    ids=["array", "array-negative", "list", "nested-list"],
)
def test_an_overflowing_long_double_is_named_not_finite(value: object) -> None:
    with pytest.raises(ValueError, match="points must contain only finite values"):
        as_float_array(value, "points")


def test_an_overflowing_long_double_becomes_an_infinity_where_infinities_are_allowed() -> None:
    out = as_float_array(np.array([HUGE, -HUGE, 2.0], dtype=np.longdouble), "x", finite=False)
    assert out.dtype == np.float64
    assert out.tolist() == [np.inf, -np.inf, 2.0]


def test_a_public_constructor_names_the_argument() -> None:
    from navkit.mapping import OccupancyGrid

    with pytest.raises(ValueError, match="logodds must contain only finite values"):
        OccupancyGrid(np.full((2, 2), HUGE), resolution=1.0)
