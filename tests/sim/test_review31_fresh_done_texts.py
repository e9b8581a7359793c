"""``done`` values review 30's container check missed or refused wrongly (review 31, FRESH).

- A one-element NumPy array of text (``np.array(["False"])``, what a flag read
  from a CSV column or a config as a string gives) is true when its text is
  not empty: ``"False"`` ended the run at its first step as "controller done".
  ``"False"`` alone is refused (review 30); in an array it should be too.
- A one-element object array holding a str, a list or ``np.ma.masked`` took
  its element's truth value unchecked: ``[False]`` and ``"False"`` true,
  ``np.ma.masked`` false (a missing flag read as "not done").
- A tuple subclass whose class gives its own ``__bool__`` (a ``NamedTuple``
  status whose truth value is its ``done`` field) was refused as a container
  "whose truth value is whether it is empty", which is not so for it.

- An object array holding itself recursed without end.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import pytest

from navkit.sim._done import done_flag


def _object_array(element: object, shape: tuple[int, ...] = (1,)) -> np.ndarray:
    # np.array([x], dtype=object) would unpack a list x into elements.
    out = np.empty(shape, dtype=object)
    out[...] = None
    out.reshape(-1)[0] = element
    return out


TEXTS = [np.array(["False"]), np.array("False"), np.array([b"0"]), np.array([""])]


@pytest.mark.parametrize("done", TEXTS, ids=["str-1", "str-0d", "bytes-1", "empty-1"])
def test_a_one_element_text_array_is_a_type_error_naming_the_flag(done: np.ndarray) -> None:
    before = done.copy()
    with pytest.raises(TypeError, match=r"^tracker\.done must be true or false, got an ndarray"):
        done_flag(done, "tracker.done")
    np.testing.assert_array_equal(done, before)


@pytest.mark.parametrize("element", ["False", "", [False], (True,)], ids=repr)
@pytest.mark.parametrize("shape", [(1,), ()], ids=["1", "0-d"])
def test_an_object_array_of_a_container_is_refused_as_the_container(
    element: object, shape: tuple[int, ...]
) -> None:
    kind = type(element).__name__
    with pytest.raises(TypeError, match=rf"^tracker\.done must be true or false, got a {kind} "):
        done_flag(_object_array(element, shape), "tracker.done")


def test_an_object_array_of_the_masked_constant_is_refused_as_missing() -> None:
    with pytest.raises(ValueError, match=r"^tracker\.done must be true or false, got a masked"):
        done_flag(_object_array(np.ma.masked), "tracker.done")


class Status(NamedTuple):
    done: bool
    reason: str

    def __bool__(self) -> bool:
        return self.done


@pytest.mark.parametrize("done", [True, False])
def test_a_tuple_with_its_own_truth_value_keeps_it(done: bool) -> None:
    assert done_flag(Status(done, "goal"), "tracker.done") is done


@pytest.mark.parametrize(
    ("element", "expected"), [(np.True_, True), (np.False_, False), (1, True), (0.0, False)]
)
def test_an_object_array_of_a_flag_still_decides(element: object, expected: bool) -> None:
    assert done_flag(_object_array(element, ()), "tracker.done") is expected
    assert done_flag(_object_array(element), "tracker.done") is expected


class Pair(tuple[bool, str]):
    """A tuple subclass without a truth value of its own: true when not empty."""


@pytest.mark.parametrize("done", [Pair((False, "x")), np.str_("False")], ids=["Pair", "np.str_"])
def test_a_container_subclass_without_its_own_truth_value_is_still_refused(
    done: object,
) -> None:
    with pytest.raises(TypeError, match=r"whose truth value is whether it is empty"):
        done_flag(done, "tracker.done")


def test_an_object_array_holding_an_array_is_refused() -> None:
    itself = np.empty(1, dtype=object)
    itself[0] = itself
    for done in (itself, _object_array(np.array([True]))):
        with pytest.raises(TypeError, match="done must be true or false, got an object array"):
            done_flag(done, "done")
