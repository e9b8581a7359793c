"""A general Extended Kalman Filter on numpy arrays.

Each step calls one compiled kernel (:mod:`navkit.estimation._ekf_kernels`),
through its compiled entry (no numba dispatcher), with the arrays as passed or
as the model functions returned them. The kernel tests in C that they are
C-contiguous writeable float64 ndarrays and returns ``BAD_TYPE`` for anything
else (a list, a strided or read-only array, another dtype, an ndarray
subclass); it checks shapes and values and computes the step, committing it
only when it is valid. Whatever it cannot take is converted and checked in
full in Python, which also raises the documented errors. The common case thus
pays for no checks in Python at all: a step costs the model functions, one copy
of the state for them, two kernel calls and the result object.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Iterable
from types import FrameType
from typing import Any, NoReturn

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.frozen import extra_state, restore_extra, restore_slots
from navkit._shared.types import FloatArray, IntArray
from navkit._shared.validation import SMALLEST_POSITIVE, as_float_array, positive_float
from navkit.errors import FilterError
from navkit.estimation._covariance import covariance, index_tuple, negative_eigenvalue_note
from navkit.estimation._ekf_kernels import (
    BAD_F,
    BAD_FX,
    BAD_H,
    BAD_HX,
    BAD_SHAPE,
    BAD_TYPE,
    BAD_Z,
    CANCELLED,
    GATE_PASSED,
    GATED,
    GATED_AT_LEAST,
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
    PredictKernel,
    UpdateKernel,
    adopt_positive_q,
    finish_cancelled,
    finish_singular_s,
    kept_q,
    new_rbuf,
    new_state,
    predict_kernel,
    rbuf_gate,
    rbuf_nis,
    retry_gated,
    set_gate,
    set_nis,
    set_options,
    set_q,
    set_r,
    update_kernel,
)
from navkit.estimation._fusion import FusionStatus
from navkit.estimation._gaussian import GaussianEstimate
from navkit.estimation._result import UpdateResult, _Building, new_result, rejected_result
from navkit.geometry import wrap_angle

__all__ = ["ExtendedKalmanFilter"]

_OVERFLOW = "overflow: not applied, float64 cannot hold "
# UpdateResult.status of the measurements not applied (PlanarFusion's codes).
_GATED = FusionStatus.GATED
_OVERFLOWED = FusionStatus.OVERFLOW
_NDARRAY = np.ndarray
_empty = np.empty
_NO_INDICES: IntArray = np.zeros(0, dtype=np.int64)
_NO_ANGLES: tuple[int, ...] = ()  # the default angle_measurements (the one empty tuple)
_INF = math.inf
_NOT_TAKEN = -float(BAD_TYPE)  # the "status" of a kernel call the fast path did not make
_SMALLEST_POSITIVE = SMALLEST_POSITIVE
_CACHE_SIZE = 16  # validated R matrices and angle index tuples kept per filter
_EXACT_INT = 2**53  # the largest of the ints that float64 holds exactly, all below it too
_UNSET = object()  # an option key no argument is: its options are checked again

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
    positive definite under rounding (the short form :math:`(I - KH)P` does not),
    or, for a measurement far more precise than the estimate, where the Joseph
    form cancels, the information form :math:`(P^{-1} + H^T R^{-1} H)^{-1}`
    (see :meth:`update`).
    After every step ``P`` is exactly symmetric (its lower triangle is computed
    and mirrored) and checked to be finite and positive definite (an LDLᵀ
    factorisation, Cholesky's without square roots); a step that would break this raises
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

    The compiled kernels are specialised for the state dimension n (the
    predict, compiled or loaded from numba's on-disk cache when the first
    filter of that n is built) and for each measurement dimension m (the
    update, at the first measurement of that size): fixed sizes let the
    compiler unroll the small matrix products.

    A filter is not thread-safe: one thread at a time may call its methods
    (in a ROS 2 node with a ``MultiThreadedExecutor``, put the callbacks that
    use it in one ``MutuallyExclusiveCallbackGroup``); different filters may
    run in different threads at once. The model functions (``f``, ``F``,
    ``h``, ``H``) may read the filter but must not call its :meth:`predict`
    or :meth:`update`: the outer step would then be computed from the state
    before the nested one and applied after it, mixing the two; such a
    nested call raises ``RuntimeError`` and leaves the filter as it was.

    Parameters
    ----------
    x0 : array_like, shape (n,), n >= 1
        Initial state (finite).
    P0 : array_like, shape (n, n)
        Initial covariance, symmetric positive definite, entries of magnitude at
        most 1e100 (as every covariance the filter takes: ``Q``, ``R``); the
        pivots of its LDLᵀ factorisation (variances, when diagonal) at least
        about 2.2e-308, the smallest normal float (as ``R``'s). Positive
        definite as float64 can tell: the factorisation is computed in
        float64, so a matrix within rounding of singular passes, as it
        passes ``numpy.linalg.cholesky`` (or the filter's own checks of the
        covariance it commits, which order the operations otherwise: its
        :attr:`P` is a valid ``P0`` while its entries stay within 1e100, which
        predictions of an unstable model or of a ``Q`` near 1e100 can pass),
        though its exact least eigenvalue
        may lie below zero (at most about ``n**2 * 2.2e-16`` times its largest
        variance; ``A @ A.T`` computed for a tall ``A`` can be such a
        matrix). The gate's exact NIS bounds do not assume more than that.
        Symmetric up to rounding, as every covariance the filter takes: an
        asymmetry of at most 1e-9 of the largest entry is averaged out, or of
        64 float32 epsilons (7.6e-6) when every entry is a float32 value (a
        matrix computed in float32, whose own rounding is that coarse; that
        tolerance also bounds a negative eigenvalue of a semi-definite ``Q``)
        and some entry looks rounded: a matrix whose every entry is an integer
        of at most 2²⁴ or a decimal of at most 6 significant digits (typed,
        ``[[1e6, 2.5], [3.5, 1e6]]``, in float64 or float32) keeps the 1e-9.
    angle_states : sequence of int, optional
        Indices of state components that are angles (rad); they are wrapped to
        (-π, π] after every step (keyword-only).

    Raises
    ------
    TypeError, ValueError
        An argument outside the ranges above, naming it.

    Notes
    -----
    Subclasses may add attributes (their own ``__slots__`` or an instance
    ``__dict__``) and methods (a motion model's ``step(u, dt)`` calling
    :meth:`predict` with its own ``f``, ``F`` and ``Q``, say), and override
    the public methods, calling the base's through ``super()``: the base's
    methods call none of the public ones, so an override changes only its
    own callers. Copies (:func:`copy.copy`, :func:`copy.deepcopy`) and
    pickles rebuild a subclass as itself, with what it adds (its
    ``__init__`` is not called), and ``repr`` names it. Names with a leading
    underscore (the compiled kernels, their buffers, the fallbacks of
    :meth:`update`) are private: a subclass must neither use nor override
    them; they may change in any release.

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

    __slots__ = (
        "_angles", "_busy", "_entry", "_gate", "_kp", "_ku", "_m", "_meas_angles", "_n",
        "_options", "_rbuf", "_rbufs", "_state",
    )  # fmt: skip

    def __init__(self, x0: ArrayLike, P0: ArrayLike, *, angle_states: Iterable[int] = ()) -> None:
        x = np.array(as_float_array(x0, "x0", ndim=1), dtype=np.float64, copy=True)
        n = x.shape[0]
        if n == 0:
            raise ValueError("x0 must have at least one component")
        p = covariance(P0, "P0", n)
        self._angles = index_tuple(angle_states, "angle_states", n)
        for i in self._angles:  # in Python (as the kernels wrap, bit for bit): compiles nothing
            x[i] = wrap_angle(float(x[i]))
        # Everything a predict needs in one array (see _ekf_kernels), including the
        # last validated Q: filters usually pass the same matrices every step, and
        # re-checking symmetry and definiteness would cost more than the step. The
        # kernels compare the Q (or R) passed with the one validated and ask for a
        # new check when they differ, unless the new one is plainly valid
        # (diagonally dominant: a Q_c dt whose dt varies every step, say; a Q that
        # an LDLᵀ factorisation finds positive definite is kept by adopt_positive_q).
        self._adopt(new_state(x, p, self._angles))

    def _adopt(self, state: FloatArray) -> None:
        """Take ``state`` (see _ekf_kernels) as the filter's estimate."""
        n: int = state.shape[1]
        self._n: int = n
        self._state: FloatArray = state
        self._x = state[STATE_X]
        self._p = state[STATE_P : STATE_P + n]
        # The kernels, compiled for n (and m) as constants: predict's now, update's
        # per measurement size with its buffer (the last validated R, the options
        # angle_measurements and gate, scratch space), the last size's tried first
        # (nothing to begin with). An entry of _rbufs is [rbuf, kernel, angle key,
        # gate key]: the keys are the (immutable) angle_measurements and gate whose
        # values the buffer holds, so that a call passing the same objects (the
        # defaults, usually) needs no look at them.
        self._kp: PredictKernel = predict_kernel(n)
        self._rbufs: dict[int, list[Any]] = {}
        self._entry: list[Any] = [_NO_RBUF, _no_update_kernel, _NO_ANGLES, None]
        self._rbuf: FloatArray = _NO_RBUF
        self._ku: UpdateKernel = _no_update_kernel
        self._options: object = _NO_ANGLES
        self._gate: object = None
        self._m: int = 0
        # Validated angle_measurements by the identity of the (immutable) tuple passed,
        # which the entry keeps alive: {id: (tuple, indices, 1 + largest index)}.
        self._meas_angles: dict[int, tuple[tuple[int, ...], IntArray, int]] = {}
        # Whether the model functions of a step are running (see _nested).
        self._busy: bool = False

    def __reduce__(self) -> tuple[Any, ...]:
        # The estimate lives in one array updated in place, with x and P views into it:
        # copies (copy.copy too) and pickles get their own array and views. A subclass
        # is rebuilt as itself, with what it adds restored after (see extra_state).
        cls = type(self)
        if cls is ExtendedKalmanFilter:
            return _restore, (self._state.copy(), self._angles)
        extra = extra_state(self, below=ExtendedKalmanFilter)
        return _restore, (self._state.copy(), self._angles, cls), extra

    def __setstate__(self, state: Any) -> None:
        """Restore what a subclass adds (see ``__reduce__``), or a pickle made before 98b4639.

        Filters pickled before their estimate lived in one array (98b4639, 30
        November 2026) were pickled attribute by attribute (``_x``, ``_p``,
        ``_angles``, ``_n`` and a ``_validated`` dict of the last checked Q and
        R; a ``__dict__`` before 0123de4): they raised AttributeError as they
        loaded. Their estimate now goes into a filter as the constructor builds
        one (the checked matrices are checked again at the next step).
        """
        instance, slots = state if isinstance(state, tuple) else (state, None)
        if hasattr(self, "_state"):  # rebuilt by _restore: a subclass's own attributes
            restore_extra(self, (instance, slots))
            return
        held = {**(instance or {}), **(slots or {})}
        if "_x" not in held or "_p" not in held:
            raise ValueError(
                "this pickle of ExtendedKalmanFilter holds no estimate (_x and _p): it "
                "was not made by navkit; build the filter again"
            )
        ExtendedKalmanFilter.__init__(
            self, held.pop("_x"), held.pop("_p"), angle_states=held.pop("_angles", ())
        )
        for name in ("_n", "_validated"):  # recomputed by the constructor and the steps
            held.pop(name, None)
        restore_slots(self, held)  # what an old subclass added, refused if not settable

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
            ``f(x) -> x'`` with ``x`` a copy of the state, shape (n,), in the
            state's units (angles in rad); ``x'`` has shape (n,), in the same
            units. ``f`` may modify ``x`` (and return it).
        F : callable or array_like, shape (n, n)
            Jacobian of ``f`` at the current (prior) state, or a function
            ``F(x)`` returning it, called first, on the same copy of the state
            as ``f`` (so it must not modify it).
        Q : array_like, shape (n, n)
            Process noise covariance for this step (products of the state's
            units, e.g. m² and rad²), symmetric positive semi-definite, entries
            of magnitude at most 1e100. A Q that changes every step (``Q_c * dt``
            with a varying ``dt``) is checked in the compiled step when it is
            diagonally dominant (a diagonal Q is) or, up to 64 states, exactly
            symmetric and positive definite by an LDLᵀ factorisation (a
            constant-velocity model's ``[[dt³/3, dt²/2], [dt²/2, dt]]``; a
            second kernel, compiled at the first such Q, about 2 µs a step); any
            other new Q (a singular one, say) is checked in Python, 0.06 ms (2
            states) to 0.2 ms (6).

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
            the state is unchanged. A ``Q`` taken as positive semi-definite to
            its rounding (see ``P0``) with a negative eigenvalue is named with
            that eigenvalue.
        RuntimeError
            If called from a model function of a step of this filter; that step
            then fails too (the error passes through it), leaving the state
            unchanged.

        Examples
        --------
        >>> import numpy as np
        >>> ekf = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))  # position m, speed m/s
        >>> F = np.array([[1.0, 0.1], [0.0, 1.0]])  # 0.1 s at constant speed
        >>> ekf.predict(lambda x: F @ x, F, 0.01 * np.eye(2))
        >>> ekf.x, ekf.P.round(4)  # x = F x, P = F P Fᵀ + Q
        (array([0.1, 1. ]), array([[1.02, 0.1 ],
                                   [0.1 , 1.01]]))
        >>> heading = ExtendedKalmanFilter([3.0], [[0.1]], angle_states=[0])
        >>> heading.predict(lambda x: x + 0.5, [[1.0]], [[0.01]])
        >>> heading.x.round(4)  # 3.5 rad wrapped to (-π, π]
        array([-2.7832])
        """
        if self._busy:
            _nested(self, "predict")
        # One copy of the state for F and f, called in this order: a Jacobian does
        # not modify its argument, and f may, once F has seen it.
        x = self._x.copy()
        self._busy = True
        try:
            jac = F(x) if callable(F) else F
            try:
                x_new = f(x)
            except TypeError:
                if not callable(f):
                    raise TypeError(f"f must be callable, got {type(f).__name__}") from None
                raise
        finally:
            self._busy = False
        # The kernel's compiled entry takes the objects as they are and checks in C that
        # each is an ndarray (exactly: a masked array, whose mask numba would drop, goes
        # the checked way, Q too) of native float64, C-contiguous and writeable (as
        # numba's dispatcher typed them), then their shapes and values: anything else
        # (BAD_TYPE, as any status but OK) is converted and checked in full by
        # _predict_checked.
        status = self._kp(self._state, x_new, jac, Q)
        if status:
            self._predict_checked(status, x_new, jac, Q)

    def _predict_checked(self, status: int, x_new: Any, jac: Any, q: Any) -> None:
        """The rest of :meth:`predict` after a kernel ``status`` other than OK."""
        n = self._n
        if status in (BAD_TYPE, BAD_SHAPE):
            square = (n, n)
            jac = _c_array(jac, "F", square)
            q = _c_array(q, "Q", square)
            x_new = _c_array(x_new, "f(x)", (n,))
            status = self._kp(self._state, x_new, jac, q)
        if status == NOISE_CHANGED:
            # A positive definite Q kept by a compiled check (one of the types the
            # predict kernel took: C-contiguous float64), else the check in Python.
            if not adopt_positive_q(self._state, q):
                set_q(self._state, q, covariance(q, "Q", n, semidefinite=True))
            status = self._kp(self._state, x_new, jac, q)
        if status == NOT_POSITIVE_DEFINITE:
            # A Q accepted as semi-definite to its rounding may hold a negative
            # eigenvalue, which the error then names (review 53, FOUND6).
            note = negative_eigenvalue_note(kept_q(self._state), "Q")
            raise FilterError(f"predicted covariance is not positive definite{note}")
        if status != OK:
            _raise(status, "predicted covariance")

    def update(
        self,
        z: ArrayLike,
        h: StateFunction,
        H: Jacobian,
        R: ArrayLike,
        *,
        angle_measurements: Iterable[int] = _NO_ANGLES,
        gate: float | None = None,
    ) -> UpdateResult:
        """Correct the state with a measurement.

        Parameters
        ----------
        z : array_like, shape (m,)
            Measurement, in the units ``h`` returns (angles in rad).
        h : callable
            Measurement model ``h(x) -> (m,)``, called on a copy of the state,
            shape (n,) (which it may modify).
        H : callable or array_like, shape (m, n)
            Jacobian of ``h`` at the current state, or a function returning it,
            called first, on the same copy as ``h`` (which it must not modify).
        R : array_like, shape (m, m)
            Measurement noise covariance (products of the units of ``z``),
            symmetric positive definite, entries of magnitude at most 1e100. As
            ``Q`` in :meth:`predict`, an R that changes every update (a sensor's
            covariance per message) is checked in the compiled step when each
            diagonal entry is at least 1e-300 and twice the sum of the magnitudes of the
            rest of its row; any other new R in Python, about 0.07 ms.
        angle_measurements : sequence of int, optional
            Indices of the components of ``z`` that are angles; their residuals
            are wrapped to (-π, π] (keyword-only). An angle residual never
            overflows: where ``z - h(x)`` would (angles near ±1.8e308), it is
            the difference of the wrapped angles, wrapped (as
            :func:`navkit.geometry.angle_diff`).
        gate : float, optional
            Chi-square threshold on the normalised innovation squared (NIS)
            yᵀ S⁻¹ y; a measurement with NIS above it is rejected (e.g.
            ``scipy.stats.chi2.ppf(0.997, m)``); keyword-only.

        Returns
        -------
        UpdateResult
            Whether the measurement was applied, its NIS (dimensionless) and
            residual ``z - h(x)`` (shape (m,), units of ``z``). Not
            applied (``accepted=False``, state unchanged) when gated (the reason
            giving the NIS in 6 significant digits, more where fewer would not
            read above the gate), or when the
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
        RuntimeError
            If called from a model function of a step of this filter, as in
            :meth:`predict`.

        Notes
        -----
        The Joseph form evaluates :math:`(I - KH) P` as :math:`P - K H P`,
        whose error relative to the posterior grows as the measurement gets
        more precise than the estimate (about ε Pᵢᵢ / P⁺ᵢᵢ, ε = 1.1e-16), and
        more where H P Hᵀ cancels (correlated states measured in a combination
        whose terms far exceed it) or S is ill-conditioned, which no variance
        shows. When some variance shrinks more than 4096-fold, or a first-order
        estimate of the Joseph P's error (ε (|P| + |K| |H| |P|) |I - KH|ᵀ
        + ε |K| |R| |K|ᵀ, the last the rounding of K R, large where the entries
        of an ill-conditioned R cancel; computed only where a cheap bound on it
        exceeds 2⁻⁴⁰ of the posterior's
        scale) does, or the Joseph P fails its check, the update also computes the
        information form :math:`(P^{-1} + H^T R^{-1} H)^{-1}` (the same matrix
        in exact arithmetic, with nothing subtracted) and its state
        :math:`x + P^+ H^T R^{-1} y`, each inverse and solve refined once
        against its residual computed exactly (every product's terms summed
        with one rounding). The same residual, :math:`J X - I` with
        :math:`J = P^{-1} + H^T R^{-1} H`, measures how far each candidate
        :math:`X` is from the posterior: the information form's own
        (estimated as what its refinement leaves plus J's rounding) and the
        Joseph result's. Where the information form's estimate is at most
        2⁻¹² / ε it replaces a Joseph result that failed its checks or whose
        measured error is more than twice its own. The state committed is
        one with a bound on its error within 2⁻²⁰ of the posterior's
        deviation or 32 ε (|x| + |x⁺ - x|): the kernel's (bounded by its
        distance from the information form's plus that one's bound, the
        roundings of g = Hᵀ R⁻¹ y and of J carried through P⁺) or, where the
        two disagree, the information form's, else the exact posterior mean
        :math:`x + P H^T S^{-1} y` in rational arithmetic, rounded once. The
        covariance committed is likewise one whose measured error is at most
        2⁻⁴⁰ of sqrt(P⁺ᵢᵢ P⁺ⱼⱼ) (an ordinary update's accuracy), else the exact
        posterior :math:`P - (HP)^T S^{-1} HP` in rational arithmetic, rounded once,
        where float64 holds it as a covariance (positive definite, as every
        committed P); where it does not (a scaled condition number beyond
        about 1e16), a computed one within 2⁻²⁰ of it, else ``FilterError``.
        So too where nothing measures the Joseph P, e.g. with
        P⁻¹ + Hᵀ R⁻¹ H singular to working precision. For more than 12
        components the exact arithmetic is, where cheaper than S's
        elimination, the information form's, exactly (R⁻¹ block by block: a
        diagonal R, as of a scan's beams, costs one n x n elimination however
        many components; 0.07 s for 360 beams of a 6-state filter, 0.17 s
        with 15 states); an update that needs it and whose exact arithmetic
        would eliminate more than 24 rows (a dense R of more than 24
        components, or more than 24 states) raises ``FilterError``, changing
        nothing (one whose computed S is singular is first gated on a lower
        bound of its exact NIS, maxₖ yₖ² / Sₖₖ (yₖ² ≤ Sₖₖ yᵀ S⁻¹ y for a
        positive definite S), Sₖₖ raised to bound its rounding (by 2⁻³⁰ cₖ, cₖ =
        (Σⱼ |Hₖⱼ| √Pⱼⱼ)² + Rₖₖ), or cₖ where less; before review 42 the mean
        Σₖ yₖ² / (m cₖ), up to m cₖ / Sₖₖ times lower: one reading 100
        deviations off among 26 refused at a gate of 1000: rejected,
        ``nis`` that bound and the reason saying "at least", where it exceeds
        the gate, and an overflow where it is beyond float64, gate or not;
        before review 41 readings 1e150 deviations apart raised;
        an R with a block singular in exact arithmetic, positive definite only
        as rounded, is gated and refused so too, as are the unvouched updates
        below (before review 42 refused at once, gate or not: a reading 1000
        deviations off at a gate of 100); before review 41 its exact update
        eliminated S whatever its size) (before review 40 measurements of more than 12 components
        committed the Joseph P and a state within a quarter deviation
        unmeasured: of 97 random precise updates of 13 to 16 components, 53
        more than 2⁻⁴⁰ or 2⁻²⁰ deviations off, P up to 53 %). Other updates are
        computed as before, bit for bit. What this gives: when
        each precisely measured direction is a state (each row of H a
        multiple of a distinct state, as in measuring positions or speeds),
        and P and R are well conditioned once their diagonals are scaled to
        one, the entries of the new P are within 1e-12 sqrt(P⁺ᵢᵢ P⁺ⱼⱼ) of
        the exact posterior P⁺ (P of condition number up to 1e3 at scales
        1e-40 to 1e40, variances of R from 1e-100 to 1e40: of 3000 random
        draws none came out above 1e-12, the worst at 2.8e-13; the choice by
        error estimates before this measured one had 10 above, the worst
        1.5e-11, and one found by hypothesis at 1.9e-10, now 1.9e-15). In
        18000 random updates of every kind (dense H, P of scaled condition
        up to 1e14) none came out more than 10 times worse than the Joseph
        form alone (this kernel's, without the fallbacks), in P, or in x
        beyond an ulp (as in 2065 updates with κ(R) 1e8 to 1e18, where that
        form was itself the weak spot before review 33: 129 had committed a
        P more than 2⁻⁴⁰ off, up to 1.6e-6, its error estimate lacking the
        rounding of K R, and 47 a state more than 2⁻²⁰ deviations off, up to
        1.5e-3 (the kernel's, committed with that P or kept by the fallback
        with a quarter-deviation bound); now 3 P, those where
        float64 holds no covariance at the exact posterior, up to 1.3e-8,
        and no state, the worst 5.7e-7), and 4356 raise
        ``FilterError`` (4648 before review 27, when the kernel refused a Joseph P
        that failed its check with no variance shrinking 4096-fold, though 292
        of these have an exact posterior that is a covariance in float64, and
        committed 8 of its Joseph Ps more than 2⁻⁴⁰ off, up to 2.8e-11; 4847
        before the exact covariance, 5013 before the
        exact state, 7348 with the Joseph form alone; 283 that the Joseph
        form alone accepts, each with a P from 1.1e-6 to 3.4e90 of the
        posterior's scale off, where float64 holds no covariance at the
        exact one; an earlier draw of the kind: 4937, 5135 with the
        estimate-based choice, 7380); of the
        3253 of that draw that reached the information form, the exact
        posterior rounded to float64 is not positive definite in 2307 and
        has a scaled condition number above 1e12 in 757. A posterior that
        float64 cannot hold still raises ``FilterError``: e.g. a sum of states x₀ + x₁
        measured 1e200 times more precisely than either is known, whose
        exact covariance, rounded entry by entry, is not positive definite.
        The NIS (and the kernel's state) come from S = H P Hᵀ + R, within
        about ε κ(S) of the exact ones; a state measured twice (two rows of H
        multiples of one state), each time far more precisely than it is
        known, makes S nearly singular: κ(S) about P/R; so does a linear
        combination of states measured so (rows of H multiples of one row),
        where no variance need shrink; so does, even for one component, a
        combination of strongly correlated states whose terms in H P Hᵀ far
        exceed it (κ(S) here counts that cancellation: S's rounding error is
        that of its terms). In an update of at most 24 components
        whose S is that ill-conditioned (ε κ(S) above 2⁻³⁰, read from the
        pivots of its LDLᵀ factorisation, or from S's scaled inverse where the
        update reaches the information form anyway; 8 before review 40, the
        NIS up to 5e-9 relative off for 10 components, 9.1 % for 16), or whose computed S is
        not positive definite at all (of any size, before review 40 at most 8;
        R/P below about 1e-16 rounds S = [[p + r, p], [p, p + r]] to a
        singular matrix, though the exact S of a positive definite P and R
        never is), the NIS is computed from S in
        exact rational arithmetic, rounded once (0.1 to 10 ms), and the update
        gated on it before anything else is decided: the reported NIS is that
        exact one, and an update whose exact NIS passes the gate is the
        update made without the gate, bit for bit (where the kernel had
        gated on its own NIS, the kernel runs again without the gate). P is
        then chosen as above, and x is the exact posterior mean from the same
        elimination, rounded once (about 0.02 ms more; before review 27 a
        state whose bound vouched for it, up to 32 ε of its size off: 1.25 ulps
        in one update where the kernel's was exact). Such an update raises ``FilterError``
        only where the gate passes it and no covariance passes the checks
        above, so readings 1e150 deviations apart are rejected by a gate,
        not refused (and without a gate applied, with the exact state).
        Updates of more than 24 components with a gate and such an S (a dense
        R: no exact route) are gated on the exact NIS alone (S's elimination,
        nothing else exact) where its work, bounded from the sizes and
        exponents before any, is within the cap of the exact posterior below
        (about 15 s of CPU; 0.05 s for 28 components of 4 states), else on the
        lower bound above, and refused with ``FilterError`` where that does
        not reject them (before review 43 the kernel's NIS stood: 28.28 for
        an exact 25.81, rejected at a gate between them; and measurements
        whose exact NIS the gate rejects were refused: 16 of 240 such draws
        at gates 0.9 to 1.1 times their exact NIS); without a gate they keep
        the kernel's NIS. Those with an exact route
        (a diagonal or block-diagonal R whose blocks, and the states, number
        at most 24) are tested as above since review 41 (before, only those
        that reach the information form, whose NIS is the exact one where S
        is that ill-conditioned or the information form's state replaced the
        kernel's for disagreeing with it: 25 readings of a combination with a
        diagonal R reported a NIS 4.1e-8 relative off, and a gate between it
        and the exact one decided wrongly); the others, where S is that
        ill-conditioned, are committed only where the information form
        vouches for their state and covariance, else refused with
        ``FilterError`` (before review 41 the kernel's x and Joseph P stood
        unmeasured: of 80 random such updates of 25 to 28 components 2 had
        been applied, both accurate, now refused) (before review 39 the
        Joseph P and the kernel's x stood unmeasured for more than 8
        components, up to 10.7 % and 3.2 deviations off). (Before review 29 one
        component was not tested, its κ(S) taken as 1: of 375 random updates
        whose H P Hᵀ cancels, 345 reported a NIS more than 1e-9 off, up to 8
        times the exact one, and a gate 0.1 % from the exact NIS decided
        wrongly in 32; now none is more than 3e-11 off, none decided wrongly.)
        Of 1200 random updates of a combination of 1 to 4 states
        measured 2 to 4 times with R/P from
        3e-17 to 1e-9 (each checked against exact arithmetic), the reported
        NIS was more than 1e-8 off the exact one in 518 before and in none
        now, and of the half gated near their exact NIS the gate decided
        wrongly in 32 before and in none now; 56 raised ``FilterError`` (58
        before; of 1500 such updates with R/P from 3e-17 to 1e-8, 12 now,
        29 before the exact covariance). x and P stayed as accurate (the
        largest error of x 6.7e-3 deviations). Such an update costs about
        0.35 ms (2 states) to 0.45 ms (6 states). Of 3000 random updates with R/P from 1e-40 to
        1e-9 (rows of H single states, multiples of each other or sparse
        random; 2 to 4 of each), 140 of the 1606 applied had a state more
        than a posterior deviation off beyond 32 ε of its size (up to 8e11
        deviations; one, at ε κ(S) 0.35 with status OK, 315 deviations or
        45,000 ulps, where the kernel's x was kept with no bound), before
        the state was required a bound or made exact; then none of 1778,
        752 raised ``FilterError`` (924 before: the 172 whose state no form
        determined got the exact one), none applied before was refused and
        the gate decided alike; of 1500 updates of combinations
        measured twice, the 410 whose state no bound put within a quarter
        deviation (up to 3.9e-5 deviations off) now get the exact one. The
        kernel's NIS had also stood where S is that ill-conditioned and the
        two states disagree (4.61 reported for an exact 2128). The exact
        state adds about 0.05 ms (median; 0.2 ms at the 90th percentile, up
        to 12 ms where P and R lie 1e140 apart), only where no bound vouches
        for a state: in none of 300 precise position or speed measurements
        of a 6-state filter (R/P from 1e-14 to 1e-2), in half of the
        precise measurements of distinct states with R from 1e-100 to 1e40
        (the posterior's deviation then below an ulp of the state). Before
        the covariance was required a measured error or made exact, of the
        same 3000 updates 94 applied had a P more than 1e-6 of the
        posterior's scale off (up to 3.7e20; 418 more than 1e-12); now none
        of 1954 (65 more than 1e-12, each within 2⁻²⁰ of an exact posterior
        that float64 holds no covariance at), 576 raise ``FilterError``
        (the 212 that no covariance passed now get the exact one; 36 applied
        before with a P from 1.1e-6 to 8.4e10 off are refused, the exact one
        not positive definite in float64), and the gate decides alike. The
        exact covariance adds about 0.04 ms (median; 0.11 ms at the 90th
        percentile, up to 1.1 ms with 6 states), where no measured error
        vouches for one: in 7 of the 300 precise measurements of a 6-state
        filter (0.06 to 0.1 ms on 0.4), in none of the precise measurements
        of distinct states.
        (Before, with κ(S) 3e16 a NIS of 21.04 was reported for
        an exact 9.377, and a measurement passing a gate of 11.3 rejected;
        with x₀ + x₁ measured twice, R = 1e-14, a NIS of 1.767 for an exact
        1.786, accepted at a gate of 1.78; R/P below 1e-16 raised
        ``FilterError``.)
        An update that reaches the information form costs about 0.5 ms
        (0.47 ms for 2 states, 0.65 to 0.75 ms for 6, where an ordinary
        6-state update takes 22 µs: about twice the cost of the choice by
        error estimates before it; it runs in NumPy, so that no user pays
        its compilation); a filter whose every update shrinks a variance more
        than 4096-fold (process noise far above the measurement noise) pays
        it each step. The exact arithmetic, where it is needed, costs more
        with more states and components and the further apart the exponents
        of P and R lie (measured on a loaded 2-core machine, 12 components:
        34 and 41 ms with 6 and 15 states and R 1e-12 of P, 0.33 s with 64
        states; with P and R 1e280 apart 0.5 s with 15 states, 2.3 s with 64,
        7.5 s with 128; 8 components: 0.2 s with 64 states, and 1e280 apart
        0.7 s with 64 and 4.5 s with 128; 24 components of a dense R: 0.25 s
        with 15 states, 1.0 s with 64, 10 s with 64 and P and R 1e280 apart; a
        diagonal R of 360 components: 0.07 s with 6 states, 0.9 s with 24): a
        loop whose period matters should not meet such measurements with many
        states. The 24-row limit bounds the elimination, not the work on the
        states: the exact posterior from S replays S's elimination on the n
        columns of H P (about m² n divisions of integers the size of det S)
        and takes about n² m products, so an update needing it whose estimated
        work exceeds about 15 s of CPU raises ``FilterError``, changing nothing
        (before review 42 it was unbounded in n: 24 components of a dense R
        with P and R 1e280 apart, measured on a loaded 2-core machine, took
        46 s with 64 states, 96 s with 128 and 197 s with 256; now 64 states
        pass, 128 are refused after S's elimination, 1.4 s). And a precise measurement
        with a dense R of more than 24 components takes the information form in
        float64 first, whose refinement of R's inverse sums m³ exact terms in
        Python before the update is applied or refused (0.4 s for 100
        components, 1.9 s for 200, 10 s for 400; re-measured in review 42 on a
        loaded 2-core machine, the refinement alone: 3.9 s for 200, 21.5 s for
        400, 140 s for 800, cubic in m and not limited: a dense R of hundreds
        of components is best split; a diagonal or block-diagonal R's blocks
        cost their own sizes cubed).

        Examples
        --------
        >>> import numpy as np
        >>> ekf = ExtendedKalmanFilter([0.0, 1.0], np.eye(2))  # position m, speed m/s
        >>> H = np.array([[1.0, 0.0]])  # the position is measured
        >>> ekf.update([0.5], lambda x: x[:1], H, [[1.0]])
        UpdateResult(accepted=True, nis=0.125, residual=array([0.5]), reason=None,
                     status=<FusionStatus.ACCEPTED: 0>)
        >>> ekf.x, ekf.P  # halfway to z: prior and measurement variances are equal
        (array([0.25, 1.  ]), array([[0.5, 0. ],
                                     [0. , 1. ]]))
        >>> result = ekf.update([10.0], lambda x: x[:1], H, [[1.0]], gate=9.0)
        >>> result.accepted, result.reason, ekf.x  # an outlier: the state is unchanged
        (False, 'rejected by the gate: NIS 63.375 > 9.0', array([0.25, 1.  ]))
        """
        if self._busy:
            _nested(self, "update")
        x = self._x.copy()  # for H and h, in this order, as in predict
        self._busy = True
        try:
            jac = H(x) if callable(H) else H
            try:
                hx = h(x)
            except TypeError:
                if not callable(h):
                    raise TypeError(f"h must be callable, got {type(h).__name__}") from None
                raise
        finally:
            self._busy = False
        # As in predict: the kernel checks shapes and values, and anything it cannot
        # take (other types, another measurement size, options it does not hold that
        # are not cheaply known valid) goes to _update_checked.
        y = _empty(self._m)
        if (angle_measurements is self._options and gate is self._gate) or self._fast_options(
            angle_measurements, gate
        ):
            out = self._ku(self._state, z, hx, jac, R, self._rbuf, y)
            if out >= 0.0:  # OK: the kernel returned the NIS
                # new_result, inlined: building the result is much of an update's Python work.
                result = _Building()
                result.accepted = True
                result.nis = out
                result.residual = y
                result.reason = None
                result.__class__ = UpdateResult  # type: ignore[assignment]
                return result  # type: ignore[return-value]
        else:
            out = _NOT_TAKEN
        return self._update_checked(int(-out), y, (z, hx, jac, R), angle_measurements, gate)

    def _fast_options(self, angle_measurements: Iterable[int], gate: float | None) -> bool:
        """Give the current buffer these options if cheaply known valid; whether it did.

        A tuple of angle indices checked before (kept by identity) or a short
        list or tuple of distinct plain ints (a new one at every call, say), each
        fitting the current measurement size, and a float gate in range or a
        positive plain int (``gate=9``), qualify; anything else is checked in full
        by _update_checked.
        """
        if self._m == 0:  # no buffer yet
            return False
        if angle_measurements is _NO_ANGLES:
            indices, bound = _NO_INDICES, 0
        else:
            hit = self._meas_angles.get(id(angle_measurements))
            if hit is not None and hit[0] is angle_measurements:
                indices, bound = hit[1], hit[2]
            else:
                # Not kept by identity (a list, or a tuple made for this call): a
                # fresh check, cheap for plain ints; anything else goes the full way.
                plain = _plain_indices(angle_measurements, self._m)
                if plain is None:
                    return False
                indices, bound = plain, 0
        if gate is None:
            threshold = _INF
        elif (isinstance(gate, float) and _SMALLEST_POSITIVE <= gate < _INF) or (
            type(gate) is int and 0 < gate <= _EXACT_INT  # gate=9, as positive_float takes it
        ):
            threshold = float(gate)
        else:
            return False
        if bound > self._m:
            return False
        self._set_options(indices, threshold, angle_measurements, gate)
        return True

    def _set_options(
        self, indices: IntArray, threshold: float, angle_measurements: object, gate: object
    ) -> None:
        """Store validated options in the current buffer, keyed by the objects passed."""
        # The keys stand for no options while the buffer changes: Python delivers a
        # KeyboardInterrupt as a call returns, and one as set_options returned left
        # the new options under the old keys, which the next update passing those
        # objects took for the buffer's (no angle wrapping, no gate: a wrong step).
        entry = self._entry
        entry[2] = self._options = _UNSET
        entry[3] = self._gate = _UNSET
        set_options(self._rbuf, indices, threshold)
        # Only immutable objects can stand for their values.
        key = angle_measurements if type(angle_measurements) is tuple else _UNSET
        gate_key = gate if gate is None or type(gate) in (float, int) else _UNSET
        entry[2] = self._options = key
        entry[3] = self._gate = gate_key

    def _update_checked(
        self,
        status: int,
        y: FloatArray,
        arrays: tuple[Any, Any, Any, Any],
        angle_measurements: Iterable[int],
        gate: float | None,
    ) -> UpdateResult:
        """The rest of :meth:`update` after a kernel ``status`` other than OK.

        ``arrays`` are z, h(x), H and R as passed or returned.
        """
        z, hx, jac, r = arrays
        m = self._m
        if (status == BAD_SHAPE and type(z) is _NDARRAY
                and z.ndim == 1 and 0 < z.shape[0] != m):  # fmt: skip
            # Most likely a measurement of another size than the last one: switch
            # buffers and try again before converting anything.
            m = z.shape[0]
            self._use_rbuf(m)
            y = _empty(m)
            status = BAD_TYPE
            if (angle_measurements is self._options and gate is self._gate) or self._fast_options(
                angle_measurements, gate
            ):
                status = self._run(z, hx, jac, r, y)
        if status in (BAD_TYPE, BAD_SHAPE):
            # Convert and check everything, in the documented order.
            z = _c_copy(as_float_array(z, "z", ndim=1))
            m = z.shape[0]
            if m == 0:
                raise ValueError("z must have at least one component")
            jac = _c_array(jac, "H", (m, self._n))
            r = _c_array(r, "R", (m, m))
            indices = self._measurement_angles(angle_measurements, m)
            threshold = _INF if gate is None else positive_float(gate, "gate")
            hx = _c_array(hx, "h(x)", (m,))
            self._use_rbuf(m)
            self._set_options(indices, threshold, angle_measurements, gate)
            y = _empty(m)
            status = self._run(z, hx, jac, r, y)
        if status == NOISE_CHANGED:
            set_r(self._rbuf, r, covariance(r, "R", m))
            status = self._run(z, hx, jac, r, y)
        if status == CANCELLED:  # a measurement far more precise than the estimate
            status = finish_cancelled(self._state, self._rbuf, jac, y)
        elif status == S_NOT_POSITIVE_DEFINITE:
            # The exact S of a positive definite P and R is positive definite: the
            # computed one lost it to rounding (a state measured twice, each far more
            # precisely than it is known). The information form needs no S.
            status = finish_singular_s(self._state, self._rbuf, jac, y)
        elif status == GATED:
            # Unless S is ill-conditioned, where the kernel's NIS is not to be trusted.
            status = retry_gated(self._state, self._rbuf, jac, y)
            if status == GATE_PASSED:
                status = self._run_past_gate(z, hx, jac, r, y)
        nis = rbuf_nis(self._rbuf)
        if status == OK:
            return new_result(True, nis, y, None)
        if status == GATED:
            threshold = rbuf_gate(self._rbuf)
            return rejected_result(
                nis, y, f"rejected by the gate: NIS {_above(nis, threshold)} > {threshold}", _GATED
            )
        if status == GATED_AT_LEAST:  # nis is a lower bound of the exact one
            threshold = rbuf_gate(self._rbuf)
            reason = f"rejected by the gate: NIS at least {_above(nis, threshold)} > {threshold}"
            return rejected_result(nis, y, reason, _GATED)
        if status == RESIDUAL_OVERFLOW:
            return rejected_result(
                math.inf, np.empty(0), _OVERFLOW + "the residual z - h(x)", _OVERFLOWED
            )
        if status == NIS_OVERFLOW:
            return rejected_result(math.inf, y, _OVERFLOW + "the NIS", _OVERFLOWED)
        if status == STATE_OVERFLOW:
            return rejected_result(nis, y, _OVERFLOW + "the updated state", _OVERFLOWED)
        if status == S_NOT_FINITE:
            _raise(NOT_FINITE, "innovation covariance S")
        if status == S_NOT_POSITIVE_DEFINITE:
            _raise(NOT_POSITIVE_DEFINITE, "innovation covariance S")
        _raise(status, "updated covariance")

    def _run(self, z: Any, hx: Any, jac: Any, r: Any, y: FloatArray) -> int:
        """One call of the current update kernel: its status.

        On OK the NIS is also left in the buffer, for the caller.
        """
        out = self._ku(self._state, z, hx, jac, r, self._rbuf, y)
        if out >= 0.0:
            set_nis(self._rbuf, out)
            return OK
        return int(-out)

    def _run_past_gate(self, z: Any, hx: Any, jac: Any, r: Any, y: FloatArray) -> int:
        """The update the kernel gated on its NIS but whose exact NIS passes: its status.

        The kernel runs again without the gate (the exact NIS, left in the buffer
        by retry_gated, is reported on OK), so that the result is the ungated
        update's, as for any measurement the gate passes.
        """
        rbuf = self._rbuf
        nis = rbuf_nis(rbuf)
        gate = rbuf_gate(rbuf)
        # As in _set_options: the keys stand for no options while the gate is lifted,
        # so that an interrupt before it is back leaves the next update to set them.
        entry = self._entry
        options, gate_key = entry[2], entry[3]
        entry[2] = self._options = _UNSET
        entry[3] = self._gate = _UNSET
        set_gate(rbuf, _INF)
        status = self._run(z, hx, jac, r, y)
        set_gate(rbuf, gate)
        entry[2] = self._options = options
        entry[3] = self._gate = gate_key
        if status == CANCELLED:
            status = finish_cancelled(self._state, rbuf, jac, y)
        if status == OK:
            set_nis(rbuf, nis)
        return status

    def _use_rbuf(self, m: int) -> None:
        """Make the buffer and kernel of ``m``-dimensional measurements the current ones."""
        entry = self._rbufs.get(m)
        if entry is None:
            if len(self._rbufs) >= _CACHE_SIZE:
                self._rbufs.clear()
            # A new buffer holds the default options (no angles, no gate).
            entry = [new_rbuf(self._n, m), update_kernel(self._n, m), _NO_ANGLES, None]
            self._rbufs[m] = entry
        self._entry = entry
        self._rbuf, self._ku, self._options, self._gate = entry
        self._m = m

    def _measurement_angles(self, indices: Iterable[int], m: int) -> IntArray:
        """``angle_measurements`` as an int64 array, checked against ``m``.

        A tuple is remembered (by identity) once checked: the fast path of
        :meth:`update` then takes its indices, checked against each
        measurement's size.
        """
        if indices is _NO_ANGLES:
            return _NO_INDICES
        out = np.array(index_tuple(indices, "angle_measurements", m), dtype=np.int64)
        if type(indices) is tuple:
            if len(self._meas_angles) >= _CACHE_SIZE:
                self._meas_angles.clear()
            self._meas_angles[id(indices)] = (indices, out, int(out.max(initial=-1)) + 1)
        return out

    def __repr__(self) -> str:
        # A user subclass is named as itself (as navkit's potential fields are). The
        # state is no argument (x0 and P0 are): <...>, as for the other reprs in call form.
        states = "state" if self._n == 1 else "states"
        return f"{type(self).__name__}(<{self._n} {states}>, angle_states={self._angles})"


_NO_RBUF: FloatArray = np.zeros((1, 1, 1))  # the buffer before the first update


def _plain_indices(value: object, m: int) -> IntArray | None:
    """``value`` as int64 indices if it is a list or tuple of distinct ints in [0, m).

    The valid cases of :func:`~navkit.estimation._covariance.index_tuple` with
    plain ``int`` items only; None for anything else (then checked in full).
    """
    if (type(value) is not list and type(value) is not tuple) or len(value) > m:
        return None
    for item in value:
        if type(item) is not int or not 0 <= item < m:
            return None
    if len(set(value)) != len(value):
        return None
    return np.array(value, dtype=np.int64)


def _no_update_kernel(*args: Any) -> float:
    """The update "kernel" before the first update: no measurement size fits."""
    return -float(BAD_SHAPE)


def _restore(
    state: FloatArray,
    angles: tuple[int, ...],
    cls: type[ExtendedKalmanFilter] = ExtendedKalmanFilter,
) -> ExtendedKalmanFilter:
    """An :class:`ExtendedKalmanFilter` (or ``cls``) with the given ``state`` array.

    For unpickling and copies; pickles made before ``cls`` existed pass two arguments.
    """
    ekf: ExtendedKalmanFilter = object.__new__(cls)
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


def _nested(ekf: ExtendedKalmanFilter, method: str) -> NoReturn:
    """Refuse a step made while a step of the same filter runs its model functions.

    From those functions (this thread's stack holds the running step), or from
    another thread meanwhile: the two need different advice. Looked up here,
    on the error path, rather than by recording the stepping thread, which
    would cost every step a call.
    """
    # Named by its class, as the repr is: a user's subclass is what the user calls.
    name = f"{type(ekf).__name__}.{method}"
    steps = (ExtendedKalmanFilter.predict.__code__, ExtendedKalmanFilter.update.__code__)
    frame: FrameType | None = sys._getframe(2)
    while frame is not None:
        if frame.f_code in steps and frame.f_locals.get("self") is ekf:
            raise RuntimeError(
                f"{name} called from a model function (f, F, h or H) of the same "
                "filter's step: the steps would mix; make it after that step returns"
            )
        frame = frame.f_back
    raise RuntimeError(
        f"{name} called while another thread's step of the same filter runs its model "
        "functions: a filter is used by one thread at a time (a lock around its steps, "
        "or one filter per thread)"
    )


def _above(nis: float, gate: float) -> str:
    """``nis`` in 6 significant digits, or as many more as show it above ``gate``.

    A gate is printed as its repr: a NIS printed with 6 digits could read equal to it
    or below while above it ("NIS 100 > 100.0" for 100.00000000000001, before review
    42, EKFREV3). A decimal that rounds to a float above the gate is above the gate's
    repr (rounding is monotonic).
    """
    for digits in range(6, 17):
        text = f"{nis:.{digits}g}"
        if float(text) > gate:
            return text
    return repr(nis)


def _raise(status: int, what: str) -> NoReturn:
    """Raise the error a kernel status code stands for."""
    name = _NON_FINITE_NAMES.get(status)
    if name is not None:
        raise ValueError(f"{name} must contain only finite values")
    if status == NOT_FINITE:
        raise FilterError(f"{what} is not finite")
    raise FilterError(f"{what} is not positive definite")
