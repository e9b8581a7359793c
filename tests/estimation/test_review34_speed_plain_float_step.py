"""PlanarFusion's fast paths check their argument types in the compiled entry (issue 17).

``update_odometry`` and the other online updates used to test ``type(x) is
float`` for each argument in Python (about 70 ns, a tenth of the call) before
calling the compiled step. The step is now entered through
``planar_step_plain_entry``, whose conversion takes a float, a NumPy float64 or
an int of magnitude at most 2**53 as its value and anything else as NaN, which
the step refuses (``INVALID``, nothing changed), so the general, validating
way still sees every other type. These tests check the entry's conversion on
each argument, that it computes the float64 step bit for bit, and that the
public calls give bit for bit the general path's results for floats, NumPy
float64s and ints, with and without ``history``.
"""

from __future__ import annotations

import dataclasses
import decimal
import fractions
import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import PlanarFusion, UpdateResult
from navkit.estimation import _fusion_kernels as k


class _General(float):
    """A float subclass defined in Python: the entry takes it as NaN (general path)."""


class _Lying(float):
    """A float subclass whose ``__float__`` says something else: never read by the entry."""

    def __float__(self) -> float:
        return 123.0


def _buffer() -> np.ndarray:
    buf = np.zeros(k.BUF_SIZE)
    buf.reshape(k.BUF_ROWS, k.W)[k.BUF_P : k.BUF_P + 6] = np.eye(6)
    buf[k.BUF_TIME] = 0.0
    return buf


_REFUSED = [
    2**53 + 1,
    -(2**53) - 1,
    2**80,
    True,
    np.bool_(True),
    "1.0",
    b"1.0",
    np.float32(0.5),
    np.float16(0.5),
    np.int64(1),
    np.longdouble(0.5),
    _General(0.5),
    _Lying(0.5),
    decimal.Decimal("0.5"),
    fractions.Fraction(1, 2),
    None,
    np.array(0.5),
    np.array([0.5]),
    0.5 + 0j,
]
# Arguments of the online step: t, first, count, z0, z1, var0, var1, gate.
_GOOD = (0.1, 1, 2, 0.5, 0.25, 0.5, 0.5, math.inf)


@pytest.mark.parametrize("position", [0, 3, 4, 5, 6])
@pytest.mark.parametrize("value", _REFUSED, ids=repr)
def test_the_entry_refuses_other_types_and_changes_nothing(position: int, value: Any) -> None:
    step = k.planar_step_plain_entry()
    args: list[Any] = list(_GOOD)
    args[position] = value
    buf = _buffer()
    before = buf.tobytes()
    status, nis = step(buf, *args)
    assert status == k.INVALID and math.isnan(nis)
    assert buf.tobytes() == before
    # The plain-Python equivalent (NUMBA_DISABLE_JIT=1) decides alike.
    assert math.isnan(k._plain_value_python(value))


@pytest.mark.parametrize(
    "value", [0.5, np.float64(0.5), 1, 2**53, -(2**53), np.float64(-3.0), 0, -0.0]
)
def test_the_python_equivalent_takes_what_the_entry_takes(value: Any) -> None:
    got = k._plain_value_python(value)
    assert type(got) is float and got == float(value)


def _as(kind: str, x: float) -> Any:
    """``x`` as a float (``kind`` "float"), NumPy float64 or int (where exact), or _General."""
    if kind == "np":
        return np.float64(x)
    if kind == "int" and x == int(x) and abs(x) <= 2**53 and math.copysign(1.0, x) > 0:
        return int(x)  # (-0.0 has no int)
    if kind == "general":
        return _General(x)
    return x


_KINDS = st.sampled_from(["float", "np", "int"])


@settings(max_examples=60, deadline=None)
@given(
    steps=st.lists(
        st.tuples(
            st.floats(0.0, 0.5),  # time step (0: a measurement at the filter time)
            st.sampled_from([(0, 0), (0, 1), (1, 1), (1, 2), (2, 1), (3, 1)]),
            st.one_of(st.floats(-5.0, 5.0), st.integers(-3, 3).map(float)),
            st.one_of(st.floats(-2.0, 2.0), st.integers(-2, 2).map(float)),
            st.floats(1e-8, 2.0),
            st.one_of(st.floats(1e-8, 2.0), st.just(1.0)),
            st.sampled_from([math.inf, 3.0, 9.0]),
            st.lists(_KINDS, min_size=5, max_size=5),
        ),
        min_size=1,
        max_size=10,
    )
)
def test_the_entry_computes_the_float64_step_bit_for_bit(steps: list[Any]) -> None:
    plain, reference = k.planar_step_plain_entry(), k.planar_step_entry()
    a, b = _buffer(), _buffer()
    t = 0.0
    for dt, (first, count), z0, z1, var0, var1, gate, kinds in steps:
        t += dt
        floats = (t, z0, z1, var0, var1)
        given_ = [_as(kind, x) for kind, x in zip(kinds, floats, strict=True)]
        got = plain(a, given_[0], first, count, *given_[1:], gate)
        want = reference(b, t, first, count, z0, z1, var0, var1, gate)
        assert got[0] == want[0]
        assert np.float64(got[1]).tobytes() == np.float64(want[1]).tobytes()
        assert a.tobytes() == b.tobytes()
        if got[0] in (k.NOT_POSITIVE_DEFINITE, k.TIME_GAP):
            k.undo_step(a)
            k.undo_step(b)


def _same_result(a: UpdateResult, b: UpdateResult) -> None:
    assert type(a) is type(b) is UpdateResult
    for field in dataclasses.fields(UpdateResult):
        x, y = getattr(a, field.name), getattr(b, field.name)
        if isinstance(x, np.ndarray):
            assert x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes()
            assert x.flags.writeable == y.flags.writeable
        elif isinstance(x, float):
            assert isinstance(y, float) and (x == y or (math.isnan(x) and math.isnan(y)))
        else:
            assert x == y and type(x) is type(y)


def _call(fusion: PlanarFusion, method: str, t: Any, a: Any, b: Any, va: Any, vb: Any) -> Any:
    if method == "odometry":
        return fusion.update_odometry(t, a, b, v_variance=va, omega_variance=vb)
    if method == "predict":
        return fusion.predict(t)
    return getattr(fusion, f"update_{method}")(t, a, variance=va)


def _outcome(fusion: PlanarFusion, method: str, args: list[Any]) -> Any:
    """The call's result, or its error's type and message."""
    try:
        return _call(fusion, method, *args)
    except (TypeError, ValueError) as error:
        return type(error), str(error)


_METHODS = st.sampled_from(["odometry", "speed", "yaw", "yaw_rate", "acceleration", "predict"])


@settings(max_examples=60, deadline=None)
@given(
    steps=st.lists(
        st.tuples(
            _METHODS,
            st.sampled_from([0.0, 0.01, 0.02, 0.25, -0.01]),  # time step; < 0: late
            st.one_of(st.floats(-5.0, 5.0), st.integers(-3, 3).map(float)),
            st.floats(-2.0, 2.0),
            st.one_of(st.floats(1e-8, 2.0), st.just(1.0)),
            st.floats(1e-8, 2.0),
            st.lists(_KINDS, min_size=5, max_size=5),
        ),
        min_size=1,
        max_size=12,
    ),
    history=st.sampled_from([0.0, 0.1]),
    gate=st.sampled_from([None, 0.9]),
)
def test_public_calls_equal_the_general_path(
    steps: list[Any], history: float, gate: float | None
) -> None:
    """Floats, NumPy float64s and ints (the fast path) against Python-defined float
    subclasses of the same values (the general path, which checks everything)."""
    fast = PlanarFusion(t0=0.0, history=history, gate_probability=gate)
    slow = PlanarFusion(t0=0.0, history=history, gate_probability=gate)
    t = 0.0
    for method, dt, a, b, va, vb, kinds in steps:
        t = max(t + dt, 0.0)
        values = (t, a, b, va, vb)
        given_ = [_as(kind, x) for kind, x in zip(kinds, values, strict=True)]
        general = [_General(x) for x in values]
        got, want = _outcome(fast, method, given_), _outcome(slow, method, general)
        if isinstance(got, UpdateResult):
            _same_result(got, want)
        else:  # None from predict, or the same error (a predict back in time)
            assert got == want
        assert fast._buf.tobytes() == slow._buf.tobytes()
        _same_steps(fast, slow)


def _same_steps(a: PlanarFusion, b: PlanarFusion) -> None:
    """The steps kept for history: equal times, arguments (as floats) and states."""
    assert len(a._steps) == len(b._steps)
    for x, y in zip(a._steps, b._steps, strict=True):
        assert x[4] == y[4]
        for i in (0, 1):  # NaN: no clock before the step, or a slot left by a gone step
            assert np.float64(x[i]).tobytes() == np.float64(y[i]).tobytes()
        assert x[2].tobytes() == y[2].tobytes()
        assert x[3] == y[3] and all(type(v) in (int, float) for v in x[3])


@pytest.mark.parametrize("method", ["odometry", "speed", "yaw_rate"])
def test_kept_steps_hold_floats_whatever_the_fast_path_was_given(method: str) -> None:
    fusion = PlanarFusion(t0=0.0, history=1.0)
    _call(fusion, method, 0.1, np.float64(1.0), 2, np.float64(0.5), 1)
    (entry,) = fusion._steps
    assert type(entry[0]) is float
    assert all(type(v) is float for v in entry[3][2:])  # values, variances, gate


@pytest.mark.parametrize("t", [np.array(0.2), np.float64(0.2), _General(0.2), 1])
def test_a_stamp_of_another_type_with_history_goes_the_general_way(t: Any) -> None:
    """With steps kept, the newest stamp is compared only with a float (an array's
    comparison would be an array): other stamps take the general way, as before."""
    fusion = PlanarFusion(t0=0.0, history=1.0)
    twin = PlanarFusion(t0=0.0, history=1.0)
    for f in (fusion, twin):
        f.update_speed(0.1, 1.0, variance=1e-2)
    got = fusion.update_odometry(t, 1.0, 0.1, v_variance=1e-2, omega_variance=1e-2)
    want = twin.update_odometry(float(t), 1.0, 0.1, v_variance=1e-2, omega_variance=1e-2)
    _same_result(got, want)
    assert fusion._buf.tobytes() == twin._buf.tobytes()
