"""A covariance typed with short decimals keeps the strict symmetry check (review 54, FOUND7).

The float32 tolerance (64 float32 epsilons of the largest entry) is for values
float32 arithmetic rounded. fafdb71 kept the strict 1e-9 for integers of at most
2²⁴; a matrix typed with halves (``[[1e6, 2.5], [3.5, 1e6]]``) or with decimals
in float32 (``np.float32([[1e6, 0.1], [0.2, 1e6]])``) was still averaged. A
matrix none of whose entries looks rounded (each an integer of at most 2²⁴ or a
decimal of at most 6 significant digits, FLT_DIG, as ``intended_resolution``
reads a float32 resolution) is now refused as a float64 one is. The rounded
entries of float32 products are 7 to 9 digits long: such products are still
averaged (FRESH's proposed rule, checked against them here).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import ExtendedKalmanFilter, PlanarFusion
from navkit.estimation._covariance import _short_decimals, _typed

_F32 = np.float32


def _digits(value: float) -> int:
    """Significant digits of the shortest decimal that float32 rounds to ``value``."""
    mantissa = np.format_float_scientific(_F32(value), unique=True).split("e")[0]
    return len(mantissa.replace(".", "").lstrip("-"))


def _as_float32(values: object) -> np.ndarray:
    """``values`` rounded to float32, held as float64 (as the filters convert them)."""
    return np.asarray(values, dtype=_F32).astype(np.float64)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.floats(width=32, allow_nan=False, allow_infinity=False), min_size=1))
def test_short_decimals_are_those_whose_shortest_float32_decimal_has_6_digits(
    values: list[float],
) -> None:
    got = _short_decimals(np.array(values, dtype=np.float64))
    assert got.tolist() == [_digits(v) <= 6 for v in values]


@settings(max_examples=300, deadline=None)
@given(st.floats(width=32, allow_nan=False, allow_infinity=False))
def test_the_first_look_at_one_entry_agrees_with_the_arrays(value: float) -> None:
    exact = value == round(value) and abs(value) <= 2.0**24
    assert _typed(value) == (exact or bool(_short_decimals(np.array([value]))[0]))


def test_short_decimals_at_their_edges() -> None:
    typed = [0.1, 2.5, 0.0078125, 1e-5, 9.99999e-6, 123456.0, 999999.0, 1e38, 1e-38, 0.0, -0.0]
    assert _short_decimals(_as_float32(typed)).all()  # as a ROS message: float64 values
    rounded = [0.1000001, 1234567.0, 1e6 + 0.0625, 2.0**24, float(_F32(1.0) / _F32(3.0))]
    assert not _short_decimals(_as_float32(rounded)).any()
    assert _short_decimals(_as_float32([[0.1, 2.5], [7.0, 0.3]])).shape == (2, 2)


@pytest.mark.parametrize(
    "p0",
    [
        np.array([[1e6, 0.1], [0.2, 1e6]], dtype=_F32),
        np.array([[1e6, 0.1], [0.2, 1e6]], dtype=_F32).astype(np.float64),  # a ROS message
        [[float(2**24), 2.5], [3.5, float(2**24)]],  # integers and halves
        [[1e5, -0.25], [0.0, 1e5]],
    ],
)
def test_a_typed_asymmetric_covariance_is_refused(p0: np.ndarray | list[list[float]]) -> None:
    with pytest.raises(ValueError, match="P0 must be symmetric"):
        ExtendedKalmanFilter(np.zeros(2), p0)
    fusion_p0 = np.diag(np.full(6, 1e6))
    fusion_p0[:2, :2] = p0
    with pytest.raises(ValueError, match="P0 must be symmetric"):
        PlanarFusion(P0=fusion_p0)


def test_one_entry_with_a_rounded_look_keeps_the_float32_tolerance() -> None:
    # 1e6 + 0.0625 is a float32 value of 8 digits: a product's, as far as values tell.
    p0 = np.array([[1e6 + 0.0625, 2.5], [3.5, 1e6]])
    ekf = ExtendedKalmanFilter(np.zeros(2), p0)
    assert ekf.P[0, 1] == ekf.P[1, 0] == 3.0


def _products(seed: int, count: int) -> list[np.ndarray]:
    """Asymmetric float32 products ``J S Jᵀ`` and ``J (S Jᵀ)``, of rows 2 to 4."""
    rng = np.random.default_rng(seed)
    variances = [1e7, 1.2e7, 8.5e6, 1e6, 1e4, 100.0, 2.5, 0.25, 0.01, 1e-4, 4.0, 1.0, 3e5, 0.05]
    found: list[np.ndarray] = []
    while len(found) < count:
        n = int(rng.integers(2, 5))
        jac = (rng.normal(size=(n, n)) * 10.0 ** rng.uniform(-2, 2.5)).astype(_F32)
        kind = rng.random()
        if kind < 0.3:  # a Jacobian typed with few digits
            jac = np.round(jac, int(rng.integers(0, 3))).astype(_F32)
        elif kind < 0.4:  # a rotation
            n, angle = 2, rng.uniform(-np.pi, np.pi)
            jac = np.array(
                [[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]], dtype=_F32
            )
        spread = np.diag(rng.choice(variances, n)).astype(_F32)
        p = jac @ spread @ jac.T if rng.random() < 0.5 else jac @ (spread @ jac.T)
        p64 = p.astype(np.float64)
        if np.isfinite(p64).all() and (p64 != p64.T).any():
            found.append(p)
    return found


def test_float32_products_are_still_averaged() -> None:
    refused = []
    for p in _products(54, 3000):
        try:
            ExtendedKalmanFilter(np.zeros(len(p)), p)
        except ValueError as exc:
            if "symmetric" in str(exc):
                refused.append(p)
    # 55 of 50,436 measured (41 of them refused before too: all integers from 2**23
    # to 2**24, every float32 value there being one); far from most of them.
    assert len(refused) <= 10
    for p in refused:  # only products no entry of which looks rounded
        values = p.astype(np.float64)
        exact = (values == np.round(values)) & (np.abs(values) <= 2.0**24)
        assert (exact | _short_decimals(values)).all()
