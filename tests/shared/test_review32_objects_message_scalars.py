"""Error messages quote NumPy scalars as the numbers they hold (review 32, OBJECTS).

NumPy 2 writes its scalars with their type, and some messages quoted the
caller's value with ``repr``: a world point passed as a cell from an array
(``tuple(xy)``) read ``start_cell must hold integers, got (np.float64(1.5),
np.float64(2.0))``, ``bits=np.int64(65)`` read ``got np.int64(65)`` and
``FusionStatus(np.int64(9))`` ``np.int64(9) is not a valid FusionStatus``. The
messages now go through ``_shared.validation.shown`` (the status lookup takes
Python's int). Found by running the fuzz catalogue with NumPy-scalar spellings
of every hostile number and scanning the messages for ``np.<type>(``.
"""

from __future__ import annotations

import re
from collections.abc import Callable

import numpy as np
import pytest

from navkit._shared.validation import shown
from navkit.estimation import FusionStatus
from navkit.kinematics import tick_delta
from navkit.planning import GreedyStep, astar
from navkit.sim import sweep
from navkit.sim.scenarios import Greedy

_NUMPY_REPR = re.compile(r"np\.\w+\(")

CASES: list[tuple[str, Callable[[], object], type[Exception], str]] = [
    (
        "a world point as a cell",
        lambda: astar(np.ones((5, 5)), (np.float64(1.5), np.float64(2.0)), (4, 4)),
        TypeError,
        "start_cell must hold integers, got (1.5, 2.0): a cell is an integer (row, col) index",
    ),
    (
        "three indices",
        lambda: astar(np.ones((5, 5)), (np.int64(1),) * 3, (4, 4)),
        ValueError,
        "start_cell must be a (row, col) pair, got (1, 1, 1)",
    ),
    (
        "a NumPy bool in a cell",
        lambda: astar(np.ones((5, 5)), (np.True_, np.int64(1)), (4, 4)),
        TypeError,
        "start_cell must hold integers, got (True, 1)",
    ),
    (
        "bits out of range",
        lambda: tick_delta(1, 2, bits=np.int64(65)),
        ValueError,
        "bits must be an integer from 2 to 64, got 65",
    ),
    ("bits a bool", lambda: tick_delta(1, 2, bits=np.True_), TypeError, "got True"),
    (
        "a fractional count",
        lambda: GreedyStep((1, 2), (0.2, 0.0), g=0.2, h=1.8, candidates=np.float64(1.5)),
        TypeError,
        "candidates must hold integers, got 1.5",
    ),
    (
        "an unknown status code",
        lambda: FusionStatus(np.int64(9)),
        ValueError,
        "9 is not a valid FusionStatus",
    ),
    (
        "a float seed",
        lambda: sweep(Greedy(noise=False), seeds=np.float32(1.5)),
        TypeError,
        "seeds must be an integer or a sequence of integers, got 1.5",
    ),
]


@pytest.mark.parametrize(("what", "call", "error", "text"), CASES, ids=[c[0] for c in CASES])
def test_messages_show_numpy_scalars_as_numbers(
    what: str, call: Callable[[], object], error: type[Exception], text: str
) -> None:
    with pytest.raises(error) as info:
        call()
    message = str(info.value)
    assert text in message, message
    assert not _NUMPY_REPR.search(message), message


def test_shown_follows_tuples_and_lists_one_level() -> None:
    assert shown((np.float64(1.5), np.int64(2))) == "(1.5, 2)"
    assert shown([np.float32(0.5), "a"]) == "[0.5, 'a']"
    assert shown(np.uint8(7)) == "7"
    # Arrays and other objects keep their own repr.
    assert shown(np.array([1.5])) == "array([1.5])"
    assert shown("x") == "'x'"
    assert shown(((np.int64(1),),)) == "((np.int64(1),),)"  # one level only
