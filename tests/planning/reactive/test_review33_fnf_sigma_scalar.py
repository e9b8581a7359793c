"""``BlendedAttraction.sigma`` of a scalar: an array, as annotated and documented (review 33).

``sigma(2.0)`` returned a NumPy scalar (scipy's ``expit`` is a ufunc) where the
annotation (``FloatArray``) and the docstring ("New array ... the shape of d")
promise an array, as the field's ``potential`` and ``force`` always return.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.planning.reactive import BlendedAttraction


@pytest.mark.parametrize("d", [2.0, 0.5, np.float64(2.0), np.array(2.0), 7])
def test_a_scalar_distance_gives_a_zero_dimensional_array(d: Any) -> None:
    field = BlendedAttraction((0.0, 0.0))
    out = field.sigma(d)
    assert type(out) is np.ndarray
    assert out.shape == () and out.dtype == np.float64
    assert out == field.sigma(np.atleast_1d(d))[0]
    assert out.flags.writeable  # a new array, the caller's to keep


def test_an_array_keeps_its_shape_and_is_not_the_input() -> None:
    field = BlendedAttraction((0.0, 0.0), threshold_radius=1.0)
    d = np.array([[0.0, 1.0], [2.0, 1e300]])
    before = d.copy()
    out = field.sigma(d)
    assert type(out) is np.ndarray and out.shape == (2, 2)
    assert out[0, 1] == 0.5 and out[1, 1] == 1.0
    assert not np.shares_memory(out, d)
    np.testing.assert_array_equal(d, before)
