"""Items ``quaternion_to_yaw``'s one-quaternion fast path must leave to the general way.

The fast path (review 33) reads a list, tuple or (4,) float64 array of exact
``float``/``np.float64`` items itself. Anything else must get the general way's
answer or refusal: ``bool`` items (an ``isinstance(v, float | int)`` test would
take ``True`` as 1.0), ``int`` subclasses, NumPy integer and float32 items,
0-d and 1-element arrays, huge ints. The oracle is a ``list`` subclass, which
the fast path never takes.
"""

from __future__ import annotations

import enum
import math

import numpy as np
import pytest

from navkit.geometry import quaternion_to_yaw


class _Listed(list):  # type: ignore[type-arg]
    """A list the fast path does not take (exact types only): the general way's oracle."""


class _Cell(enum.IntEnum):
    SEVEN = 7


def _outcome(value: object) -> tuple[str, object]:
    try:
        out = quaternion_to_yaw(value)  # type: ignore[arg-type]
    except (TypeError, ValueError) as e:
        return type(e).__name__, str(e)
    assert isinstance(out, float)
    return "float", (out, math.copysign(1.0, out))


_QUATERNIONS = [
    [0.0, 0.0, True, 1.0],
    [0.0, 0.0, 1, 1],
    [0.0, 0.0, np.int64(1), 1.0],
    [0.0, 0.0, np.float32(0.6), 0.8],
    (0.0, 0.0, np.array(0.6), 0.8),
    [0.0, 0.0, _Cell.SEVEN, 1.0],
    [0.0, 0.0, 2**1100, 1.0],
    [np.array([0.0]), 0.0, 0.6, 0.8],
    [1e-300, 1e-300, 1e-300, 1e-300],
    [5e-324, 0.0, 0.0, 0.0],
    [0.0, 0.0, 1e-170, 1e-170],
    [0.0, 0.0, -0.0, -1.0],
]


@pytest.mark.parametrize("q", _QUATERNIONS, ids=lambda q: repr(q)[:40])
def test_quaternion_to_yaw_items_as_general(q: list[object]) -> None:
    assert _outcome(q) == _outcome(_Listed(q))


def test_bool_quaternion_refused_named() -> None:
    with pytest.raises(TypeError, match="quaternion"):
        quaternion_to_yaw([0.0, 0.0, True, 1.0])


def test_fast_path_follows_no_caller_seterr() -> None:
    q = [1e-200, 1e-200, 1e-200, 1.0]  # the squares underflow (review 31's case)
    with np.errstate(all="raise"):
        got = _outcome(q)
    assert got == _outcome(_Listed(q)) and got[0] == "float"
