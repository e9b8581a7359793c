"""A list of float32 signalling NaNs is refused as not finite, with no warning (review 30, FRESH).

Review 29 ran the list path's cast under ``np.errstate`` only for long doubles
(itemsize > 8), to keep lists of Python floats fast. A list (or tuple) of
``np.float32`` holding a signalling NaN (a driver's or a bag's float32 read
element by element) also casts: NumPy warns "invalid value encountered in
cast", which under ``-W error`` (pytest's ``filterwarnings = error``) escaped as
a ``RuntimeWarning`` instead of the ``ValueError`` naming the argument, as the
ndarray path already gives. Checked: against ``validation.py`` before the
change every test here but the array case (the regression guard) fails with
that RuntimeWarning.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit._shared.validation import as_float_array

SNAN32 = np.frombuffer(np.uint32(0x7FA00000).tobytes(), dtype=np.float32)[0]


@pytest.mark.parametrize(
    "value",
    [[SNAN32], (np.float32(1.0), SNAN32), [[np.float16(0.5), SNAN32]], np.array([SNAN32])],
    ids=["list", "tuple", "nested-float16", "array"],
)
def test_a_float32_signalling_nan_is_named_not_finite(value: object) -> None:
    with pytest.raises(ValueError, match="points must contain only finite values"):
        as_float_array(value, "points")


def test_a_float32_signalling_nan_is_a_nan_where_nans_are_allowed() -> None:
    out = as_float_array([SNAN32, np.float32(2.0)], "x", finite=False)
    assert out.dtype == np.float64
    assert np.isnan(out[0]) and out[1] == 2.0
