"""A user's ``__getstate__`` inherited from a user's base class is the user's (MUTANT15).

``frozen._user_method`` walks a record subclass's MRO for the first class that
defines the method; a subclass of the user's class that defines nothing itself
must find the base's. Skipping the ``continue`` for the classes without the
method (a surviving mutant) stopped at the subclass and answered "no user
method": the copy then kept what the user's ``__getstate__`` leaves out (here
a lock, which no pickle takes).
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from test_review30_fresh_user_getstate_alone import COPIES, Cached


class Deeper(Cached):
    """Defines nothing: its ``__getstate__`` is ``Cached``'s."""


@pytest.mark.parametrize("make_copy", COPIES)
def test_an_inherited_user_getstate_is_used(make_copy: Callable[[Any], Any]) -> None:
    field: Any = Deeper((1.0, 2.0), m=2.0)
    field.note = "kept"
    field.lock = threading.Lock()
    out: Any = make_copy(field)
    assert out.note == "kept"
    assert type(out) is Deeper
    assert not hasattr(out, "lock")
    np.testing.assert_array_equal(out.goal_xy, [1.0, 2.0])
    assert out.m == 2.0
    assert not out.goal_xy.flags.writeable
