"""The EKF under a ROS 2 ``MultiThreadedExecutor``'s ways of calling it.

A model function (``f``, ``F``, ``h``, ``H``) that called back into the same
filter's ``predict`` or ``update`` had the nested step applied and then
overwritten by the outer one, computed from the state before it: a nested
predict left ``x`` one step behind a ``P`` propagated twice, a nested update
counted the measurement's residual twice (``x`` overshot both measurements).
Such a call now raises ``RuntimeError`` and leaves the filter unchanged.
Filters in different threads share no buffers.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter

F = np.array([[1.0, 0.1], [0.0, 1.0]])
Q = 0.01 * np.eye(2)
H = np.array([[1.0, 0.0]])
R = np.array([[0.01]])


def _predict(ekf: ExtendedKalmanFilter) -> None:
    ekf.predict(lambda x: F @ x, F, Q)


def _update(ekf: ExtendedKalmanFilter) -> None:
    ekf.update([1.0], lambda x: H @ x, H, R)


NESTED: dict[str, Callable[[ExtendedKalmanFilter], None]] = {
    "predict": _predict,
    "update": _update,
}


def _outer_calls(
    ekf: ExtendedKalmanFilter, slot: str, inner: Callable[[ExtendedKalmanFilter], None]
) -> None:
    """An outer step whose model function ``slot`` calls ``inner(ekf)``."""

    def nesting(fn: Callable[[Any], Any]) -> Callable[[Any], Any]:
        def wrapped(x: Any) -> Any:
            inner(ekf)
            return fn(x)

        return wrapped

    models: dict[str, Callable[[Any], Any]] = {
        "f": lambda x: F @ x, "F": lambda x: F, "h": lambda x: H @ x, "H": lambda x: H,
    }  # fmt: skip
    models[slot] = nesting(models[slot])
    if slot in ("f", "F"):
        ekf.predict(models["f"], models["F"], Q)
    else:
        ekf.update([1.0], models["h"], models["H"], R)


@pytest.mark.parametrize("slot", ["f", "F", "h", "H"])
@pytest.mark.parametrize("inner", sorted(NESTED))
def test_a_step_nested_in_a_model_function_raises_and_changes_nothing(
    slot: str, inner: str
) -> None:
    ekf = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    _predict(ekf)
    x, p = ekf.x, ekf.P
    with pytest.raises(RuntimeError, match=f"ExtendedKalmanFilter.{inner}"):
        _outer_calls(ekf, slot, NESTED[inner])
    np.testing.assert_array_equal(ekf.x, x)
    np.testing.assert_array_equal(ekf.P, p)
    # Usable afterwards, as if the failed step never happened.
    reference = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    _predict(reference)
    for filt in (ekf, reference):
        _predict(filt)
        _update(filt)
    np.testing.assert_array_equal(ekf.x, reference.x)
    np.testing.assert_array_equal(ekf.P, reference.P)


def test_a_model_function_raising_leaves_the_filter_usable() -> None:
    ekf = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))

    def boom(x: Any) -> Any:
        raise KeyError("model failed")

    with pytest.raises(KeyError):
        ekf.predict(boom, F, Q)
    with pytest.raises(KeyError):
        ekf.update([1.0], lambda x: H @ x, boom, R)
    _predict(ekf)  # not refused as nested
    _update(ekf)


def test_model_functions_may_read_and_copy_the_filter() -> None:
    import copy

    ekf = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    seen: list[Any] = []

    def f(x: Any) -> Any:
        twin = copy.deepcopy(ekf)
        _predict(twin)  # a copy is another filter: it may step
        seen.append((ekf.x, twin.x))
        return F @ x

    ekf.predict(f, F, Q)
    reference = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    _predict(reference)
    np.testing.assert_array_equal(ekf.x, reference.x)
    np.testing.assert_array_equal(seen[0][0], [0.0, 1.0])
    np.testing.assert_array_equal(seen[0][1], reference.x)


def _run(seed: int) -> list[np.ndarray]:
    rng = np.random.default_rng(seed)
    ekf = ExtendedKalmanFilter(rng.normal(size=3), np.eye(3), angle_states=(2,))
    out = []
    for i in range(60):
        jac = np.eye(3) + 0.01 * rng.normal(size=(3, 3))
        ekf.predict(jac.__matmul__, jac, 0.01 * np.eye(3))
        m = 1 + i % 3  # measurement sizes switch the update buffers
        h = rng.normal(size=(m, 3))
        ekf.update(rng.normal(size=m), h.__matmul__, h, 0.1 * np.eye(m), gate=100.0)
        out += [ekf.x, ekf.P]
    return out


def test_filters_in_threads_give_what_they_give_alone() -> None:
    threads = 6
    alone = [_run(seed) for seed in range(threads)]
    barrier = threading.Barrier(threads)

    def task(seed: int) -> list[np.ndarray]:
        barrier.wait()
        return _run(seed)

    with ThreadPoolExecutor(threads) as pool:
        together = list(pool.map(task, range(threads)))
    for a, b in zip(alone, together, strict=True):
        for u, v in zip(a, b, strict=True):
            np.testing.assert_array_equal(u, v)
