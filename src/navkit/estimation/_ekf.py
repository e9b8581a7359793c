"""A general Extended Kalman Filter on numpy arrays.

The public layer checks types and shapes and calls one compiled kernel per step
(:mod:`navkit.estimation._ekf_kernels`), which checks values, computes the step
and commits it only when it is valid.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from typing import Any, NoReturn

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.se2 import wrap_scalar
from navkit._shared.types import FloatArray, IntArray
from navkit._shared.validation import as_float_array, positive_float
from navkit.errors import FilterError
from navkit.estimation._covariance import covariance, index_tuple
from navkit.estimation._ekf_kernels import (
    BAD_F,
    BAD_FX,
    BAD_H,
    BAD_HX,
    BAD_Z,
    GATED,
    NIS_OVERFLOW,
    NOISE_CHANGED,
    NOT_FINITE,
    NOT_POSITIVE_DEFINITE,
    OK,
    RESIDUAL_OVERFLOW,
    S_NOT_FINITE,
    S_NOT_POSITIVE_DEFINITE,
    STATE_OVERFLOW,
    STATE_P,
    STATE_X,
    ekf_predict,
    ekf_update,
    new_rbuf,
    new_state,
    set_q,
    set_r,
)
from navkit.estimation._gaussian import GaussianEstimate
from navkit.estimation._result import UpdateResult, new_result

__all__ = ["ExtendedKalmanFilter"]

_OVERFLOW = "overflow: not applied, float64 cannot hold "
_F64 = np.dtype(np.float64)
_NDARRAY = np.ndarray
_NO_INDICES: IntArray = np.zeros(0, dtype=np.int64)
_CACHE_SIZE = 16  # validated R matrices and angle index tuples kept per filter

StateFunction = Callable[[FloatArray], ArrayLike]
Jacobian = Callable[[FloatArray], ArrayLike] | ArrayLike


class ExtendedKalmanFilter(GaussianEstimate):
    r"""Extended Kalman Filter with angle-aware residuals and Mahalanobis gating.

    Prediction :math:`x \leftarrow f(x)`, :math:`P \leftarrow F P F^T + Q` with
    :math:`F = \partial f/\partial x` at the prior state. Update with
    :math:`y = z - h(x)` (angle components wrapped to (-π, π]),
    :math:`S = H P H^T + R`, :math:`K = P H^T S^{-1}`, :math:`x \leftarrow x + K y`
    and the Joseph-form covariance
    :math:`P \leftarrow (I - KH) P (I - KH)^T + K R K^T`, which stays symmetric
    positive definite under rounding (the short form :math:`(I - KH)P` does not).
    After every step ``P`` is exactly symmetric (its lower triangle is computed
    and mirrored) and checked to be finite and positive definite (a Cholesky
    factorisation); a step that would break this raises
    :class:`~navkit.errors.FilterError` and leaves the filter unchanged. A
    measurement whose residual, NIS or updated state would overflow float64 is
    not applied (``accepted=False`` with the reason). The state and covariance
    never become NaN or infinite. A covariance whose condition number nears
    1/machine-epsilon (about 1e16; e.g. after a Jacobian entry of 1e16 or
    variances 1e16 apart that the model couples) cannot be propagated reliably in
    float64: a later step may then raise ``FilterError``, again leaving the filter
    unchanged.

    An ordinary class with ``__slots__`` rather than a frozen dataclass: every
    step changes its estimate in place.

    Parameters
    ----------
    x0 : array_like, shape (n,), n >= 1
        Initial state (finite).
    P0 : array_like, shape (n, n)
        Initial covariance, symmetric positive definite, entries of magnitude at
        most 1e100 (as every covariance the filter takes: ``Q``, ``R``).
    angle_states : sequence of int, optional
        Indices of state components that are angles (rad); they are wrapped to
        (-π, π] after every step (keyword-only).

    Raises
    ------
    TypeError, ValueError
        An argument outside the ranges above, naming it.

    Examples
    --------
    A 1-D constant-velocity model observed in position:

    >>> import numpy as np
    >>> ekf = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))
    >>> F = np.array([[1.0, 0.1], [0.0, 1.0]])
    >>> ekf.predict(lambda x: F @ x, F, 0.01 * np.eye(2))
    >>> result = ekf.update([0.12], lambda x: x[:1], np.array([[1.0, 0.0]]), [[0.01]])
    >>> result.accepted, ekf.x.round(4)
    (True, array([0.1198, 1.0019]))
    """

    __slots__ = ("_angles", "_meas_angles", "_n", "_rbufs", "_state")

    def __init__(self, x0: ArrayLike, P0: ArrayLike, *, angle_states: Iterable[int] = ()) -> None:
        x = np.array(as_float_array(x0, "x0", ndim=1), dtype=np.float64, copy=True)
        n = x.shape[0]
        if n == 0:
            raise ValueError("x0 must have at least one component")
        p = covariance(P0, "P0", n)
        self._angles = index_tuple(angle_states, "angle_states", n)
        for i in self._angles:
            x[i] = wrap_scalar(float(x[i]))
        # Everything a predict needs in one array (see _ekf_kernels), including the
        # last validated Q: filters usually pass the same matrices every step, and
        # re-checking symmetry and definiteness would cost more than the step. The
        # kernels compare the Q (or R) passed with the one validated and ask for a
        # new check when they differ.
        self._adopt(new_state(x, p, self._angles))

    def _adopt(self, state: FloatArray) -> None:
        """Take ``state`` (see _ekf_kernels) as the filter's estimate."""
        n: int = state.shape[1]
        self._n: int = n
        self._state: FloatArray = state
        self._x = state[STATE_X]
        self._p = state[STATE_P : STATE_P + n]
        # Per measurement size m: the last validated R and the update's scratch space.
        self._rbufs: dict[int, FloatArray] = {}
        # Validated angle_measurements by the identity of the (immutable) tuple passed,
        # which the entry keeps alive: {id: (tuple, m, indices)}.
        self._meas_angles: dict[int, tuple[tuple[int, ...], int, IntArray]] = {}

    def __reduce__(self) -> tuple[Callable[..., ExtendedKalmanFilter], tuple[Any, ...]]:
        # The estimate lives in one array updated in place, with x and P views into it:
        # copies (copy.copy too) and pickles get their own array and views.
        return _restore, (self._state.copy(), self._angles)

    @property
    def dim(self) -> int:
        """State dimension n."""
        return self._n

    @property
    def angle_states(self) -> tuple[int, ...]:
        """Indices of the angle components of the state."""
        return self._angles

    def predict(self, f: StateFunction, F: Jacobian, Q: ArrayLike) -> None:
        """Propagate the state through the motion model.

        Parameters
        ----------
        f : callable
            ``f(x) -> x'`` with ``x`` a copy of the state, shape (n,).
        F : callable or array_like, shape (n, n)
            Jacobian of ``f`` at the current (prior) state, or a function
            ``F(x)`` returning it.
        Q : array_like, shape (n, n)
            Process noise covariance for this step, symmetric positive
            semi-definite, entries of magnitude at most 1e100.

        Notes
        -----
        The values ``f`` and ``F`` return are checked like arguments: real,
        finite, of the right shape (``TypeError``/``ValueError`` naming
        ``f(x)`` or ``F``).

        Raises
        ------
        TypeError, ValueError
            On non-callable ``f``, wrong shapes, non-finite values or an invalid
            ``Q``; the state is unchanged.
        FilterError
            If the predicted covariance is not finite or not positive definite;
            the state is unchanged.
        """
        if not callable(f):
            raise TypeError(f"f must be callable, got {type(f).__name__}")
        n = self._n
        square = (n, n)
        # Arrays of the kernels' one type (C-contiguous writeable float64) and of the
        # right shape go straight to the kernel, which checks their values; anything
        # else is converted and checked in full first (the checks are inlined: this
        # runs every step).
        jac = F(self._x.copy()) if callable(F) else F
        if not (type(jac) is _NDARRAY and jac.dtype is _F64 and jac.shape == square
                and jac.flags.carray):  # fmt: skip
            jac = _c_array(jac, "F", square)
        q = Q
        if not (type(q) is _NDARRAY and q.dtype is _F64 and q.shape == square
                and q.flags.carray):  # fmt: skip
            q = _c_array(q, "Q", square)
        x_new = f(self._x.copy())
        if not (type(x_new) is _NDARRAY and x_new.dtype is _F64 and x_new.shape == (n,)
                and x_new.flags.carray):  # fmt: skip
            x_new = _c_array(x_new, "f(x)", (n,))
        status = ekf_predict(self._state, x_new, jac, q)
        if status == OK:
            return
        if status == NOISE_CHANGED:
            set_q(self._state, q, covariance(q, "Q", n, semidefinite=True))
            status = ekf_predict(self._state, x_new, jac, q)
        if status != OK:
            _raise(status, "predicted covariance")

    def update(
        self,
        z: ArrayLike,
        h: StateFunction,
        H: Jacobian,
        R: ArrayLike,
        *,
        angle_measurements: Iterable[int] = (),
        gate: float | None = None,
    ) -> UpdateResult:
        """Correct the state with a measurement.

        Parameters
        ----------
        z : array_like, shape (m,)
            Measurement.
        h : callable
            Measurement model ``h(x) -> (m,)``.
        H : callable or array_like, shape (m, n)
            Jacobian of ``h`` at the current state, or a function returning it.
        R : array_like, shape (m, m)
            Measurement noise covariance, symmetric positive definite, entries
            of magnitude at most 1e100.
        angle_measurements : sequence of int, optional
            Indices of the components of ``z`` that are angles; their residuals
            are wrapped to (-π, π] (keyword-only).
        gate : float, optional
            Chi-square threshold on the normalised innovation squared (NIS)
            yᵀ S⁻¹ y; a measurement with NIS above it is rejected (e.g.
            ``scipy.stats.chi2.ppf(0.997, m)``); keyword-only.

        Returns
        -------
        UpdateResult
            Whether the measurement was applied, its NIS and residual. Not
            applied (``accepted=False``, state unchanged) when gated, or when the
            residual, the NIS or the updated state would overflow float64 (the
            reason says ``"overflow"``; ``nis`` is inf and ``residual`` empty when
            they overflowed).

        Raises
        ------
        TypeError, ValueError
            On wrong shapes, non-finite values or an invalid ``R`` or ``gate``
            (also in what ``h`` and ``H`` return); the state is unchanged.
        FilterError
            If the innovation or updated covariance is not finite or not
            positive definite; the state is unchanged.
        """
        if not callable(h):
            raise TypeError(f"h must be callable, got {type(h).__name__}")
        meas = z
        if not (type(meas) is _NDARRAY and meas.dtype is _F64 and meas.ndim == 1
                and meas.flags.carray):  # fmt: skip
            meas = _c_copy(as_float_array(meas, "z", ndim=1))
        m = meas.shape[0]
        if m == 0:
            raise ValueError("z must have at least one component")
        shape = (m, self._n)
        jac = H(self._x.copy()) if callable(H) else H
        if not (type(jac) is _NDARRAY and jac.dtype is _F64 and jac.shape == shape
                and jac.flags.carray):  # fmt: skip
            jac = _c_array(jac, "H", shape)
        r = R
        shape = (m, m)
        if not (type(r) is _NDARRAY and r.dtype is _F64 and r.shape == shape
                and r.flags.carray):  # fmt: skip
            r = _c_array(r, "R", shape)
        rbuf = self._rbufs.get(m)
        if rbuf is None:
            rbuf = self._new_rbuf(m)
        if type(angle_measurements) is tuple and not angle_measurements:
            angles = _NO_INDICES
        else:
            angles = self._measurement_angles(angle_measurements, m)
        threshold = math.inf if gate is None else positive_float(gate, "gate")
        hx = h(self._x.copy())
        if not (type(hx) is _NDARRAY and hx.dtype is _F64 and hx.shape == (m,)
                and hx.flags.carray):  # fmt: skip
            hx = _c_array(hx, "h(x)", (m,))
        y = np.empty(m)
        status, nis = ekf_update(self._state, meas, hx, jac, r, rbuf, angles, threshold, y)
        if status == NOISE_CHANGED:
            set_r(rbuf, r, covariance(r, "R", m))
            status, nis = ekf_update(self._state, meas, hx, jac, r, rbuf, angles, threshold, y)
        if status == OK:
            return new_result(True, nis, y, None)
        if status == GATED:
            return new_result(False, nis, y, f"rejected by the gate: NIS {nis:.6g} > {threshold}")
        if status == RESIDUAL_OVERFLOW:
            return new_result(False, math.inf, np.empty(0), _OVERFLOW + "the residual z - h(x)")
        if status == NIS_OVERFLOW:
            return new_result(False, math.inf, y, _OVERFLOW + "the NIS")
        if status == STATE_OVERFLOW:
            return new_result(False, nis, y, _OVERFLOW + "the updated state")
        if status == S_NOT_FINITE:
            _raise(NOT_FINITE, "innovation covariance S")
        if status == S_NOT_POSITIVE_DEFINITE:
            _raise(NOT_POSITIVE_DEFINITE, "innovation covariance S")
        _raise(status, "updated covariance")

    def _new_rbuf(self, m: int) -> FloatArray:
        """A new R-and-scratch buffer for ``m``-dimensional measurements (kept for reuse)."""
        if len(self._rbufs) >= _CACHE_SIZE:
            self._rbufs.clear()
        rbuf = self._rbufs[m] = new_rbuf(self._n, m)
        return rbuf

    def _measurement_angles(self, indices: Iterable[int], m: int) -> IntArray:
        """``angle_measurements`` as an int64 array, validated once per tuple object."""
        if type(indices) is tuple:
            hit = self._meas_angles.get(id(indices))
            if hit is not None and hit[0] is indices and hit[1] == m:
                return hit[2]
        out = np.array(index_tuple(indices, "angle_measurements", m), dtype=np.int64)
        if type(indices) is tuple:
            if len(self._meas_angles) >= _CACHE_SIZE:
                self._meas_angles.clear()
            self._meas_angles[id(indices)] = (indices, m, out)
        return out

    def __repr__(self) -> str:
        return f"ExtendedKalmanFilter(dim={self._n}, angle_states={self._angles})"


def _restore(state: FloatArray, angles: tuple[int, ...]) -> ExtendedKalmanFilter:
    """An :class:`ExtendedKalmanFilter` with the given ``state`` array (unpickling, copies)."""
    ekf: ExtendedKalmanFilter = object.__new__(ExtendedKalmanFilter)
    ekf._angles = angles
    ekf._adopt(state)
    return ekf


_NON_FINITE_NAMES = {BAD_F: "F", BAD_FX: "f(x)", BAD_Z: "z", BAD_H: "H", BAD_HX: "h(x)"}


def _c_copy(arr: FloatArray) -> FloatArray:
    """A C-contiguous writeable float64 copy of ``arr``."""
    return np.array(arr, dtype=np.float64, order="C", copy=True)


def _c_array(value: ArrayLike, name: str, shape: tuple[int, ...]) -> FloatArray:
    """``value`` converted and checked in full as a C-contiguous float64 array of ``shape``.

    The slow path, for what is not already a C-contiguous writeable float64
    ndarray of the right shape (lists, other dtypes, read-only or strided arrays).
    Raises ``TypeError``/``ValueError`` naming ``name``.
    """
    return _c_copy(as_float_array(value, name, shape=shape))


def _raise(status: int, what: str) -> NoReturn:
    """Raise the error a kernel status code stands for."""
    name = _NON_FINITE_NAMES.get(status)
    if name is not None:
        raise ValueError(f"{name} must contain only finite values")
    if status == NOT_FINITE:
        raise FilterError(f"{what} is not finite")
    raise FilterError(f"{what} is not positive definite")
