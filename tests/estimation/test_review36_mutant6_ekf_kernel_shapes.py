"""Every argument of the EKF's steps one row or column too many is refused, by name.

Mutation gap (MUTANT6): the predict kernel's shape test reading ``q.shape[1]``
for ``q.shape[0]`` passed every test. The kernel then took a Q with an extra
row whose first n rows are the Q already validated as that Q (its
``_equal`` compares n rows), and predicted with it, where the contract (Q is
n x n) refuses it. Each argument is tried after a step with the right
arrays, so the kernels' own checks (not the first call's full validation)
are what stands between the wrong shape and the numbers; the filter is
unchanged afterwards.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter

N, M = 3, 2
JAC = np.array([[1.0, 0.1, 0.0], [0.0, 1.0, 0.1], [0.0, 0.0, 1.0]])
Q = 0.01 * np.eye(N)
H = np.eye(M, N)
R = 0.1 * np.eye(M)


def _row(a: Any) -> Any:
    """``a`` with one more row (entry) of zeros: its leading block unchanged."""
    return np.append(a, np.zeros((1, *a.shape[1:])), axis=0)


def _col(a: Any) -> Any:
    return np.append(a, np.zeros((a.shape[0], 1)), axis=1)


def _fx(x: Any) -> Any:
    return JAC @ x


def _hx(x: Any) -> Any:
    return H @ x


_CASES: dict[str, tuple[str, Callable[[ExtendedKalmanFilter], object]]] = {
    "f(x) row": ("f(x)", lambda e: e.predict(lambda x: _row(_fx(x)), JAC, Q)),
    "F row": ("F", lambda e: e.predict(_fx, _row(JAC), Q)),
    "F column": ("F", lambda e: e.predict(_fx, _col(JAC), Q)),
    "Q row": ("Q", lambda e: e.predict(_fx, JAC, _row(Q))),
    "Q column": ("Q", lambda e: e.predict(_fx, JAC, _col(Q))),
    "h(x) row": ("h(x)", lambda e: e.update(np.zeros(M), lambda x: _row(_hx(x)), H, R)),
    "H row": ("H", lambda e: e.update(np.zeros(M), _hx, _row(H), R)),
    "H column": ("H", lambda e: e.update(np.zeros(M), _hx, _col(H), R)),
    "R row": ("R", lambda e: e.update(np.zeros(M), _hx, H, _row(R))),
    "R column": ("R", lambda e: e.update(np.zeros(M), _hx, H, _col(R))),
}


@pytest.mark.parametrize("case", sorted(_CASES))
def test_one_row_or_column_too_many_after_good_steps_is_refused(case: str) -> None:
    name, call = _CASES[case]
    ekf = ExtendedKalmanFilter(np.ones(N), np.eye(N))
    for _ in range(2):  # the kernels are compiled and hold these Q and R as validated
        ekf.predict(_fx, JAC, Q)
        ekf.update(np.zeros(M), _hx, H, R)
    x, p = ekf.x, ekf.P
    message = rf"^{re.escape(name)} must have length \d along axis [01]"
    with pytest.raises(ValueError, match=message):
        call(ekf)
    np.testing.assert_array_equal(ekf.x, x)
    np.testing.assert_array_equal(ekf.P, p)
