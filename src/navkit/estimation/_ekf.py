"""A general Extended Kalman Filter on numpy arrays."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.se2 import wrap_scalar
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array, positive_float
from navkit.errors import FilterError
from navkit.estimation._covariance import covariance, index_tuple
from navkit.estimation._gaussian import GaussianEstimate
from navkit.estimation._result import UpdateResult, new_result

__all__ = ["ExtendedKalmanFilter"]

_OVERFLOW = "overflow: not applied, float64 cannot hold "

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
    After every step ``P`` is symmetrised and checked to be finite and positive
    definite; a step that would break this raises
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

    __slots__ = ("_angles", "_n", "_validated")

    def __init__(self, x0: ArrayLike, P0: ArrayLike, *, angle_states: Iterable[int] = ()) -> None:
        x = np.array(as_float_array(x0, "x0", ndim=1), dtype=np.float64, copy=True)
        n = x.shape[0]
        if n == 0:
            raise ValueError("x0 must have at least one component")
        self._n: int = n
        self._p: FloatArray = covariance(P0, "P0", n)
        self._angles = index_tuple(angle_states, "angle_states", n)
        self._x: FloatArray = self._wrap_states(x)
        # The last validated Q and R: filters usually pass the same matrices every step,
        # and re-checking symmetry and definiteness would cost more than the step.
        self._validated: dict[str, FloatArray] = {}

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
        jac = as_float_array(F(self._x.copy()) if callable(F) else F, "F", shape=(n, n))
        q = self._noise(Q, "Q", n, semidefinite=True)
        x_new = np.array(as_float_array(f(self._x.copy()), "f(x)", shape=(n,)), copy=True)
        p_new = self._checked(jac @ self._p @ jac.T + q, "predicted covariance")
        self._x = self._wrap_states(x_new)
        self._p = p_new

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
        meas = as_float_array(z, "z", ndim=1)
        m = meas.shape[0]
        n = self._n
        if m == 0:
            raise ValueError("z must have at least one component")
        jac = as_float_array(H(self._x.copy()) if callable(H) else H, "H", shape=(m, n))
        r = self._noise(R, "R", m, semidefinite=False)
        angles = index_tuple(angle_measurements, "angle_measurements", m)
        threshold = None if gate is None else positive_float(gate, "gate")
        hx = as_float_array(h(self._x.copy()), "h(x)", shape=(m,))

        y = meas - hx
        for i in angles:
            y[i] = wrap_scalar(float(y[i]))
        ph = self._p @ jac.T
        s = self._checked(jac @ ph + r, "innovation covariance S")
        # S is small, symmetric and positive definite here: one explicit inverse serves both
        # the NIS and the gain K = P Hᵀ S⁻¹.
        s_inv = np.linalg.inv(s)
        nis = float(y @ s_inv @ y)
        # Also catches an infinite residual (NaN or inf NIS). Overflows are rare enough
        # that NumPy's RuntimeWarning is left alone (np.errstate would cost every step).
        if not nis < math.inf:
            finite = bool(np.all(np.isfinite(y)))
            reason = _OVERFLOW + ("the NIS" if finite else "the residual z - h(x)")
            return new_result(False, math.inf, y if finite else np.empty(0), reason)
        if threshold is not None and nis > threshold:
            return new_result(False, nis, y, f"rejected by the gate: NIS {nis:.6g} > {threshold}")
        gain = ph @ s_inv
        x_new = self._x + gain @ y
        if not np.isfinite(x_new).all():
            return new_result(False, nis, y, _OVERFLOW + "the updated state")
        x_new = self._wrap_states(x_new)
        ikh = np.eye(n) - gain @ jac
        p_new = self._checked(ikh @ self._p @ ikh.T + gain @ r @ gain.T, "updated covariance")
        self._x = x_new
        self._p = p_new
        return new_result(True, nis, y, None)

    def _noise(self, value: ArrayLike, name: str, n: int, *, semidefinite: bool) -> FloatArray:
        """Validated noise covariance, reusing the last one when the values are identical."""
        last = self._validated.get(name)
        if last is not None and last.shape == (n, n):
            # Only a float64 array is compared directly; anything else (lists, other
            # dtypes, complex or string data) is converted by the checking helper first.
            arr = (
                value
                if type(value) is np.ndarray and value.dtype == np.float64
                else as_float_array(value, name, shape=(n, n))
            )
            # Equal values (NaN never compares equal) passed the same checks before.
            if arr.shape == last.shape and np.array_equal(arr, last):
                return last
        checked = covariance(value, name, n, semidefinite=semidefinite)
        checked.flags.writeable = False
        self._validated[name] = checked
        return checked

    def _wrap_states(self, x: FloatArray) -> FloatArray:
        for i in self._angles:
            x[i] = wrap_scalar(float(x[i]))
        return x

    @staticmethod
    def _checked(p: FloatArray, what: str) -> FloatArray:
        # 0.5*a + 0.5*b is 0.5*(a + b) bit for bit, and cannot overflow.
        p = 0.5 * p + 0.5 * p.T
        if not np.all(np.isfinite(p)):
            raise FilterError(f"{what} is not finite")
        try:
            np.linalg.cholesky(p)
        except np.linalg.LinAlgError:
            raise FilterError(f"{what} is not positive definite") from None
        return p

    def __repr__(self) -> str:
        return f"ExtendedKalmanFilter(dim={self._n}, angle_states={self._angles})"
