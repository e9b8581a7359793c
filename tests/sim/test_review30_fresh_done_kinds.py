"""``done`` kinds that review 29's number check missed (review 30, FRESH).

- A masked ``done`` (``np.ma.masked``, a one-element masked array) is no
  flag: it was decided by the data under the mask (``np.ma.array([0.5],
  mask=[True])`` ended the run, ``np.ma.masked`` never did), silently. Now
  refused (``ValueError``) naming the flag.
- A one-element object array holding a number (what ``np.array([x],
  dtype=object)`` or a pandas ``.values`` of mixed columns gives) skipped the
  check: ``0.5`` and NaN in one were true. Now checked as its element is.
- An int beyond Python's 4300-digit str limit (or a Decimal that long) made
  the message itself raise a ``ValueError`` naming nothing ("Exceeds the
  limit (4300 digits) for integer string conversion"). The message is now
  bounded and names the flag.

Checked: against ``_done.py`` before the change every refusal test here fails
(``True``/``False`` came back, or the int-string message); the others pass.
"""

from __future__ import annotations

import math
from decimal import Decimal

import numpy as np
import pytest

from navkit.sim._done import done_flag

MASKED = [
    np.ma.masked,
    np.ma.array([0.5], mask=[True]),
    np.ma.array([0.0], mask=[True]),
    np.ma.array(1.0, mask=True),
    np.ma.array([True], mask=[True]),
]


@pytest.mark.parametrize("done", MASKED, ids=["constant", "0.5", "0.0", "0-d", "bool"])
def test_a_masked_done_is_refused_naming_it(done: object) -> None:
    with pytest.raises(ValueError, match=r"tracker\.done must be true or false, got a masked"):
        done_flag(done, "tracker.done")


def test_an_unmasked_masked_array_keeps_its_flag() -> None:
    assert done_flag(np.ma.array([True], mask=[False]), "tracker.done") is True
    assert done_flag(np.ma.array([0.0], mask=[False]), "tracker.done") is False


@pytest.mark.parametrize("value", [0.5, math.nan, 2, Decimal("0.5")], ids=repr)
def test_a_one_element_object_array_is_checked_as_its_element(value: object) -> None:
    done = np.array([value], dtype=object)
    with pytest.raises(ValueError, match=r"tracker\.done must be true or false, got ndarray"):
        done_flag(done, "tracker.done")
    assert done[0] is value  # not changed


@pytest.mark.parametrize(("value", "expected"), [(1, True), (0.0, False), (True, True)])
def test_a_one_element_object_array_of_a_flag_keeps_it(value: object, expected: bool) -> None:
    assert done_flag(np.array([value], dtype=object), "tracker.done") is expected


@pytest.mark.parametrize("done", [10**5000, -(10**5000), Decimal("5" * 5000)], ids=type)
def test_a_huge_number_is_refused_with_a_bounded_message(done: object) -> None:
    with pytest.raises(ValueError, match=r"^tracker\.done must be true or false, got ") as info:
        done_flag(done, "tracker.done")
    assert len(str(info.value)) < 200
