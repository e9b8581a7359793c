"""The nested-step refusal of a filter subclass names the subclass (review 29, FNF2).

A step called from a model function of a step of the same filter raised
``RuntimeError("ExtendedKalmanFilter.predict called from ...")`` for a user's
subclass too, while its repr names the subclass. Checked: fails against
``_ekf.py`` before the change (the message named ExtendedKalmanFilter).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter

F = np.array([[1.0, 0.1], [0.0, 1.0]])
Q = 0.01 * np.eye(2)
H = np.array([[1.0, 0.0]])


class Tracker2D(ExtendedKalmanFilter):
    __slots__ = ()


@pytest.mark.parametrize("cls", [ExtendedKalmanFilter, Tracker2D])
@pytest.mark.parametrize("inner", ["predict", "update"])
def test_the_nested_step_refusal_names_the_class(
    cls: type[ExtendedKalmanFilter], inner: str
) -> None:
    ekf = cls([0.0, 1.0], np.eye(2))

    def f(x: np.ndarray) -> np.ndarray:
        if inner == "predict":
            ekf.predict(lambda y: F @ y, F, Q)
        else:
            ekf.update([0.0], lambda y: y[:1], H, [[0.01]])
        return F @ x

    x, p = ekf.x, ekf.P
    with pytest.raises(
        RuntimeError, match=rf"^{cls.__name__}\.{inner} called from a model function"
    ):
        ekf.predict(f, F, Q)
    np.testing.assert_array_equal(ekf.x, x)
    np.testing.assert_array_equal(ekf.P, p)
