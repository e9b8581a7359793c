"""ExtendedKalmanFilter under long random sequences of steps, checked against NumPy.

The filter keeps caches between calls (the last validated ``Q`` and ``R`` per
measurement size, ``angle_measurements`` tuples by identity, the options of the
last update): a hypothesis state machine mixes predictions and updates of
measurement sizes 1-3, re-passes the same matrix objects with new values, swaps
options and gates (float, NumPy float, int), makes invalid calls (which must raise
and change nothing) and swaps the filter for a copy or a pickle round trip. After
every step the state and covariance equal a plain NumPy EKF implementing the
documented equations (Joseph form, residual angles and angle states wrapped to
(-π, π], the NIS gate), the covariance is exactly symmetric and positive definite.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, rule

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter
from stateful_runs import COPIERS, run_machine

Array = np.ndarray[Any, np.dtype[np.float64]]
_COPIERS: tuple[Callable[[ExtendedKalmanFilter], ExtendedKalmanFilter], ...] = COPIERS


def _wrap(a: Array) -> Array:
    w = np.mod(a + np.pi, 2.0 * np.pi) - np.pi
    out: Array = np.where(w == -np.pi, np.pi, w)
    return out


def _spd(rng: np.random.Generator, k: int, scale: float) -> Array:
    a = rng.normal(size=(k, k))
    out: Array = scale * (a @ a.T + k * np.eye(k)) / k
    return out


class EKFMachine(RuleBasedStateMachine):
    rng: np.random.Generator
    n: int
    angles: list[int]
    x: Array
    P: Array
    ekf: ExtendedKalmanFilter
    Qs: list[Array]
    Rs: dict[int, list[Array]]
    angle_options: dict[int, list[Any]]

    @initialize(n=st.integers(1, 3), seed=st.integers(0, 2**32 - 1), data=st.data())
    def start(self, n: int, seed: int, data: st.DataObject) -> None:
        self.rng = np.random.default_rng(seed)
        self.n = n
        self.angles = sorted(data.draw(st.sets(st.integers(0, n - 1))))
        x0 = 2.0 * self.rng.normal(size=n)
        self.P = _spd(self.rng, n, 1.0)
        self.ekf = ExtendedKalmanFilter(x0, self.P, angle_states=self.angles)
        self.x = x0.copy()
        self.x[self.angles] = _wrap(self.x[self.angles])
        # Objects passed again and again: the filter caches by identity and by value.
        self.Qs = [_spd(self.rng, n, 0.01) for _ in range(2)]
        self.Rs = {m: [_spd(self.rng, m, s) for s in (0.1, 1.0)] for m in (1, 2, 3)}
        # (), every component, the last one, and a list (mutable: never cached).
        self.angle_options = {m: [(), tuple(range(m)), (m - 1,), [0]] for m in (1, 2, 3)}

    @rule(q=st.integers(0, 2), scale_in_place=st.booleans())
    def predict(self, q: int, scale_in_place: bool) -> None:
        n = self.n
        F = np.eye(n) + 0.2 * self.rng.normal(size=(n, n))
        u = 0.3 * self.rng.normal(size=n)
        Q = np.zeros((n, n)) if q == 2 else self.Qs[q]
        if scale_in_place and q < 2:
            Q *= 1.5  # the same object as a cached Q, with other values
        self.ekf.predict(lambda x: F @ x + u, F, Q)
        x = F @ self.x + u
        x[self.angles] = _wrap(x[self.angles])
        P = F @ self.P @ F.T + Q
        self.x, self.P = x, (P + P.T) / 2

    @rule(kind=st.sampled_from(["not symmetric", "negative", "nan", "shape"]))
    def predict_refused(self, kind: str) -> None:
        n = self.n
        Q = self.Qs[0].copy()
        if kind == "not symmetric" and n > 1:
            Q[0, 1] += 1.0
        elif kind in ("negative", "not symmetric"):
            Q = -np.eye(n)
        elif kind == "nan":
            Q[0, 0] = np.nan
        else:
            Q = np.eye(n + 1)
        with pytest.raises((ValueError, FilterError)):
            self.ekf.predict(lambda x: x, np.eye(n), Q)

    @rule(
        m=st.integers(1, 3),
        r=st.integers(0, 1),
        option=st.integers(0, 3),
        gate=st.sampled_from([None, 4.0, 50.0, 1e9]),
        gate_type=st.sampled_from([float, np.float64, int]),
        scale_in_place=st.booleans(),
        pass_defaults=st.booleans(),
    )
    def update(
        self,
        m: int,
        r: int,
        option: int,
        gate: float | None,
        gate_type: Callable[[float], float],
        scale_in_place: bool,
        pass_defaults: bool,
    ) -> None:
        n = self.n
        H = self.rng.normal(size=(m, n))
        c = self.rng.normal(size=m)
        z = H @ self.x + c + 2.0 * self.rng.normal(size=m)
        R = self.Rs[m][r]
        if scale_in_place:
            R *= 1.25
        angles = self.angle_options[m][option]
        if isinstance(angles, list):
            angles[:] = [int(self.rng.integers(0, m))]  # the same list, new contents
        kwargs: dict[str, Any] = {}
        if option or pass_defaults:
            kwargs["angle_measurements"] = angles
        if gate is not None:
            kwargs["gate"] = gate_type(gate)
        elif pass_defaults:
            kwargs["gate"] = None
        result = self.ekf.update(z, lambda x: H @ x + c, H, R, **kwargs)

        y = z - (H @ self.x + c)
        y[list(angles)] = _wrap(y[list(angles)])
        S = H @ self.P @ H.T + R
        nis = float(y @ np.linalg.solve(S, y))
        np.testing.assert_allclose(result.residual, y, rtol=1e-12, atol=1e-12)
        assert math.isclose(result.nis, nis, rel_tol=1e-7, abs_tol=1e-9)
        accepted = gate is None or nis <= gate
        if gate is not None and math.isclose(nis, gate, rel_tol=1e-6):
            accepted = result.accepted  # too close to the gate to call
        assert result.accepted == accepted
        if accepted:
            K = np.linalg.solve(S, H @ self.P).T
            x = self.x + K @ y
            x[self.angles] = _wrap(x[self.angles])
            A = np.eye(n) - K @ H
            P = A @ self.P @ A.T + K @ R @ K.T
            self.x, self.P = x, (P + P.T) / 2

    @rule(
        m=st.integers(1, 3),
        kind=st.sampled_from(["cached angles", "list", "gate 0", "gate < 0", "R", "H shape"]),
    )
    def update_refused(self, m: int, kind: str) -> None:
        n = self.n
        H = np.ones((m, n))
        R = self.Rs[m][0]
        kwargs: dict[str, Any] = {}
        if kind == "cached angles":
            # A tuple validated with 3-component measurements (here by a gated one,
            # which changes nothing) names a component a smaller one does not have.
            last = self.angle_options[3][2]
            gated = self.ekf.update(
                np.full(3, 5.0), lambda x: np.zeros(3), np.ones((3, n)), self.Rs[3][0],
                angle_measurements=last, gate=1e-300,
            )
            assert not gated.accepted
            kwargs["angle_measurements"] = last if m < 3 else (3,)
        elif kind == "list":
            kwargs["angle_measurements"] = listed = self.angle_options[m][3]
            listed[:] = [m]  # a list passed before, changed in place to a bad index
        elif kind == "gate 0":
            kwargs["gate"] = 0.0
        elif kind == "gate < 0":
            kwargs["gate"] = -1.0
        elif kind == "R":
            R = -np.eye(m)
        else:
            H = np.ones((m, n + 1))
        with pytest.raises((ValueError, TypeError, FilterError)):
            self.ekf.update(np.zeros(m), lambda x: np.zeros(m), H, R, **kwargs)

    @rule(how=st.integers(0, len(_COPIERS) - 1))
    def swap_for_copy(self, how: int) -> None:
        old, self.ekf = self.ekf, _COPIERS[how](self.ekf)
        n = self.n
        # The original moving on must not reach the copy (checked by the invariant).
        old.predict(lambda x: x + 1.0, np.eye(n), np.eye(n))
        old.update(np.ones(1), lambda x: x[:1], np.ones((1, n)), np.eye(1))

    @invariant()
    def equals_numpy_reference(self) -> None:
        np.testing.assert_allclose(self.ekf.x, self.x, rtol=1e-8, atol=1e-8)
        np.testing.assert_allclose(self.ekf.P, self.P, rtol=1e-8, atol=1e-10)
        P = self.ekf.P
        np.testing.assert_array_equal(P, P.T)
        assert np.linalg.eigvalsh(P).min() > 0.0
        assert np.all(np.abs(self.ekf.x[self.angles]) <= np.pi)


def test_step_sequences_match_numpy_ekf() -> None:
    run_machine(EKFMachine, examples=30, steps=20)


@pytest.mark.slow
def test_step_sequences_match_numpy_ekf_long() -> None:
    run_machine(EKFMachine, examples=400, steps=40)
