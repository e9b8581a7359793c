"""The fast paths' PLAIN_FLOAT conversion at its edges (a fresh review of review 34).

``planar_step_plain_entry`` converts its five float arguments in C, calling
``PyLong_AsLongLongAndOverflow`` on an ``int``: these pin what review 34's
tests left out, all found sound: an int subclass (``IntEnum``) and ints at and
beyond the 64-bit range and the float range go the general way (NaN, nothing
changed) with no Python error left pending and no reference kept or lost; and
the public updates given them answer as the general way does.
"""

from __future__ import annotations

import enum
import gc
import math
import sys
from typing import Any

import numpy as np
import pytest

from navkit.estimation import PlanarFusion
from navkit.estimation import _fusion_kernels as k


class _Gear(enum.IntEnum):
    ONE = 1


class _Count(int):
    """An int subclass defined in Python."""


_GOOD = (0.1, 1, 2, 0.5, 0.25, 0.5, 0.5, math.inf)  # t, first, count, z0, z1, var0, var1, gate

# Values the entry takes as NaN: ints beyond 2**53 up to far beyond 2**1024 (their
# float() overflows), the long long boundary, and int subclasses.
_NAN = [2**63 - 1, 2**63, -(2**63), -(2**63) - 1, 2**64, 2**1024, -(2**1100),
        _Gear.ONE, _Count(1), np.uint64(1)]  # fmt: skip


def _buffer() -> np.ndarray:
    buf = np.zeros(k.BUF_SIZE)
    buf.reshape(k.BUF_ROWS, k.W)[k.BUF_P : k.BUF_P + 6] = np.eye(6)
    buf[k.BUF_TIME] = 0.0
    return buf


@pytest.mark.parametrize("position", [0, 3, 4, 5, 6])
@pytest.mark.parametrize("value", _NAN, ids=repr)
def test_large_ints_and_int_subclasses_arrive_as_nan(position: int, value: Any) -> None:
    step = k.planar_step_plain_entry()
    args: list[Any] = list(_GOOD)
    args[position] = value
    buf = _buffer()
    before = buf.tobytes()
    status, nis = step(buf, *args)
    assert status == k.INVALID and math.isnan(nis)
    assert buf.tobytes() == before
    assert math.isnan(k._plain_value_python(value))


def test_no_reference_is_kept_and_no_error_left_pending() -> None:
    step = k.planar_step_plain_entry()
    # Objects of this test's own (no small int, interned str or None, whose counts
    # move with anything else the process does).
    values = [*(v + 0 if type(v) is int else v for v in _NAN), 12345678901, 0.5 + 0.25,
              np.float64(0.5), "".join(["0", ".5"]), object()]  # fmt: skip
    counts = [sys.getrefcount(v) for v in values]
    buf = _buffer()
    for _ in range(2000):
        for v in values:
            step(buf, 0.1, 1, 1, v, 0.0, 1.0, 1.0, math.inf)
    del v  # the loop's own reference to the last value
    gc.collect()
    assert [sys.getrefcount(v) for v in values] == counts
    # An error left set in C would surface at the next call into the C API.
    assert sys.exc_info() == (None, None, None)
    assert int("7") + len([1]) == 8


def test_ints_at_two_to_the_53_are_taken_exactly() -> None:
    step = k.planar_step_plain_entry()
    for value in (2**53, -(2**53), 2**53 - 1):
        a, b = _buffer(), _buffer()
        got = step(a, 0.1, 1, 1, value, 0.0, 1.0, 1.0, math.inf)
        want = step(b, 0.1, 1, 1, float(value), 0.0, 1.0, 1.0, math.inf)
        assert got[0] == want[0] == k.ACCEPTED
        assert a.tobytes() == b.tobytes()


@pytest.mark.parametrize("value", [2**63, 2**1100, _Gear.ONE, _Count(1), 2**53 + 1])
@pytest.mark.parametrize("history", [0.0, 5.0])
def test_the_public_update_answers_as_the_general_way(value: Any, history: Any) -> None:
    # The general way converts what float() takes (an IntEnum, 2**63 rounded) or refuses
    # it naming the argument (2**1100 overflows): the same as with the fast path bypassed.
    def fusion() -> PlanarFusion:
        return PlanarFusion(np.zeros(6), np.eye(6), t0=0.0, history=history)

    def call(f: PlanarFusion, v: Any) -> Any:
        try:
            return f.update_odometry(0.1, v, 0.0, v_variance=1e30, omega_variance=1.0)
        except (TypeError, ValueError) as exc:
            return type(exc), str(exc)

    fast, general = fusion(), fusion()
    got = call(fast, value)
    try:
        as_float: Any = float(value)
    except OverflowError:
        as_float = value  # refused the same way either way
    want = call(general, as_float)
    if isinstance(got, tuple):
        assert got == want
        assert "v" in got[1]
    else:
        assert not isinstance(want, tuple)
        assert got.status == want.status
        assert fast.x.tobytes() == general.x.tobytes()
        assert fast.P.tobytes() == general.P.tobytes()
