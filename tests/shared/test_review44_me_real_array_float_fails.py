"""An object array whose numbers cannot become floats is a TypeError (review 44).

MUTANT18's mutants 192–194 (the final float64 conversion of ``_real_array``)
survived: no test gave a ``numbers.Real`` whose ``__float__`` fails.
"""

from __future__ import annotations

import numbers
from typing import Any

import numpy as np
import pytest

from navkit._shared.validation import as_float_array


class _Unconvertible(numbers.Real):
    """A Real whose conversion to float fails, as a user's number type's may."""

    def __float__(self) -> float:
        raise ValueError("no float for this one")


for _name in numbers.Real.__abstractmethods__ - {"__float__"}:
    setattr(_Unconvertible, _name, lambda *args, **kwargs: NotImplemented)
_Unconvertible.__abstractmethods__ = frozenset()


@pytest.mark.parametrize("shape", [(2,), (2, 2)])
def test_an_unconvertible_real_is_a_type_error_naming_the_argument(shape: tuple[int, ...]) -> None:
    values: Any = np.empty(shape, dtype=object)
    values[...] = _Unconvertible()
    with pytest.raises(TypeError, match=r"^xs must be numeric array-like: no float for this one"):
        as_float_array(values, "xs")
