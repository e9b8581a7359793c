"""``angle_diff`` near the float limit and of empty arrays: the overflow guard's edges.

Review 48 (mutation testing, MUTANT28). ``angle_diff`` subtracts directly unless
an angle's magnitude reaches 8e307, where ``a - b`` may overflow and the angles
are wrapped first. Two mutants of the guard's ``_peak`` passed every test:

* the largest value instead of the largest magnitude: ``a = -1.7e308`` with
  ``b = 5e307`` (neither above 8e307 as a signed value) overflowed to ``-inf``
  and raised "angle must be finite" for finite angles;
* no guard for empty arrays: ``np.max`` of nothing raised NumPy's "zero-size
  array to reduction operation maximum which has no identity".
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.typing import ArrayLike

from navkit.geometry import angle_diff, wrap_angle

BIG = 1.7e308


@pytest.mark.parametrize(
    ("a", "b"),
    [(-BIG, 5e307), (-BIG, 1e307), (BIG, -5e307), (-BIG, 0.7e308)],
)
def test_a_huge_negative_angle_minus_a_positive_one_is_wrapped(a: float, b: float) -> None:
    # a - b overflows although only one of the angles is beyond 8e307 and, for
    # a < 0, not as a signed value: the angles are wrapped first (the docstring).
    want = float(wrap_angle(wrap_angle(a) - wrap_angle(b)))
    assert -math.pi < want <= math.pi
    assert angle_diff(a, b) == want
    got = angle_diff(np.array([a, 0.25]), np.array([b, 0.5]))
    np.testing.assert_array_equal(got, [want, -0.25])
    # And reversed: b - a, the same circle distance the other way round.
    back = np.asarray(angle_diff(np.array([b]), np.array([a])))
    assert back[0] == float(wrap_angle(wrap_angle(b) - wrap_angle(a)))


@pytest.mark.parametrize(
    ("a", "b"),
    [
        (np.empty(0), np.empty(0)),
        ([], 0.5),
        (0.5, []),
        (np.empty((0, 3)), np.zeros(3)),
    ],
)
def test_angle_diff_of_empty_arrays_is_empty(a: ArrayLike, b: ArrayLike) -> None:
    got = angle_diff(a, b)
    assert isinstance(got, np.ndarray) and got.size == 0 and got.dtype == np.float64
    assert got.shape == np.broadcast_shapes(np.shape(a), np.shape(b))
