"""A ``done`` whose truth value raises is refused naming the flag (review 32, mutants).

``done_flag`` documents that a value without a truth value (NumPy's "truth
value ... is ambiguous" for an array of several flags) is refused with a
``TypeError`` naming ``name``. No test reached that last branch: a mutant
replacing its ``raise`` with ``pass`` survived the suite, and returned None
(false: the run went on, past the controller's done) for an array of two
flags. Oracle: Python's own truth value raises for these objects (NumPy's
``ValueError`` for the arrays, the class's own for the user type), so no
answer could be right. Checked: the test fails on that mutant of ``_done.py``
and passes on HEAD.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.sim._done import done_flag


class _Undecided:
    """A user's flag whose ``__bool__`` refuses to answer."""

    def __bool__(self) -> bool:
        raise RuntimeError("not decided yet")


@pytest.mark.parametrize(
    ("done", "cause"),
    [
        (np.array([True, False]), "ambiguous"),
        (np.array([[True]] * 2), "ambiguous"),
        (np.array([1.0, 0.0]), "ambiguous"),
        (_Undecided(), "not decided yet"),
    ],
    ids=["two flags", "a column of flags", "two numbers", "a raising __bool__"],
)
def test_a_value_without_a_truth_value_is_refused(done: object, cause: str) -> None:
    with pytest.raises(TypeError, match=r"^tracker\.done must be true or false, got ") as info:
        done_flag(done, "tracker.done")
    assert cause in str(info.value)
    assert type(done).__name__ in str(info.value)
