"""A general Extended Kalman Filter on numpy arrays."""

from __future__ import annotations

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
    After every step ``P`` is symmetrised and checked to be positive definite; a
    step that would break this raises :class:`~navkit.errors.FilterError` and
    leaves the filter unchanged.

    An ordinary class with ``__slots__`` rather than a frozen dataclass: every
    step changes its estimate in place.

    Parameters
    ----------
    x0 : array_like, shape (n,)
        Initial state.
    P0 : array_like, shape (n, n)
        Initial covariance, symmetric positive definite.
    angle_states : sequence of int, optional
        Indices of state components that are angles (rad); they are wrapped to
        (-π, π] after every step (keyword-only).

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
            semi-definite.

        Raises
        ------
        TypeError, ValueError
            On non-callable ``f``, wrong shapes, non-finite values or an invalid
            ``Q``; the state is unchanged.
        FilterError
            If the predicted covariance is not positive definite.
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
            Measurement noise covariance, symmetric positive definite.
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
            Whether the measurement was applied, its NIS and residual.

        Raises
        ------
        TypeError, ValueError
            On wrong shapes, non-finite values or an invalid ``R`` or ``gate``;
            the state is unchanged.
        FilterError
            If the innovation or updated covariance is not positive definite.
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
        s = jac @ ph + r
        s = 0.5 * (s + s.T)
        try:
            np.linalg.cholesky(s)
        except np.linalg.LinAlgError:
            raise FilterError("innovation covariance S is not positive definite") from None
        # S is small, symmetric and positive definite here: one explicit inverse serves both
        # the NIS and the gain K = P Hᵀ S⁻¹.
        s_inv = np.linalg.inv(s)
        nis = float(y @ s_inv @ y)
        if threshold is not None and nis > threshold:
            return new_result(False, nis, y, f"rejected by the gate: NIS {nis:.6g} > {threshold}")
        gain = ph @ s_inv
        x_new = self._wrap_states(self._x + gain @ y)
        ikh = np.eye(n) - gain @ jac
        p_new = self._checked(ikh @ self._p @ ikh.T + gain @ r @ gain.T, "updated covariance")
        self._x = x_new
        self._p = p_new
        return new_result(True, nis, y, None)

    def _noise(self, value: ArrayLike, name: str, n: int, *, semidefinite: bool) -> FloatArray:
        """Validated noise covariance, reusing the last one when the values are identical."""
        last = self._validated.get(name)
        if last is not None and last.shape == (n, n):
            try:
                arr = np.asarray(value, dtype=np.float64)
            except (TypeError, ValueError):
                arr = last[:0]  # never equal: let covariance() report the problem
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
        p = 0.5 * (p + p.T)
        if not np.all(np.isfinite(p)):
            raise FilterError(f"{what} is not finite")
        try:
            np.linalg.cholesky(p)
        except np.linalg.LinAlgError:
            raise FilterError(f"{what} is not positive definite") from None
        return p

    def __repr__(self) -> str:
        return f"ExtendedKalmanFilter(dim={self._n}, angle_states={self._angles})"
