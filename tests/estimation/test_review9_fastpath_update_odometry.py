"""``PlanarFusion.update_odometry``: the plain-float fast path equals the general path.

The fast path builds its :class:`UpdateResult` through a plain slotted twin
whose class is then switched; the general path (taken by anything but five
Python floats, here NumPy float64 scalars of the same values) builds it with
``new_result``. Both must give the same filter state bit for bit, results equal
field by field (every field of the dataclass, so a field added later is
covered), genuine frozen UpdateResults that copy and pickle, and the same
errors for the same bad values.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import pickle
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import PlanarFusion, UpdateResult


def _same_result(a: UpdateResult, b: UpdateResult) -> None:
    assert type(a) is type(b) is UpdateResult
    for field in dataclasses.fields(UpdateResult):
        x, y = getattr(a, field.name), getattr(b, field.name)
        if isinstance(x, np.ndarray):
            assert isinstance(y, np.ndarray)
            assert x.dtype == y.dtype and x.shape == y.shape
            assert x.tobytes() == y.tobytes()
            assert x.flags.writeable == y.flags.writeable
        elif isinstance(x, float):
            assert isinstance(y, float)
            assert x == y or (math.isnan(x) and math.isnan(y))
        else:
            assert x == y and type(x) is type(y)


def _general(*values: float) -> tuple[Any, ...]:
    """The same values as NumPy scalars: not plain floats, so the general path."""
    return tuple(np.float64(v) for v in values)


@settings(max_examples=40, deadline=None)
@given(
    steps=st.lists(
        st.tuples(
            st.floats(1e-4, 0.5),  # time step
            st.floats(-3.0, 3.0),  # v
            st.floats(-2.0, 2.0),  # omega
            st.floats(1e-8, 1.0),  # v variance
            st.floats(1e-8, 1.0),  # omega variance
        ),
        min_size=1,
        max_size=12,
    ),
    gate=st.sampled_from([None, 0.5, 0.99]),
)
def test_fast_path_equals_general_path(
    steps: list[tuple[float, float, float, float, float]], gate: float | None
) -> None:
    fast = PlanarFusion(t0=0.0, gate_probability=gate)
    slow = PlanarFusion(t0=0.0, gate_probability=gate)
    t = 0.0
    for dt, v, w, vv, wv in steps:
        t += dt
        a = fast.update_odometry(t, v, w, v_variance=vv, omega_variance=wv)
        gt, gv, gw, gvv, gwv = _general(t, v, w, vv, wv)
        b = slow.update_odometry(gt, gv, gw, v_variance=gvv, omega_variance=gwv)
        _same_result(a, b)
        assert fast._buf.tobytes() == slow._buf.tobytes()


def test_fast_result_is_a_genuine_independent_frozen_update_result() -> None:
    fusion = PlanarFusion(t0=0.0)
    first = fusion.update_odometry(0.01, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)
    kept = first.residual.copy()
    assert type(first) is UpdateResult and first.accepted and first.reason is None
    with pytest.raises(dataclasses.FrozenInstanceError):
        first.nis = 0.0  # type: ignore[misc]
    # The next step writes the filter's residual row: the result keeps its own.
    second = fusion.update_odometry(0.02, -1.0, 0.5, v_variance=1e-4, omega_variance=1e-4)
    assert not np.shares_memory(first.residual, second.residual)
    assert not np.shares_memory(first.residual, fusion._buf)
    assert first.residual.tobytes() == kept.tobytes()
    for clone in (copy.copy(first), copy.deepcopy(first), pickle.loads(pickle.dumps(first))):
        _same_result_values(clone, first)
        assert type(clone) is UpdateResult
        assert not clone.residual.flags.writeable
    assert repr(first).startswith("UpdateResult(accepted=True, nis=")
    assert bool(first) is True


def _same_result_values(a: UpdateResult, b: UpdateResult) -> None:
    assert (a.accepted, a.nis, a.reason) == (b.accepted, b.nis, b.reason)
    assert a.residual.tobytes() == b.residual.tobytes()


@pytest.mark.parametrize(
    ("args", "name"),
    [
        ((math.nan, 1.0, 0.1, 1e-4, 1e-4), "t"),
        ((0.01, math.inf, 0.1, 1e-4, 1e-4), "v"),
        ((0.01, 1.0, -math.inf, 1e-4, 1e-4), "omega"),
        ((0.01, 1.0, 0.1, 0.0, 1e-4), "v_variance"),
        ((0.01, 1.0, 0.1, 1e-4, 1e200), "omega_variance"),
        ((0.01, 1.0, 0.1, -1e-4, 1e-4), "v_variance"),
    ],
)
def test_bad_floats_get_the_general_paths_error(args: tuple[float, ...], name: str) -> None:
    errors = []
    for values in (args, _general(*args)):
        fusion = PlanarFusion(t0=0.0)
        before = fusion._buf.tobytes()
        t, v, w, vv, wv = values
        with pytest.raises((TypeError, ValueError)) as info:
            fusion.update_odometry(t, v, w, v_variance=vv, omega_variance=wv)
        assert fusion._buf.tobytes() == before
        errors.append((type(info.value), str(info.value)))
    assert errors[0] == errors[1]
    assert name in errors[0][1]


@pytest.mark.parametrize("position", range(5))
@pytest.mark.parametrize("bad", [True, np.bool_(False), "1.0", 1 + 0j, None])
def test_non_numbers_refused_wherever_they_are(position: int, bad: Any) -> None:
    values: list[Any] = [0.01, 1.0, 0.1, 1e-4, 1e-4]
    values[position] = bad
    fusion = PlanarFusion(t0=0.0)
    before = fusion._buf.tobytes()
    names = ("t", "v", "omega", "v_variance", "omega_variance")
    with pytest.raises(TypeError, match=names[position]):
        fusion.update_odometry(
            values[0], values[1], values[2], v_variance=values[3], omega_variance=values[4]
        )
    assert fusion._buf.tobytes() == before


@pytest.mark.parametrize(
    "values",
    [
        (1, 1, 0, 1e-4, 1e-4),  # Python ints
        (np.float32(0.25), np.float32(1.5), 0.1, 1e-4, np.float32(1e-3)),
        (np.int64(1), 1.0, np.float16(0.5), 1e-4, 1e-4),
    ],
)
def test_other_real_types_give_the_float_results(values: tuple[Any, ...]) -> None:
    plain = tuple(float(v) for v in values)
    a, b = PlanarFusion(t0=0.0), PlanarFusion(t0=0.0)
    ra = a.update_odometry(
        values[0], values[1], values[2], v_variance=values[3], omega_variance=values[4]
    )
    rb = b.update_odometry(
        plain[0], plain[1], plain[2], v_variance=plain[3], omega_variance=plain[4]
    )
    _same_result(ra, rb)
    assert a._buf.tobytes() == b._buf.tobytes()


def test_out_of_order_and_gated_results_equal_the_general_paths() -> None:
    fast = PlanarFusion(t0=0.0, gate_probability=0.5)
    slow = PlanarFusion(t0=0.0, gate_probability=0.5)
    for t, v in ((0.1, 0.0), (0.05, 0.0), (0.2, 50.0), (0.3, 0.01)):
        a = fast.update_odometry(t, v, 0.0, v_variance=1e-6, omega_variance=1e-6)
        gt, gv, gw, gvv, gwv = _general(t, v, 0.0, 1e-6, 1e-6)
        b = slow.update_odometry(gt, gv, gw, v_variance=gvv, omega_variance=gwv)
        _same_result(a, b)
        assert fast._buf.tobytes() == slow._buf.tobytes()
    assert not fast.update_odometry(0.05, 0.0, 0.0, v_variance=1e-6, omega_variance=1e-6)
