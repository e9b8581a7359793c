"""numba kernels of the planar odometry + IMU filter, navkit.estimation.PlanarFusion (private).

State layout (6,): ``[x, y, theta, v, omega, a]`` — world position (m), heading
(rad, wrapped to (-pi, pi]), forward speed (m/s), yaw rate (rad/s) and forward
acceleration (m/s^2). Measurements use the "component" layout (4,):
``[theta, v, omega, a]`` (the observation vector [θ, ẋ, θ̇, ẍ]); component ``k``
observes state ``k + 2``, so every measurement model is linear.

The filter lives in one caller-owned array ``buf`` (layout ``BUF_*`` below):
state, covariance, process noise, the current measurement, the filter time and
scratch space, because at this size heap allocations would cost more than the
arithmetic. The public layer (:mod:`navkit.estimation._fusion`) validates
input; these kernels assume finite, well-shaped arrays and never raise (the
online step checks its scalars itself and reports ``INVALID``). They never
return a non-finite state either: a prediction that would overflow float64 (a
huge time gap) is undone (``TIME_GAP``), and an update that would overflow (a
measurement absurdly far from the state for its variance) is not applied
(``OVERFLOW``).

Compilation (first use with an empty cache) is kept short by design (issue 17):

* the filter is one function, the step :func:`_planar_step`, which the online
  entry :func:`planar_step_plain` and the batch loop :func:`planar_run` call
  (a separate filter function called by both was optimised by LLVM three
  times: alone and linked into each caller). It is a helper (no Python
  wrapper, no machine code of its own), linked into the online entry
  :func:`planar_step_plain`; since review 51 the batch loop calls that
  entry's compiled function by its address (:func:`step_address`,
  :mod:`navkit.estimation._step_call`) instead of linking a second copy,
  which LLVM optimised and translated again (about 0.3 s; it was called, not
  inlined, there too). :func:`planar_step`, the same step entered with
  float64 arguments, is compiled only when Python calls it (tests,
  benchmarks). Every kernel is compiled for the one signature the public
  layer passes;
* no array is copied with slice assignment: numba compiles ``a[:] = b`` with a
  shape-mismatch error path whose message it builds with f-strings, 0.2-1.9 s
  per site; copies are loops;
* the buffer is flat and indexed at constant offsets (``buf[_P0 + W * i + j]``),
  not through 2-D views: a 2-D index or a slice lowers to several times the IR
  of a 1-D index, and LLVM sees every address as a constant offset from one
  pointer (no run-time row stride to multiply by or to version loops on). This
  cut the unoptimised IR of planar_step from 18,600 to 12,900 lines and its
  compilation by about 0.2 s, and made the batch loop about 10 % faster;
* a loop over the observed components (their number m, 1-4, known only at
  run time) is never nested in a loop of constant length: LLVM unrolled such
  a loop four times, with a remainder loop, inside each of the 6-36 entries of
  the unrolled 6 x 6 loops around it (half of planar_step's 11,700 lines of
  optimised IR). The loops over the components are the outer ones, and K and
  S⁻¹ y come from one solve with 7 right-hand sides: LLVM spends about 0.7 s
  less over both kernels, and the kernels run faster;
* no ``.view()``: numba compiles a dtype-compatibility check for it (0.3 s), so
  the indices of the observed components are stored as floats;
* a helper inlined at numba IR level (``njit_inline``) is copied, typed and
  lowered again at every call site: :func:`compose_scalar
  <navkit._shared.se2.compose_scalar>` is written out (the step has its cosine
  and sine already) and the three angle wraps call :func:`_wrap`, typed once
  and inlined by LLVM (0.07 s less). The Cholesky factorisation (two sites) and
  the solve stay IR-inlined: as ``njit_force_inline`` functions they cost
  about 0.1 s more (separate compilations, and LLVM work at each site).

Together: planar_step about 2.6 -> 1.9 s, planar_run 0.8 -> 0.4 s, the first
use of PlanarFusion 3.7 -> 2.5 s of CPU.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, cast

import numpy as np

from navkit._shared.jit import (
    bind_numba_names,
    njit_force_inline,
    njit_helper,
    njit_inline,
    njit_no_refcount,
    njit_released,
)
from navkit._shared.se2 import wrap_scalar
from navkit._shared.types import KernelInt

# (review 51: se2.wrap_scalar/exp_body compiled once and inlined by LLVM; see _wrap.)

# A float64 of a PLAIN_FLOAT argument (navkit.estimation._plain_float, which imports
# numba: bound when numba loads), for planar_step_plain.
plain_value: Any = None


def _plain_value_python(x: Any) -> float:
    """``plain_value`` when the JIT is disabled: the float ``x`` as PLAIN_FLOAT takes it.

    Kernels then run as Python: a float, an instance of a float subclass defined
    in C (NumPy's float64) or an int of magnitude at most 2**53 gives its value,
    anything else NaN.
    """
    if type(x) is float:
        return x
    if type(x) is int:
        return float(x) if -_EXACT_INT <= x <= _EXACT_INT else math.nan
    if isinstance(x, float) and not type(x).__flags__ & _HEAPTYPE:
        return float.__float__(x)  # its value, calling nothing of its own
    return math.nan


_HEAPTYPE = 1 << 9  # CPython's type flag of classes defined in Python
_EXACT_INT = 2**53  # the ints float64 holds exactly lie within ±this
bind_numba_names(
    globals(), "navkit.estimation._plain_float",
    python={"plain_value": _plain_value_python}, plain_value="plain_value",
)  # fmt: skip
# The batch loop's call of the step by its address, and the online entry's answer of
# that address (navkit.estimation._step_call, which imports numba: bound when numba
# loads); with the JIT disabled the step itself, called as Python, and no address.
# (review 51, FRESH2: call_step raises the step's exception, if any; a cached planar_run
# made before then is made again.)
call_step: Any = None
step_pointer: Any = None


def _call_step_python(address: int, *args: Any) -> tuple[int, float]:
    """``call_step`` when the JIT is disabled: the step, called as Python (no address)."""
    return _planar_step(*args)


def _step_pointer_python(step: Any) -> int:
    """``step_pointer`` when the JIT is disabled: no compiled step, no address."""
    return 0


bind_numba_names(
    globals(), "navkit.estimation._step_call",
    python={"call_step": _call_step_python, "step_pointer": _step_pointer_python},
    call_step="call_step", step_pointer="step_pointer",
)  # fmt: skip

N_STATE = 6
N_COMP = 4
THETA = 2

# Status codes shared with the public layer.
ACCEPTED = 0
GATED = 1
NOT_POSITIVE_DEFINITE = 2
OUT_OF_ORDER = 3
TIME_GAP = 4
OVERFLOW = 5
# Online step only: the arguments failed its checks (see planar_step); nothing changed.
INVALID = -1
# planar_step_plain's ``count`` asking for the step's address (see step_address).
STEP_ADDRESS = -2

# The filter buffer of :func:`planar_step` is one flat float64 array: everything in one
# array, because numba's per-call dispatch cost grows with every array argument, and
# flat, so that every index is a constant offset plus 6 i + j (see "Compilation").
# It is laid out in rows of W entries; a matrix takes N_STATE rows, stored by rows.
W = 6
BUF_X = 0  # 1 row: state x
BUF_P = 1  # 6 rows: covariance P
BUF_Q = 7  # 6 rows: process noise per second Q
BUF_MEAS = 13  # 3 rows: values, variances, residuals (entries 0-3, component layout)
BUF_T = 16  # 1 row: the filter time (NaN until the clock is set), then the time saved
#            by the online step (see undo_step)
BUF_WORK = 17  # scratch rows, below
# Scratch rows.
_E = BUF_WORK  # 4 rows: F - I (rows 0-3 of F), predict
_FP = _E + 4  # 6 rows: F P, predict; reused as A P, update
_Y = _FP + N_STATE  # 1 row: residual y, update
_INV = _Y + 1  # 2 rows: 1/diag(L) of S and of the updated covariance, update
_COMP = _INV + 2  # 1 row: the indices of the observed components (as floats), update
_CHOL = _COMP + 1  # 4 rows: Cholesky factor of S (m x m in the top-left corner)
_SOLVE = _CHOL + N_COMP  # 7 rows (m entries each): K (rows 0-5) and S⁻¹ y (row 6)
_XN = _SOLVE + N_STATE + 1  # 1 row: updated state
_PN = _XN + 1  # 6 rows: updated covariance (below the state, as P below x)
_CHECK = _PN + N_STATE  # 6 rows: positive-definiteness check
_SAVED = _CHECK + N_STATE  # 7 rows: x and P saved by planar_step
BUF_ROWS = _SAVED + 1 + N_STATE
BUF_SIZE = W * BUF_ROWS
#: Indices in the buffer of the filter time and of the time saved by the online step.
BUF_TIME = W * BUF_T
BUF_SAVED_TIME = BUF_TIME + 1
#: Index of the pending-undo mark: nonzero from an online step's return of
#: ``TIME_GAP`` or ``NOT_POSITIVE_DEFINITE`` until :func:`undo_step` has undone
#: it. A ``KeyboardInterrupt`` delivered as the step returns loses its status;
#: the mark tells the public layer there is a step to undo.
BUF_UNDO = BUF_TIME + 2

# Offsets (entries) of the blocks the kernels index.
_X0 = W * BUF_X
_P0 = W * BUF_P
_Q0 = W * BUF_Q
_Z0 = W * BUF_MEAS  # values
_R0 = _Z0 + W  # variances
_RES0 = _R0 + W  # residuals
_E0 = W * _E
_FP0 = W * _FP
_Y0 = W * _Y
_INV0 = W * _INV
_COMP0 = W * _COMP
_CHOL0 = W * _CHOL
_SOLVE0 = W * _SOLVE
_PN0 = W * _PN
_CHECK0 = W * _CHECK
_XN0 = W * _XN
_SAVED0 = W * _SAVED


@njit_force_inline
def _wrap(a: float) -> float:
    """:func:`navkit._shared.se2.wrap_scalar`, typed once (LLVM inlines it)."""
    return wrap_scalar(a)


@njit_inline
def _cholesky_inplace(buf: np.ndarray, a: int, n: int, inv_diag: int) -> bool:
    """Lower Cholesky factor L of the leading n×n block of the matrix at ``buf[a]``, in place.

    The matrix is stored by rows of ``W`` entries. Also stores 1 / L[j, j] in
    ``buf[inv_diag + j]`` so that the solves multiply instead of divide.
    Returns False (and stops) if the block is not positive definite or not
    finite (an inf or NaN entry makes some pivot inf or NaN).
    """
    for j in range(n):
        s = buf[a + W * j + j]
        for k in range(j):
            s -= buf[a + W * j + k] * buf[a + W * j + k]
        if not 0.0 < s < math.inf:
            return False
        d = math.sqrt(s)
        buf[a + W * j + j] = d
        inv = 1.0 / d
        buf[inv_diag + j] = inv
        for i in range(j + 1, n):
            t = buf[a + W * i + j]
            for k in range(j):
                t -= buf[a + W * i + k] * buf[a + W * j + k]
            buf[a + W * i + j] = t * inv
    return True


@njit_inline
def _cho_solve_rows(buf: np.ndarray, lower: int, inv_diag: int, n: int, b: int) -> None:
    """Solve (L Lᵀ) uᵣ = bᵣ for the 7 rows bᵣ (first n entries) of the block at ``buf[b]``.

    ``L`` is the factor at ``buf[lower]`` and ``buf[inv_diag]`` the inverse of its
    diagonal (:func:`_cholesky_inplace`); the solutions replace the rows. The
    rows are solved together, entry by entry, so that the loops over the rows
    have a constant length (LLVM unrolls them) and the loops over ``n`` are not
    copied once per row; each entry sees the same operations in the same order
    as in a solve of its row alone.
    """
    for i in range(n):
        for k in range(i):
            f = buf[lower + W * i + k]
            for r in range(N_STATE + 1):
                buf[b + W * r + i] -= f * buf[b + W * r + k]
        f = buf[inv_diag + i]
        for r in range(N_STATE + 1):
            buf[b + W * r + i] *= f
    for i in range(n - 1, -1, -1):
        for k in range(i + 1, n):
            f = buf[lower + W * k + i]
            for r in range(N_STATE + 1):
                buf[b + W * r + i] -= f * buf[b + W * r + k]
        f = buf[inv_diag + i]
        for r in range(N_STATE + 1):
            buf[b + W * r + i] *= f


@njit_helper
def _planar_step(
    buf: np.ndarray,
    t: float,
    first: KernelInt,
    count: KernelInt,
    z0: float,
    z1: float,
    var0: float,
    var1: float,
    gate: float,
) -> tuple[int, float]:
    """Predict the filter in ``buf`` to time ``t``, then update it with one measurement.

    The one compiled body of the filter: the online updates call it through
    :func:`planar_step_plain` and the batch loop (:func:`planar_run`) calls it,
    so that numba types and lowers it once and LLVM optimises it once in each
    caller (issue 17). ``buf`` (BUF_SIZE,) holds x, P, Q, the
    measurement, the filter time and the scratch space (layout ``BUF_*``
    above); x and P change in place. It allocates nothing: the indices of the
    observed components go to a scratch row of ``buf`` (as floats).

    Online (``count`` >= 0): the measurement observes ``count`` (0, 1 or 2)
    consecutive components starting at ``first``, with values ``z0``, ``z1`` and
    variances ``var0``, ``var1`` (the second ones unused when ``count`` is 1;
    ``count`` 0 only predicts); passing scalars is cheaper than writing them
    into ``buf`` from Python. Returns ``INVALID`` and changes nothing unless the
    filter time is set, ``t`` is not older than it, ``t``, ``z0`` and ``z1`` are
    finite and the variances of the observed components are in [1e-100,
    1e100]: the public layer calls this first and takes its general
    (validating, raising) way only then. Otherwise x, P and the filter time are
    saved in ``buf``, the time becomes ``t`` and x and P are overwritten with
    the result; after ``NOT_POSITIVE_DEFINITE`` or ``TIME_GAP`` (the prediction
    overflowed; no update was tried) the caller restores them with
    :func:`undo_step` (rare outcomes: the public layer raises after them). A
    gated or overflowing measurement keeps the prediction.

    Batch (``count`` -1, :func:`planar_run`): the caller has written the
    measurement block of ``buf`` and passes the time step in ``z0``; nothing is
    checked, saved, restored or timed here (``t``, ``first``, ``z1``, ``var0``
    and ``var1`` are unused).

    Predict: constant-acceleration unicycle. The distance s = v·dt + a·dt²/2 is
    travelled along the mid-step heading θ + ω·dt/2 (second order in dt), then
    θ += ω·dt, v += a·dt; ω and a are random walks. Q is the process noise per
    second, so P = F P Fᵀ + Q·dt. If the prediction overflows, the status is
    ``TIME_GAP`` (``nis`` NaN).

    Update: the measurement block (3 rows of ``buf``) packs the measurement in
    component layout (entries 0-3): row 0 the values ``z``, row 1 the noise
    variances (> 0 for the observed components, 0 for the others, none
    observed: predict only; the noise is independent between components), row
    2 receives the residuals of the observed components (others untouched).
    The yaw residual is wrapped. The covariance uses the Joseph form
    P = (I - KH) P (I - KH)ᵀ + K R Kᵀ, then is symmetrised and checked
    positive definite. Returns ``(status, nis)``; past
    the prediction, x and P change only when the status is ``ACCEPTED``.
    ``gate`` is the NIS threshold (``inf`` disables gating). ``OVERFLOW`` (with
    ``nis`` inf when the NIS itself overflowed) means the residual, the NIS or
    the updated state is not finite.
    """
    # For mypy alone (numba ignores a bare annotation): component indices below are
    # np.int64 conversions of buffer entries.
    k: KernelInt
    online = count >= 0
    if online:
        last = buf[BUF_TIME]
        z = 0.0
        if not last <= t or (t * z + z0 * z) + z1 * z != 0.0:  # NaN last: no clock yet
            return INVALID, math.nan
        if count > 0 and not 1e-100 <= var0 <= 1e100:
            return INVALID, math.nan
        if count > 1 and not 1e-100 <= var1 <= 1e100:
            return INVALID, math.nan
        for k in range(N_COMP):
            buf[_R0 + k] = 0.0
        if count > 0:
            buf[_Z0 + first] = z0
            buf[_R0 + first] = var0
        if count > 1:
            buf[_Z0 + first + 1] = z1
            buf[_R0 + first + 1] = var1
        for i in range(W * (1 + N_STATE)):  # x and P
            buf[_SAVED0 + i] = buf[_X0 + i]
        buf[BUF_SAVED_TIME] = last
        buf[BUF_UNDO] = 0.0  # a mark left by an interrupted undo is not this step's
        buf[BUF_TIME] = t
        dt = t - last
    else:
        dt = z0
    if dt != 0.0:
        v = buf[_X0 + 3]
        omega = buf[_X0 + 4]
        acc = buf[_X0 + 5]
        s = v * dt + 0.5 * acc * dt * dt
        half = 0.5 * omega * dt
        mid = buf[_X0 + 2] + half
        c = math.cos(mid)
        sn = math.sin(mid)
        # navkit._shared.se2.compose_scalar(x, y, mid, s, 0.0, half) written out (it would
        # compute the cosine and sine again): from the mid-step heading with a half turn.
        buf[_X0] = buf[_X0] + c * s - sn * 0.0
        buf[_X0 + 1] = buf[_X0 + 1] + sn * s + c * 0.0
        buf[_X0 + 2] = _wrap(mid + half)
        buf[_X0 + 3] = v + acc * dt

        # F = I + E with E non-zero only in rows 0-3 and columns 2-5, so F P Fᵀ is done
        # sparsely: FP = P + E P (rows 0-3 change), then FP Fᵀ = FP + FP Eᵀ (columns 0-3).
        for i in range(4 * W):
            buf[_E0 + i] = 0.0
        buf[_E0 + 2] = -sn * s
        buf[_E0 + 3] = c * dt
        buf[_E0 + 4] = -sn * s * 0.5 * dt
        buf[_E0 + 5] = c * 0.5 * dt * dt
        buf[_E0 + W + 2] = c * s
        buf[_E0 + W + 3] = sn * dt
        buf[_E0 + W + 4] = c * s * 0.5 * dt
        buf[_E0 + W + 5] = sn * 0.5 * dt * dt
        buf[_E0 + 2 * W + 4] = dt
        buf[_E0 + 3 * W + 5] = dt
        for i in range(N_STATE):
            for j in range(N_STATE):
                tmp = buf[_P0 + W * i + j]
                if i < 4:
                    ep = 0.0
                    for k in range(2, N_STATE):
                        ep += buf[_E0 + W * i + k] * buf[_P0 + W * k + j]
                    tmp += ep
                buf[_FP0 + W * i + j] = tmp
        for i in range(N_STATE):
            for j in range(N_STATE):
                tmp = buf[_FP0 + W * i + j]
                if j < 4:
                    for k in range(2, N_STATE):
                        tmp += buf[_FP0 + W * i + k] * buf[_E0 + W * j + k]
                buf[_P0 + W * i + j] = tmp + buf[_Q0 + W * i + j] * dt
        for i in range(N_STATE):
            for j in range(i + 1, N_STATE):
                tmp = 0.5 * (buf[_P0 + W * i + j] + buf[_P0 + W * j + i])
                buf[_P0 + W * i + j] = tmp
                buf[_P0 + W * j + i] = tmp
        # Overflow check: the prediction changes x, y, θ, v and P. An overflow anywhere in P
        # shows on its diagonal (as inf or NaN): every entry of a positive semi-definite
        # matrix is bounded by its diagonal (|P_ij| <= sqrt(P_ii P_jj)). ``u * 0.0`` is 0
        # for a finite ``u`` and NaN otherwise, so the check never overflows itself.
        z = 0.0
        for i in range(N_STATE):
            z += buf[_X0 + i] * 0.0 + buf[_P0 + (W + 1) * i] * 0.0
        if z != 0.0:
            if online:
                buf[BUF_UNDO] = TIME_GAP
            return TIME_GAP, math.nan

    # The indices of the observed components (as floats), the residuals and S.
    m = 0
    for k in range(N_COMP):
        if buf[_R0 + k] > 0.0:
            buf[_COMP0 + m] = k
            m += 1
    if m == 0:
        return ACCEPTED, 0.0
    # Right-hand sides solved with S: the rows of P Hᵀ (for K = P Hᵀ S⁻¹; S is symmetric, so
    # each row of K solves S kᵢ = (P Hᵀ)ᵢ) and, in row 6, y (for the NIS yᵀ S⁻¹ y).
    for a in range(m):
        # np.int64, not int(): numba compiles int() as an overload of its own on
        # first use (issue 17); both truncate.
        k = np.int64(buf[_COMP0 + a])
        r = buf[_Z0 + k] - buf[_X0 + k + 2]
        if k + 2 == THETA:
            r = _wrap(r)
        buf[_RES0 + k] = r
        buf[_Y0 + a] = r
        buf[_SOLVE0 + W * N_STATE + a] = r
        for i in range(N_STATE):
            buf[_SOLVE0 + W * i + a] = buf[_P0 + W * i + k + 2]
    for a in range(m):
        k = np.int64(buf[_COMP0 + a])
        for b in range(m):
            buf[_CHOL0 + W * a + b] = buf[_P0 + W * (k + 2) + np.int64(buf[_COMP0 + b]) + 2]
            # The observed states' own rows of K, H K = H P Hᵀ S⁻¹ = I - R S⁻¹, would
            # cancel: solve for -R S⁻¹ instead (its row a solves S u = -R e_a).
            buf[_SOLVE0 + W * (k + 2) + b] = 0.0
        buf[_CHOL0 + (W + 1) * a] += buf[_R0 + k]
        buf[_SOLVE0 + W * (k + 2) + a] = -buf[_R0 + k]
    if not _cholesky_inplace(buf, _CHOL0, m, _INV0):
        if online:
            buf[BUF_UNDO] = NOT_POSITIVE_DEFINITE
        return NOT_POSITIVE_DEFINITE, math.nan
    _cho_solve_rows(buf, _CHOL0, _INV0, m, _SOLVE0)
    nis = 0.0
    for a in range(m):
        nis += buf[_Y0 + a] * buf[_SOLVE0 + W * N_STATE + a]
    if not nis < math.inf:  # also NaN: an infinite residual
        return OVERFLOW, math.inf
    if nis > gate:
        return GATED, nis
    # E = R S⁻¹ (m x m) to the rows of F - I (free after the prediction), then the
    # observed rows of K: off the diagonal -E; on it 1 - E where E <= 1/2, otherwise
    # (a measurement less precise than the estimate) (H P Hᵀ S⁻¹)_aa with S⁻¹ = R⁻¹ E.
    for a in range(m):
        ka = np.int64(buf[_COMP0 + a]) + 2
        for b in range(m):
            buf[_E0 + W * a + b] = -buf[_SOLVE0 + W * ka + b]
    for a in range(m):
        ka = np.int64(buf[_COMP0 + a]) + 2
        for b in range(m):
            buf[_SOLVE0 + W * ka + b] = -buf[_E0 + W * a + b]
        e = buf[_E0 + (W + 1) * a]
        if e <= 0.5:
            buf[_SOLVE0 + W * ka + a] = 1.0 - e
        else:
            t = 0.0
            for b in range(m):
                kb = np.int64(buf[_COMP0 + b])
                t += buf[_P0 + W * ka + kb + 2] * (buf[_E0 + W * b + a] / buf[_R0 + kb])
            buf[_SOLVE0 + W * ka + a] = t
    # From here on K is rows 0-5 of the solved block. The loops over the observed
    # components are the outer ones: the inner loops have a constant length and LLVM
    # unrolls them, instead of copying a loop over the components (unrolled four times,
    # with a remainder loop) into each of 6 or 36 entries. Each entry still sees the same
    # operations in the same order.
    for i in range(N_STATE):
        buf[_XN0 + i] = buf[_X0 + i]
    for a in range(m):
        ya = buf[_Y0 + a]
        for i in range(N_STATE):
            buf[_XN0 + i] += buf[_SOLVE0 + W * i + a] * ya
    buf[_XN0 + THETA] = _wrap(buf[_XN0 + THETA])
    # Joseph form P = A P Aᵀ + K R Kᵀ with H selecting the observed states: A = I - K H
    # differs from I only in those columns, so A P = P - K (H P) and (A P) Aᵀ =
    # A P - (A P Hᵀ) Kᵀ. Except in the rows of A of the observed states themselves:
    # there A = I - H K = R S⁻¹ (on the observed columns, 0 elsewhere), which
    # 1 - K computes with a cancellation that leaves about ε² P for a K rounded by ε,
    # all that is left when R < ε² P (P 1e100 and R 1e-100 gave a variance of 4e68,
    # not 1e-100, and cross-covariances wrong by orders of magnitude). R S⁻¹ itself,
    # (solved above), keeps them to rounding; A P Aᵀ + K R Kᵀ stays a sum of positive
    # semi-definite terms.
    for i in range(W * N_STATE):
        buf[_FP0 + i] = buf[_P0 + i]
    for a in range(m):
        k = np.int64(buf[_COMP0 + a]) + 2
        for i in range(N_STATE):
            g = buf[_SOLVE0 + W * i + a]
            for j in range(N_STATE):
                buf[_FP0 + W * i + j] -= g * buf[_P0 + W * k + j]
    # The observed rows of A P: (R S⁻¹ H P) = R Kᵀ.
    for a in range(m):
        k = np.int64(buf[_COMP0 + a])
        rk = buf[_R0 + k]
        for j in range(N_STATE):
            buf[_FP0 + W * (k + 2) + j] = rk * buf[_SOLVE0 + W * j + a]
    # M = A P + (K R - A P Hᵀ) Kᵀ, entry by entry, ...
    for i in range(W * N_STATE):
        buf[_PN0 + i] = buf[_FP0 + i]
    for a in range(m):
        k = np.int64(buf[_COMP0 + a])
        rk = buf[_R0 + k]
        for i in range(N_STATE):
            g = buf[_SOLVE0 + W * i + a] * rk - buf[_FP0 + W * i + k + 2]
            for j in range(N_STATE):
                buf[_PN0 + W * i + j] += g * buf[_SOLVE0 + W * j + a]
    # ... but in the observed columns (A P) Aᵀ takes the rows R S⁻¹ of A:
    # M[:, c] = Σ_b (A P)[:, b] (R S⁻¹)[c, b] + K R K[c, :]ᵀ.
    for c in range(m):
        kc = np.int64(buf[_COMP0 + c]) + 2
        for i in range(N_STATE):
            buf[_PN0 + W * i + kc] = 0.0
        for b in range(m):
            kb = np.int64(buf[_COMP0 + b])
            e = buf[_E0 + W * c + b]
            kr = buf[_SOLVE0 + W * kc + b] * buf[_R0 + kb]
            for i in range(N_STATE):
                buf[_PN0 + W * i + kc] += (
                    buf[_FP0 + W * i + kb + 2] * e + buf[_SOLVE0 + W * i + b] * kr
                )
    # The result is symmetric in exact arithmetic, so it is the mean of M and Mᵀ (exactly
    # symmetric).
    for i in range(N_STATE):
        for j in range(i, N_STATE):
            tmp = 0.5 * (buf[_PN0 + W * i + j] + buf[_PN0 + W * j + i])
            buf[_PN0 + W * i + j] = tmp
            buf[_PN0 + W * j + i] = tmp
    # The state may overflow (then it is inf or NaN); the covariance is checked finite
    # by the Cholesky factorisation below.
    z = 0.0
    for i in range(N_STATE):
        z += buf[_XN0 + i] * 0.0
    if z != 0.0:
        return OVERFLOW, nis
    for i in range(W * N_STATE):
        buf[_CHECK0 + i] = buf[_PN0 + i]
    if not _cholesky_inplace(buf, _CHECK0, N_STATE, _INV0 + W):
        if online:
            buf[BUF_UNDO] = NOT_POSITIVE_DEFINITE
        return NOT_POSITIVE_DEFINITE, nis
    for i in range(W * (1 + N_STATE)):  # x and P from the updated x and P below each other
        buf[_X0 + i] = buf[_XN0 + i]
    return ACCEPTED, nis


@njit_no_refcount
def planar_step(
    buf: np.ndarray,
    t: float,
    first: KernelInt,
    count: KernelInt,
    z0: float,
    z1: float,
    var0: float,
    var1: float,
    gate: float,
) -> tuple[int, float]:
    """The online step (:func:`_planar_step`) called from Python with float64 arguments."""
    return _planar_step(buf, t, first, count, z0, z1, var0, var1, gate)


@njit_released
def planar_run(
    buf: np.ndarray,
    times: np.ndarray,
    values: np.ndarray,
    variances: np.ndarray,
    gates: np.ndarray,
    out_x: np.ndarray,
    out_p: np.ndarray,
    out_status: np.ndarray,
    out_nis: np.ndarray,
    step: KernelInt,
) -> None:
    """Fuse a log into the filter in ``buf`` with :func:`_planar_step` (in batch mode).

    Row ``i`` is a measurement at ``times[i]`` with values ``values[i]`` (4,) and
    independent variances ``variances[i]`` (4,), 0 marking components it does
    not observe. ``gates[m]`` is the NIS threshold for an m-component
    measurement (``inf`` disables gating). x, P and the time in ``buf`` are
    updated in place; the state after each row goes to ``out_x[i]``, ``out_p[i]``. Rows
    older than the filter time are not applied (``OUT_OF_ORDER``); nor are rows
    whose prediction would overflow (``TIME_GAP``: the state and time stay as
    they were). A row whose update fails numerically keeps the prediction and
    is marked ``NOT_POSITIVE_DEFINITE`` or ``OVERFLOW``.

    The filter time in ``buf`` is the time before the first row (NaN: the
    clock starts at ``times[0]``) and is set to the final time on return. The
    caller stores the initial x and P in ``out_x[-1]`` and ``out_p[-1]`` too: a
    ``TIME_GAP`` in row 0 restores them from there (a copy made here would slow
    the loop down measurably).

    ``step`` is :func:`step_address`, got in this process: the step is called
    through it, not linked into this kernel, so that its code is optimised and
    made once, in :func:`planar_step_plain` (issue 17, review 51: linked here, LLVM
    optimised and translated the step a second time, about 0.3 s of a first
    ``PlanarFusion`` use; it did not inline it, so each row made a call anyway).
    Any other value crashes the process: the public layer alone calls this.
    """
    t = buf[BUF_TIME]
    if math.isnan(t):  # no clock yet: it starts at the first row
        t = times[0]
    # Batch mode of _planar_step (count -1). Typed int64, not as literal constants: a literal
    # argument would compile _planar_step a second time, for the literal values.
    first = np.int64(0)
    batch = np.int64(-1)
    for i in range(times.shape[0]):
        ti = times[i]
        if ti < t:
            out_status[i] = OUT_OF_ORDER
            out_nis[i] = math.nan
        else:
            m = 0
            for k in range(N_COMP):
                buf[_Z0 + k] = values[i, k]
                buf[_R0 + k] = variances[i, k]
                if variances[i, k] > 0.0:
                    m += 1
            status, nis = call_step(step, buf, ti, first, batch, ti - t, 0.0, 0.0, 0.0, gates[m])
            if status == TIME_GAP:
                # Undo the prediction: back to the state after the previous row (for
                # row 0, index -1: the caller's copy of the initial state).
                for j in range(N_STATE):
                    buf[_X0 + j] = out_x[i - 1, j]
                    for k in range(N_STATE):
                        buf[_P0 + W * j + k] = out_p[i - 1, j, k]
            else:
                t = ti
            out_status[i] = status
            out_nis[i] = nis
        for j in range(N_STATE):
            out_x[i, j] = buf[_X0 + j]
            for k in range(N_STATE):
                out_p[i, j, k] = buf[_P0 + W * j + k]
    buf[BUF_TIME] = t


def undo_step(buf: np.ndarray) -> None:
    """Undo an online :func:`planar_step` that returned ``TIME_GAP`` or ``NOT_POSITIVE_DEFINITE``.

    Restores x, P and the filter time saved by the step (in NumPy: these
    outcomes are rare, and the public layer raises after them).

    Examples
    --------
    >>> buf = np.zeros(BUF_SIZE)
    >>> buf.reshape(BUF_ROWS, W)[BUF_P : BUF_P + 6] = np.eye(6)
    >>> buf[BUF_TIME] = 0.0
    >>> status, nis = planar_step_entry()(buf, 1e300, 0, 0, 0.0, 0.0, 0.0, 0.0, math.inf)
    >>> status == TIME_GAP, float(buf[BUF_TIME])
    (True, 1e+300)
    >>> undo_step(buf)
    >>> float(buf[BUF_TIME]), float(buf[W * BUF_P])
    (0.0, 1.0)
    """
    size = W * (1 + N_STATE)  # x and P
    # The time first: interrupted between the two (a KeyboardInterrupt as copyto
    # is entered), x and P are still the overflowed ones, which PlanarFusion
    # finds and undoes again (the other way round, x and P restored at the
    # overflowed time: every later measurement out of order).
    buf[BUF_TIME] = buf[BUF_SAVED_TIME]
    np.copyto(buf[_X0 : _X0 + size], buf[_SAVED0 : _SAVED0 + size])
    buf[BUF_UNDO] = 0.0  # last: interrupted before this, the step is undone again


def _step_types() -> tuple[Any, ...]:
    """numba argument types of :func:`planar_step`: the ones the public layer always passes.

    Argument types only, as :func:`planar_run` compiles it (also the key of the
    on-disk cache).
    """
    from numba.core import types

    return (
        types.Array(types.float64, 1, "C"),
        types.float64,  # t
        types.int64,  # first
        types.int64,  # count
        *(types.float64,) * 5,  # z0, z1, var0, var1, gate
    )


def planar_step_entry() -> Callable[..., tuple[int, float]]:
    """Compiled entry of :func:`planar_step`, skipping numba's per-call type dispatch.

    (The filter's online updates use :func:`planar_step_plain_entry`.)

    Calling a dispatcher first types all nine arguments to pick the compiled
    version (about 0.15 µs of a 1 µs call); the entry returned here is that
    version itself, compiled (or loaded from the cache) now. It checks no types:
    the caller passes the filter's buffer (a writable C-contiguous float64 array
    of shape (BUF_ROWS, 6)), Python floats for ``t``, the values, variances and
    gate and ints for ``first`` and ``count``.

    Examples
    --------
    >>> buf = np.zeros(BUF_SIZE)
    >>> buf.reshape(BUF_ROWS, W)[BUF_P : BUF_P + 6] = np.eye(6)
    >>> buf[BUF_TIME] = 0.0
    >>> status, nis = planar_step_entry()(buf, 0.1, 1, 1, 1.0, 0.0, 1.0, 1.0, math.inf)
    >>> status == ACCEPTED, round(nis, 3), float(buf[BUF_TIME])
    (True, 0.5, 0.1)
    """
    dispatcher: Any = planar_step
    if not hasattr(dispatcher, "compile"):  # NUMBA_DISABLE_JIT=1: a plain function
        return cast(Callable[..., tuple[int, float]], dispatcher)
    return cast(Callable[..., tuple[int, float]], dispatcher.compile(_step_types()))


@njit_no_refcount
def planar_step_plain(
    buf: np.ndarray,
    t: float,
    first: KernelInt,
    count: KernelInt,
    z0: float,
    z1: float,
    var0: float,
    var1: float,
    gate: float,
) -> tuple[int, float]:
    """The online step (:func:`_planar_step`), ``t``, the values and the variances as given.

    Its compiled entry (:func:`planar_step_plain_entry`) takes those five
    arguments as :data:`~navkit.estimation._plain_float.PLAIN_FLOAT`: a float, a
    NumPy float64 or an int float64 holds exactly is its value, anything else
    NaN, which the step refuses (``INVALID``, nothing changed). The public
    layer's fast paths call it with whatever they were given, instead of
    checking five types in Python first.

    With ``count`` ``STEP_ADDRESS`` it returns instead, as its status, the
    address of the step's compiled function in its own library, which the
    batch loop calls (:func:`step_address`).
    """
    if count == STEP_ADDRESS:
        return step_pointer(_planar_step), math.nan
    return _planar_step(
        buf, plain_value(t), first, count, plain_value(z0), plain_value(z1),
        plain_value(var0), plain_value(var1), gate,
    )  # fmt: skip


def planar_step_plain_entry() -> Callable[..., tuple[int, float]]:
    """Compiled entry of :func:`planar_step_plain`: the online step for the fast paths.

    As :func:`planar_step_entry`, with ``t``, ``z0``, ``z1``, ``var0`` and
    ``var1`` of type :data:`~navkit.estimation._plain_float.PLAIN_FLOAT`: a
    ``float``, a NumPy ``float64`` or an ``int`` of magnitude at most 2**53 is
    taken as its float value; anything else (a bool, a larger int, a string, a
    ``float32``, a float subclass defined in Python) is taken as NaN, without
    calling any of its methods, so that the step returns ``INVALID`` and
    changes nothing (it refuses a NaN time or value; the variances it reads
    must lie in [1e-100, 1e100]: pass 1.0 for an unobserved second component,
    as the filter does). The caller passes the filter's buffer, ints for
    ``first`` and ``count`` and a float gate. With the JIT disabled, the
    kernel itself (in Python), converting the same way.

    Examples
    --------
    >>> buf = np.zeros(BUF_SIZE)
    >>> buf.reshape(BUF_ROWS, W)[BUF_P : BUF_P + 6] = np.eye(6)
    >>> buf[BUF_TIME] = 0.0
    >>> step = planar_step_plain_entry()
    >>> status, nis = step(buf, 0.1, 1, 1, 1.0, 0.0, 1.0, 1.0, math.inf)
    >>> status == ACCEPTED, round(nis, 3), float(buf[BUF_TIME])
    (True, 0.5, 0.1)
    >>> step(buf, 0.2, 1, 1, "1.0", 0.0, 1.0, 1.0, math.inf)[0] == INVALID  # a string
    True
    >>> float(buf[BUF_TIME])  # nothing changed
    0.1
    """
    dispatcher: Any = planar_step_plain
    if not hasattr(dispatcher, "compile"):  # NUMBA_DISABLE_JIT=1: a plain function
        return cast(Callable[..., tuple[int, float]], dispatcher)
    from navkit.estimation._plain_float import PLAIN_FLOAT

    types = list(_step_types())
    for i in (1, 4, 5, 6, 7):  # t, z0, z1, var0, var1
        types[i] = PLAIN_FLOAT
    return cast(Callable[..., tuple[int, float]], dispatcher.compile(tuple(types)))


#: The address :func:`step_address` found, once per process ([] before).
_STEP_ADDRESS: list[int] = []


def step_address() -> int:
    """Address of the step's compiled function in :func:`planar_step_plain`'s library.

    For :func:`planar_run`, which calls the step through it. Compiles the
    online entry (or loads it from numba's cache) first, and asks it. The
    address is this process's (a forked child shares it); 0 with the JIT
    disabled, where the batch loop calls the step as Python.

    Examples
    --------
    >>> step_address() == step_address()
    True
    """
    if not _STEP_ADDRESS:
        buf = np.zeros(BUF_SIZE)
        address, _ = planar_step_plain_entry()(buf, 0.0, 0, STEP_ADDRESS, 0.0, 0.0, 1.0, 1.0, 0.0)
        _STEP_ADDRESS.append(int(address))
    return _STEP_ADDRESS[0]
