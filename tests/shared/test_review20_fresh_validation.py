"""Fresh-eyes review 20 of session 23's foreign-array work (validation.py).

* ``has_array_protocol`` counted NumPy scalars (``np.float64(1.0)`` has
  ``__array__``) as arrays, so since session 23 ``as_pose(np.float64(1.0))``
  raised a ValueError about a 0-d shape where ``as_pose(1.0)`` (the ``float``
  that ``np.float64`` subclasses) raises the TypeError "must be a Pose2D or a
  sequence", as both did before.
* ``refuse_masked`` reduced a structured masked array's mask with ``np.any``,
  which cannot cast a structured mask to bool: an unnamed TypeError ("Iterator
  operand 1 dtype could not be cast ...") came before the callers' dtype check
  could name the argument, masked entries or not.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit._shared.validation import has_array_protocol, refuse_masked
from navkit.geometry import as_pose, as_twist
from navkit.planning import distance_field

_SCALARS = [np.float64, np.float32, np.float16, np.int64, np.int8, np.uint16, np.longdouble]


@pytest.mark.parametrize("kind", _SCALARS, ids=lambda kind: kind.__name__)
@given(value=st.floats(0.0, 100.0, allow_nan=False))
def test_numpy_scalar_is_refused_as_a_python_number_is(kind: type, value: float) -> None:
    scalar = kind(value)
    assert not has_array_protocol(scalar)
    for convert, name in ((as_pose, "pose"), (as_twist, "twist")):
        with pytest.raises(TypeError, match=f"^{name} must be a ") as from_python:
            convert(float(scalar))
        with pytest.raises(TypeError, match=f"^{name} must be a ") as from_numpy:
            convert(scalar)
        # The same sentence, but for the type's name at the end.
        assert str(from_numpy.value).rsplit(",", 1)[0] == str(from_python.value).rsplit(",", 1)[0]


def test_classes_and_non_numeric_scalars_are_no_arrays() -> None:
    scalars = (np.bool_(True), np.datetime64("2020-01-01"), np.str_("1"))
    for value in (np.ndarray, np.float64, *scalars):
        assert not has_array_protocol(value)
    assert has_array_protocol(np.zeros(2))
    assert has_array_protocol(np.zeros(()))  # a 0-d array is an array


def test_zero_d_array_still_reads_as_an_array() -> None:
    with pytest.raises(ValueError, match="pose must be 1-D"):
        as_pose(np.array(1.0))


_FIELDS = np.dtype([("x", "f8"), ("y", [("a", "f8"), ("b", "f8", (2,))])])


@st.composite
def _structured_masks(draw: st.DrawFn) -> np.ma.MaskedArray:
    rows = draw(st.integers(1, 3))
    cols = draw(st.integers(1, 3))
    data = np.ma.array(np.zeros((rows, cols), dtype=_FIELDS))
    for _ in range(draw(st.integers(0, 3))):
        r, c = draw(st.integers(0, rows - 1)), draw(st.integers(0, cols - 1))
        field = draw(st.sampled_from(["x", "a", "b0", "b1"]))
        if field == "x":
            data.mask[r, c]["x"] = True
        elif field == "a":
            data.mask[r, c]["y"]["a"] = True
        else:
            data.mask[r, c]["y"]["b"][int(field[1])] = True
    return data


@given(data=_structured_masks())
def test_structured_masked_arrays_get_named_errors(data: np.ma.MaskedArray) -> None:
    flat = np.ma.getmaskarray(data).view(np.bool_)  # the fields' booleans, all of them
    masked = bool(flat.any())
    if masked:
        with pytest.raises(ValueError, match=r"^costs has masked entries"):
            refuse_masked(data, "costs")
        with pytest.raises(ValueError, match=r"^costs has masked entries \(in an element"):
            refuse_masked(list(data), "costs")
    else:
        refuse_masked(data, "costs")
        refuse_masked(list(data), "costs")
    # A public function names the argument either way (not an unnamed TypeError).
    with pytest.raises(ValueError, match=r"^costs "):
        distance_field(data, (0, 0))


def test_structured_masked_scalar_row() -> None:
    data = np.ma.array(np.zeros(2, dtype=[("x", "f8"), ("y", "f8")]))
    data.mask[0]["y"] = True
    with pytest.raises(ValueError, match="v has masked entries"):
        refuse_masked(data[0], "v")  # an mvoid with a masked field
    refuse_masked(data[1], "v")
