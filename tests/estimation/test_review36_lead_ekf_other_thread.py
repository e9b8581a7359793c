"""A step refused because another thread's step runs says so (review 36, lead).

``ExtendedKalmanFilter`` refuses a step made while a step of the same filter
runs its model functions. Such a step made by another thread was told it was
"called from a model function (f, F, h or H) of the same filter's step",
advice for a nested call the caller never made (found by review 36's thread
review, CONCUR). The refusal now tells the two apart by the calling thread's
stack. Checked: the other-thread test fails against ``_ekf.py`` before the change.
"""

from __future__ import annotations

import threading
from collections.abc import Callable

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter

F = np.array([[1.0, 0.1], [0.0, 1.0]])
Q = 0.01 * np.eye(2)
H = np.array([[1.0, 0.0]])


class Tracker2D(ExtendedKalmanFilter):
    __slots__ = ()

    def predict(self, *args: object, **kwargs: object) -> None:  # type: ignore[override]
        super().predict(*args, **kwargs)  # type: ignore[arg-type]


def _step(ekf: ExtendedKalmanFilter, which: str) -> Callable[[], None]:
    if which == "predict":
        return lambda: ekf.predict(lambda y: F @ y, F, Q)
    return lambda: ekf.update([0.0], lambda y: y[:1], H, [[0.01]])


@pytest.mark.parametrize("cls", [ExtendedKalmanFilter, Tracker2D])
@pytest.mark.parametrize("outer", ["predict", "update"])
@pytest.mark.parametrize("inner", ["predict", "update"])
def test_another_threads_step_is_told_so(
    cls: type[ExtendedKalmanFilter], outer: str, inner: str
) -> None:
    ekf = cls([0.0, 1.0], np.eye(2))
    inside = threading.Event()
    release = threading.Event()

    def model(x: np.ndarray) -> np.ndarray:
        inside.set()
        assert release.wait(30)
        return F @ x if outer == "predict" else x[:1]

    if outer == "predict":
        first = threading.Thread(target=lambda: ekf.predict(model, F, Q))
    else:
        first = threading.Thread(target=lambda: ekf.update([0.5], model, H, [[0.01]]))
    first.start()
    try:
        assert inside.wait(30)
        with pytest.raises(RuntimeError) as info:
            _step(ekf, inner)()
    finally:
        release.set()
        first.join(30)
    message = str(info.value)
    assert message.startswith(f"{cls.__name__}.{inner} called while another thread's step")
    assert "one thread at a time" in message
    assert "model function (f, F, h or H) of the same filter" not in message
    # The first thread's step was not disturbed: the filter steps on afterwards.
    _step(ekf, inner)()
    assert np.all(np.isfinite(ekf.x))


@pytest.mark.parametrize("cls", [ExtendedKalmanFilter, Tracker2D])
@pytest.mark.parametrize("inner", ["predict", "update"])
def test_a_nested_step_deeper_in_the_model_function_is_still_a_nested_one(
    cls: type[ExtendedKalmanFilter], inner: str
) -> None:
    ekf = cls([0.0, 1.0], np.eye(2))

    def helper() -> None:
        _step(ekf, inner)()

    def h(x: np.ndarray) -> np.ndarray:
        helper()
        return x[:1]

    x, p = ekf.x, ekf.P
    with pytest.raises(
        RuntimeError, match=rf"^{cls.__name__}\.{inner} called from a model function"
    ):
        ekf.update([0.3], h, H, [[0.01]])
    np.testing.assert_array_equal(ekf.x, x)
    np.testing.assert_array_equal(ekf.P, p)
