"""The shared grid-coordinate helpers and the cost validator under hostile input."""

from __future__ import annotations

import math
import warnings
from fractions import Fraction

import numpy as np
import pytest

from navkit._shared.costs import validate_costs
from navkit._shared.grid_coords import CELL_LIMIT, as_pairs, round_half_up


def test_far_coordinates_round_to_a_clamped_cell_not_an_undefined_cast() -> None:
    values = np.array([1e300, -1e300, 2.0**70, -(2.0**70), 3.4])
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no "invalid value encountered in cast"
        cells = round_half_up(values)
    assert cells.dtype == np.int64
    assert cells.tolist() == [2**62, -(2**62), 2**62, -(2**62), 3]
    assert CELL_LIMIT == 2.0**62


def test_values_just_below_a_cell_edge_and_odd_integers_past_2_52_keep_their_cell() -> None:
    # floor(v + 0.5) rounds the sum first: 0.5 - 2**-54 + 0.5 is 1.0, and
    # 2**52 + 1.5 is 2**52 + 2 (ties to even), each one cell too far.
    below_edge = np.nextafter(0.5, 0.0)
    values = np.array([below_edge, -below_edge, 2.0**52 + 1, -(2.0**52 + 1), 2.0**53 - 1])
    assert round_half_up(values).tolist() == [0, 0, 2**52 + 1, -(2**52 + 1), 2**53 - 1]
    # Exact rational arithmetic agrees on values of every magnitude, edges included.
    rng = np.random.default_rng(7)
    values = rng.choice([-1.0, 1.0], 2000) * 2.0 ** rng.uniform(-3, 55, 2000)
    values[:8] = [0.5, -0.5, 1.5, -1.5, 2.5, -2.5, 0.0, -0.0]
    exact = [math.floor(Fraction(v) + Fraction(1, 2)) for v in values.tolist()]
    assert round_half_up(values).tolist() == exact


def test_pairs_one_or_many() -> None:
    assert as_pairs([1.0, 2.0], "p")[1] is True
    assert as_pairs(np.empty((0, 2)), "p")[0].shape == (0, 2)
    with pytest.raises(ValueError, match="p must have shape"):
        as_pairs(np.empty((2, 0)), "p")


@pytest.mark.parametrize(
    "costs",
    [
        [[1.0, 2.0], [3.0]],  # ragged
        [[1.0, None]],
        [[1.0, 10**400]],
        "11",
        {"a": 1},
        np.ones((2, 2), dtype=complex),
        np.ones((2, 2), dtype=bool),
        [[True, 2.0], [1.0, 1.0]],  # NumPy would read True as the cost 1
        ([1.0, np.True_],),
    ],
)
def test_costs_refuse_what_is_not_a_numeric_grid_with_a_value_error(costs: object) -> None:
    with pytest.raises(ValueError, match=r"^costs must"):
        validate_costs(costs)  # type: ignore[arg-type]


def test_typed_njit_decorators_compile_with_navkit_options() -> None:
    from navkit._shared.jit import njit_cached, njit_inline, typed_njit

    @njit_cached
    def twice(x: float) -> float:
        return 2.0 * x

    @njit_inline
    def plus_one(x: float) -> float:
        return x + 1.0

    @typed_njit(cache=False, fastmath=True)
    def both(x: float) -> float:
        return plus_one(twice(x))

    assert both(1.5) == 4.0
    # Numba dispatchers wrapping the original functions, signatures kept for mypy.
    assert twice.py_func.__name__ == "twice"  # type: ignore[attr-defined]
    assert plus_one.py_func(1.0) == 2.0  # type: ignore[attr-defined]
