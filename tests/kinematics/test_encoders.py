"""Encoder helpers."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.kinematics import tick_delta, ticks_to_distance


def test_ticks_to_distance() -> None:
    assert ticks_to_distance(2048, ticks_per_rev=2048, wheel_radius=0.1) == pytest.approx(
        2 * math.pi * 0.1
    )
    assert ticks_to_distance(-512, ticks_per_rev=2048, wheel_radius=0.1) == pytest.approx(
        -math.pi * 0.05
    )
    np.testing.assert_allclose(
        ticks_to_distance(np.array([0, 1024]), ticks_per_rev=2048, wheel_radius=0.1),
        [0.0, math.pi * 0.1],
    )
    with pytest.raises(ValueError, match="ticks_per_rev"):
        ticks_to_distance(1, ticks_per_rev=0, wheel_radius=0.1)
    with pytest.raises(ValueError, match="wheel_radius"):
        ticks_to_distance(1, ticks_per_rev=100, wheel_radius=-0.1)
    with pytest.raises(TypeError, match="positional"):
        ticks_to_distance(1, 2048, 0.1)  # type: ignore[call-overload]


@pytest.mark.parametrize(
    ("prev", "cur", "bits", "expected"),
    [
        (65535, 2, 16, 3),
        (5, 65534, 16, -7),
        (100, 250, 16, 150),
        (32767, -32768, 16, 1),
        (2**32 - 10, 10, 32, 20),
        (10, 2**32 - 10, 32, -20),
        (0, 2**31, 32, -(2**31)),
    ],
)
def test_tick_delta_known(prev: int, cur: int, bits: int, expected: int) -> None:
    assert tick_delta(prev, cur, bits=bits) == expected


@settings(max_examples=40)
@given(
    st.integers(8, 64).flatmap(
        lambda b: st.tuples(
            st.just(b), st.integers(0, 2**b - 1), st.integers(-(2 ** (b - 1)), 2 ** (b - 1) - 1)
        )
    )
)
def test_tick_delta_recovers_true_step(case: tuple[int, int, int]) -> None:
    bits, start, step = case
    cur = (start + step) % 2**bits
    assert tick_delta(start, cur, bits=bits) == step


test_tick_delta_recovers_true_step_thoroughly = slow_twin(
    test_tick_delta_recovers_true_step, max_examples=100
)


def test_tick_delta_arrays_and_errors() -> None:
    prev = np.array([65530, 0, 100], dtype=np.int64)
    cur = np.array([4, 65535, 90], dtype=np.int64)
    np.testing.assert_array_equal(tick_delta(prev, cur, bits=16), [10, -1, -10])
    unsigned = np.array([2**64 - 1], dtype=np.uint64)
    assert tick_delta(unsigned, np.array([1], dtype=np.uint64), bits=64)[0] == 2
    with pytest.raises(ValueError, match="bits"):
        tick_delta(0, 1, bits=1)
    with pytest.raises(TypeError, match="previous"):
        tick_delta(0.5, 1, bits=16)
    with pytest.raises(ValueError, match="current"):
        tick_delta(0, 70000, bits=16)
    with pytest.raises(TypeError, match="positional"):
        tick_delta(0, 1, 16)  # type: ignore[call-overload]


@pytest.mark.parametrize(
    ("prev", "cur", "bits", "expected"),
    [
        ([], [], 16, []),  # an empty list is float64 to NumPy
        ([2**64 - 1, -1], [0, 2**63], 64, [1, -(2**63) + 1]),  # no common integer dtype
        ([[2**64 - 1], [-1]], 0, 64, [[1], [1]]),
    ],
)
def test_tick_delta_takes_python_int_readings_that_numpy_gives_no_integer_dtype(
    prev: object, cur: object, bits: int, expected: list[int]
) -> None:
    """Unsigned and signed readings may be mixed, and a log may be empty."""
    out = tick_delta(prev, cur, bits=bits)  # type: ignore[call-overload]
    assert isinstance(out, np.ndarray) and out.dtype == np.int64
    np.testing.assert_array_equal(out, expected)


@pytest.mark.parametrize("huge", [2**64, 2**70, -(2**70), [3, 2**100]])
def test_tick_delta_readings_beyond_64_bits_are_out_of_range(huge: object) -> None:
    # They used to be refused as a TypeError ("got dtype object"), not as out of range.
    with pytest.raises(ValueError, match=r"current holds readings outside .* 64-bit"):
        tick_delta(0, huge, bits=64)  # type: ignore[call-overload]
    with pytest.raises(ValueError, match=r"previous holds readings outside .* 16-bit"):
        tick_delta(huge, 0, bits=16)  # type: ignore[call-overload]


@pytest.mark.parametrize("readings", [[True, 5], (0, False), [[1, 2], [np.True_, 3]]])
def test_tick_delta_refuses_booleans_mixed_into_lists(readings: object) -> None:
    # NumPy converts [True, 5] to int64 [1, 5]: a flag read as a counter value.
    with pytest.raises(TypeError, match=r"previous .* bool"):
        tick_delta(readings, 0, bits=16)  # type: ignore[call-overload]
    with pytest.raises(TypeError, match=r"current .* bool"):
        tick_delta(0, readings, bits=16)  # type: ignore[call-overload]


@pytest.mark.parametrize("bits", [True, np.True_, 16.0])
def test_tick_delta_bits_that_are_not_integers_are_type_errors(bits: object) -> None:
    # As documented: a bool is not a counter width, even though operator.index takes it.
    with pytest.raises(TypeError, match="bits"):
        tick_delta(1, 2, bits=bits)  # type: ignore[arg-type]
