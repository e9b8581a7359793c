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

Compilation (first use with an empty cache) is kept short by design: the filter
is one function, the online step :func:`planar_step`, which the batch loop
:func:`planar_run` calls too (a separate filter function called by both, as
before issue 17's second round, was optimised by LLVM three times: alone and
linked into each caller); no array is copied with slice assignment (see
:func:`_copy_vector`); every kernel is compiled for the one signature the
public layer passes.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, cast

import numpy as np

from navkit._shared.jit import njit_inline, njit_no_refcount
from navkit._shared.se2 import compose_scalar, wrap_scalar

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

# Rows of the scratch array (each row has 6 entries).
_E = 0  # 4 rows: F - I (rows 0-3 of F), predict
_FP = 4  # 6 rows: F P, predict; reused as A P, update
_VEC = 10  # rows 10-14: residual y, solved u, a row of K, two 1/diag(L) rows
_CHOL = 15  # 4 rows: Cholesky factor of S (m x m in the top-left corner)
_GAIN = 19  # 6 rows: K (6 x m)
_PN = 25  # 6 rows: updated covariance
_CHECK = 31  # 6 rows: positive-definiteness check
_X = 37  # 1 row: updated state
_SAVED = 38  # 7 rows: x and P saved by planar_step
_COMP = 45  # 1 row: the indices of the observed components (as int64), update
WORK_ROWS = 46

# Rows of the online filter buffer of :func:`planar_step`: everything in one array,
# because numba's per-call dispatch cost grows with every array argument.
BUF_X = 0  # 1 row: state x
BUF_P = 1  # 6 rows: covariance P
BUF_Q = 7  # 6 rows: process noise per second Q
BUF_MEAS = 13  # 3 rows: values, variances, residuals (columns 0-3, component layout)
BUF_T = 16  # 1 row: the filter time in column 0 (NaN until the clock is set), in column 1
#            the time saved by the online step (see undo_step)
BUF_WORK = 17  # WORK_ROWS rows: scratch
BUF_ROWS = BUF_WORK + WORK_ROWS


@njit_inline
def _cholesky_inplace(a: np.ndarray, n: int, inv_diag: np.ndarray) -> bool:
    """Lower Cholesky factor L of the leading n×n block of ``a``, in place.

    Also stores 1 / L[j, j] in ``inv_diag[j]`` so that the solves multiply
    instead of divide. Returns False (and stops) if the block is not positive
    definite or not finite (an inf or NaN entry makes some pivot inf or NaN).
    """
    for j in range(n):
        s = a[j, j]
        for k in range(j):
            s -= a[j, k] * a[j, k]
        if not 0.0 < s < math.inf:
            return False
        d = math.sqrt(s)
        a[j, j] = d
        inv = 1.0 / d
        inv_diag[j] = inv
        for i in range(j + 1, n):
            t = a[i, j]
            for k in range(j):
                t -= a[i, k] * a[j, k]
            a[i, j] = t * inv
    return True


@njit_inline
def _cho_solve_vec(lower: np.ndarray, inv_diag: np.ndarray, n: int, b: np.ndarray) -> None:
    """Solve (L Lᵀ) u = b for the first n entries of ``b``, in place."""
    for i in range(n):
        t = b[i]
        for k in range(i):
            t -= lower[i, k] * b[k]
        b[i] = t * inv_diag[i]
    for i in range(n - 1, -1, -1):
        t = b[i]
        for k in range(i + 1, n):
            t -= lower[k, i] * b[k]
        b[i] = t * inv_diag[i]


@njit_inline
def _finite(x: np.ndarray, p: np.ndarray) -> bool:
    """Whether the predicted state ``x`` (6,) and covariance ``p`` (6, 6) are finite.

    The prediction changes only x, y, θ, v and the covariance; the diagonal
    suffices for the covariance: every entry of a positive semi-definite matrix
    is bounded by its diagonal (|P_ij| <= sqrt(P_ii P_jj)), so an overflow
    anywhere shows on the diagonal (as inf or NaN). ``v * 0.0`` is 0 for a
    finite ``v`` and NaN otherwise, so the check never overflows itself; the sum
    is a tree, not a chain, to keep its latency short.
    """
    z = 0.0
    a = (x[0] * z + x[1] * z) + (x[2] * z + x[3] * z)
    b = (p[0, 0] * z + p[1, 1] * z) + (p[2, 2] * z + p[3, 3] * z)
    ok: bool = (a + b) + (p[4, 4] * z + p[5, 5] * z) == 0.0
    return ok


@njit_inline
def _copy_vector(dst: np.ndarray, src: np.ndarray) -> None:
    """``dst[:] = src`` for 1-D arrays of equal length, as a loop.

    numba compiles an array-to-array slice assignment with a shape-mismatch
    error path that builds its message with f-strings: about 0.2-1.9 s of
    compilation per assignment site, for a copy of 6 or 36 numbers.
    """
    for i in range(dst.shape[0]):
        dst[i] = src[i]


@njit_inline
def _copy_matrix(dst: np.ndarray, src: np.ndarray) -> None:
    """``dst[:, :] = src`` for 2-D arrays of equal shape, as a loop (see :func:`_copy_vector`)."""
    for i in range(dst.shape[0]):
        for j in range(dst.shape[1]):
            dst[i, j] = src[i, j]


@njit_inline
def _symmetrize(p: np.ndarray) -> None:
    for i in range(p.shape[0]):
        for j in range(i + 1, p.shape[0]):
            m = 0.5 * (p[i, j] + p[j, i])
            p[i, j] = m
            p[j, i] = m


@njit_no_refcount
def planar_step(
    buf: np.ndarray,
    t: float,
    first: int,
    count: int,
    z0: float,
    z1: float,
    var0: float,
    var1: float,
    gate: float,
) -> tuple[int, float]:
    """Predict the filter in ``buf`` to time ``t``, then update it with one measurement.

    The one compiled body of the filter: the online updates call it from
    Python and the batch loop (:func:`planar_run`) calls it, so that numba
    types and lowers it once and LLVM optimises it twice (alone and linked into
    the batch loop; issue 17). ``buf`` (BUF_ROWS, 6) holds x, P, Q, the
    measurement, the filter time and the scratch space (layout ``BUF_*``
    above); x and P change in place. It allocates nothing: the indices of the
    observed components go to a scratch row of ``buf`` viewed as int64.

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

    Update: the measurement block (3, 4) of ``buf`` packs the measurement in
    component layout: row 0 the values ``z``, row 1 the noise variances (> 0 for
    the observed components, 0 for the others, none observed: predict only; the
    noise is independent between components), row 2 receives the residuals of
    the observed components (others untouched). The yaw residual is wrapped. The
    covariance uses the Joseph form P = (I - KH) P (I - KH)ᵀ + K R Kᵀ, then is
    symmetrised and checked positive definite. Returns ``(status, nis)``; past
    the prediction, x and P change only when the status is ``ACCEPTED``.
    ``gate`` is the NIS threshold (``inf`` disables gating). ``OVERFLOW`` (with
    ``nis`` inf when the NIS itself overflowed) means the residual, the NIS or
    the updated state is not finite.
    """
    online = count >= 0
    if online:
        last = buf[BUF_T, 0]
        z = 0.0
        if not last <= t or (t * z + z0 * z) + z1 * z != 0.0:  # NaN last: no clock yet
            return INVALID, math.nan
        if count > 0 and not 1e-100 <= var0 <= 1e100:
            return INVALID, math.nan
        if count > 1 and not 1e-100 <= var1 <= 1e100:
            return INVALID, math.nan
        meas = buf[BUF_MEAS : BUF_MEAS + 3]
        for k in range(N_COMP):
            meas[1, k] = 0.0
        if count > 0:
            meas[0, first] = z0
            meas[1, first] = var0
        if count > 1:
            meas[0, first + 1] = z1
            meas[1, first + 1] = var1
        state = buf[BUF_X : BUF_P + N_STATE]
        saved = buf[BUF_WORK + _SAVED : BUF_WORK + _SAVED + 1 + N_STATE]
        _copy_matrix(saved, state)
        buf[BUF_T, 1] = last
        buf[BUF_T, 0] = t
        dt = t - last
    else:
        dt = z0
    x = buf[BUF_X]
    p = buf[BUF_P : BUF_P + N_STATE]
    q = buf[BUF_Q : BUF_Q + N_STATE]
    meas = buf[BUF_MEAS : BUF_MEAS + 3]
    work = buf[BUF_WORK:]
    if dt != 0.0:
        v = x[3]
        w = x[4]
        acc = x[5]
        s = v * dt + 0.5 * acc * dt * dt
        half = 0.5 * w * dt
        mid = x[2] + half
        c = math.cos(mid)
        sn = math.sin(mid)
        # Composing from the mid-step heading with a half turn lands on theta + w*dt, wrapped.
        x[0], x[1], x[2] = compose_scalar(x[0], x[1], mid, s, 0.0, half)
        x[3] = v + acc * dt

        # F = I + E with E non-zero only in rows 0-3 and columns 2-5, so F P Fᵀ is done
        # sparsely: FP = P + E P (rows 0-3 change), then FP Fᵀ = FP + FP Eᵀ (columns 0-3).
        e = work[_E : _E + 4]
        e[:, :] = 0.0
        e[0, 2] = -sn * s
        e[0, 3] = c * dt
        e[0, 4] = -sn * s * 0.5 * dt
        e[0, 5] = c * 0.5 * dt * dt
        e[1, 2] = c * s
        e[1, 3] = sn * dt
        e[1, 4] = c * s * 0.5 * dt
        e[1, 5] = sn * 0.5 * dt * dt
        e[2, 4] = dt
        e[3, 5] = dt
        fp = work[_FP : _FP + N_STATE]
        _copy_matrix(fp, p)
        for i in range(4):
            for j in range(N_STATE):
                tmp = 0.0
                for k in range(2, N_STATE):
                    tmp += e[i, k] * p[k, j]
                fp[i, j] += tmp
        for i in range(N_STATE):
            for j in range(N_STATE):
                tmp = fp[i, j]
                if j < 4:
                    for k in range(2, N_STATE):
                        tmp += fp[i, k] * e[j, k]
                p[i, j] = tmp + q[i, j] * dt
        _symmetrize(p)
        if not _finite(x, p):
            return TIME_GAP, math.nan

    comp = work[_COMP].view(np.int64)
    y = work[_VEC]
    u = work[_VEC + 1]
    row = work[_VEC + 2]
    inv_diag = work[_VEC + 3]
    m = 0
    for k in range(N_COMP):
        if meas[1, k] > 0.0:
            comp[m] = k
            m += 1
    if m == 0:
        return ACCEPTED, 0.0
    for a in range(m):
        k = comp[a]
        y[a] = meas[0, k] - x[k + 2]
        if k + 2 == THETA:
            y[a] = wrap_scalar(y[a])
        meas[2, k] = y[a]
    chol = work[_CHOL : _CHOL + N_COMP]
    for a in range(m):
        for b in range(m):
            chol[a, b] = p[comp[a] + 2, comp[b] + 2]
        chol[a, a] += meas[1, comp[a]]
    if not _cholesky_inplace(chol, m, inv_diag):
        return NOT_POSITIVE_DEFINITE, math.nan
    for a in range(m):
        u[a] = y[a]
    _cho_solve_vec(chol, inv_diag, m, u)
    nis = 0.0
    for a in range(m):
        nis += y[a] * u[a]
    if not nis < math.inf:  # also NaN: an infinite residual
        return OVERFLOW, math.inf
    if nis > gate:
        return GATED, nis
    # K = P Hᵀ S⁻¹; S is symmetric, so each row of K solves S kᵢ = (P Hᵀ)ᵢ.
    gain = work[_GAIN : _GAIN + N_STATE]
    for i in range(N_STATE):
        for a in range(m):
            row[a] = p[i, comp[a] + 2]
        _cho_solve_vec(chol, inv_diag, m, row)
        for a in range(m):
            gain[i, a] = row[a]
    xn = work[_X]
    for i in range(N_STATE):
        tmp = x[i]
        for a in range(m):
            tmp += gain[i, a] * y[a]
        xn[i] = tmp
    xn[THETA] = wrap_scalar(xn[THETA])
    # Joseph form with H selecting the observed states: A = I - K H differs from I only in
    # those columns, so A P = P - K (H P) and (A P) Aᵀ = A P - (A P Hᵀ) Kᵀ; then + K R Kᵀ.
    ap = work[_FP : _FP + N_STATE]
    for i in range(N_STATE):
        for j in range(N_STATE):
            tmp = p[i, j]
            for a in range(m):
                tmp -= gain[i, a] * p[comp[a] + 2, j]
            ap[i, j] = tmp
    # The result is symmetric: compute the upper triangle and mirror it (exact symmetry).
    pn = work[_PN : _PN + N_STATE]
    for i in range(N_STATE):
        for j in range(i, N_STATE):
            t1 = ap[i, j]
            t2 = ap[j, i]
            for a in range(m):
                k = comp[a]
                rk = meas[1, k]
                t1 += (gain[i, a] * rk - ap[i, k + 2]) * gain[j, a]
                t2 += (gain[j, a] * rk - ap[j, k + 2]) * gain[i, a]
            tmp = 0.5 * (t1 + t2)
            pn[i, j] = tmp
            pn[j, i] = tmp
    # The state may overflow (then it is inf or NaN); the covariance is checked finite
    # by the Cholesky factorisation below.
    z = 0.0
    if ((xn[0] * z + xn[1] * z) + (xn[2] * z + xn[3] * z)) + (xn[4] * z + xn[5] * z) != 0.0:
        return OVERFLOW, nis
    check = work[_CHECK : _CHECK + N_STATE]
    _copy_matrix(check, pn)
    if not _cholesky_inplace(check, N_STATE, work[_VEC + 4]):
        return NOT_POSITIVE_DEFINITE, nis
    _copy_vector(x, xn)
    _copy_matrix(p, pn)
    return ACCEPTED, nis


@njit_no_refcount
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
) -> None:
    """Fuse a log into the filter in ``buf`` with :func:`planar_step` (in batch mode).

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
    """
    t = buf[BUF_T, 0]
    if math.isnan(t):  # no clock yet: it starts at the first row
        t = times[0]
    x = buf[BUF_X]
    p = buf[BUF_P : BUF_P + N_STATE]
    meas = buf[BUF_MEAS : BUF_MEAS + 3]
    # Batch mode of planar_step (count -1). Typed int64, not as literal constants: a literal
    # argument would compile planar_step a second time, for the literal values.
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
                meas[0, k] = values[i, k]
                meas[1, k] = variances[i, k]
                if variances[i, k] > 0.0:
                    m += 1
            status, nis = planar_step(buf, ti, first, batch, ti - t, 0.0, 0.0, 0.0, gates[m])
            if status == TIME_GAP:
                # Undo the prediction: back to the state after the previous row (for
                # row 0, index -1: the caller's copy of the initial state).
                _copy_vector(x, out_x[i - 1])
                _copy_matrix(p, out_p[i - 1])
            else:
                t = ti
            out_status[i] = status
            out_nis[i] = nis
        _copy_vector(out_x[i], x)
        _copy_matrix(out_p[i], p)
    buf[BUF_T, 0] = t


def undo_step(buf: np.ndarray) -> None:
    """Undo an online :func:`planar_step` that returned ``TIME_GAP`` or ``NOT_POSITIVE_DEFINITE``.

    Restores x, P and the filter time saved by the step (in NumPy: these
    outcomes are rare, and the public layer raises after them).

    Examples
    --------
    >>> buf = np.zeros((BUF_ROWS, 6))
    >>> buf[BUF_P : BUF_P + 6] = np.eye(6)
    >>> buf[BUF_T, 0] = 0.0
    >>> status, nis = planar_step_entry()(buf, 1e300, 0, 0, 0.0, 0.0, 0.0, 0.0, math.inf)
    >>> status == TIME_GAP, float(buf[BUF_T, 0])
    (True, 1e+300)
    >>> undo_step(buf)
    >>> float(buf[BUF_T, 0]), float(buf[BUF_P, 0])
    (0.0, 1.0)
    """
    saved = BUF_WORK + _SAVED
    np.copyto(buf[BUF_X : BUF_P + N_STATE], buf[saved : saved + 1 + N_STATE])
    buf[BUF_T, 0] = buf[BUF_T, 1]


def _step_types() -> tuple[Any, ...]:
    """numba argument types of :func:`planar_step`: the ones the public layer always passes.

    Argument types only, as :func:`planar_run` compiles it (also the key of the
    on-disk cache).
    """
    from numba.core import types

    return (
        types.Array(types.float64, 2, "C"),
        types.float64,  # t
        types.int64,  # first
        types.int64,  # count
        *(types.float64,) * 5,  # z0, z1, var0, var1, gate
    )


def planar_step_entry() -> Callable[..., tuple[int, float]]:
    """Compiled entry of :func:`planar_step`, skipping numba's per-call type dispatch.

    Calling a dispatcher first types all nine arguments to pick the compiled
    version (about 0.15 µs of a 1 µs call); the entry returned here is that
    version itself, compiled (or loaded from the cache) now. It checks no types:
    the caller passes the filter's buffer (a writable C-contiguous float64 array
    of shape (BUF_ROWS, 6)), Python floats for ``t``, the values, variances and
    gate and ints for ``first`` and ``count``.

    Examples
    --------
    >>> buf = np.zeros((BUF_ROWS, 6))
    >>> buf[BUF_P : BUF_P + 6] = np.eye(6)
    >>> buf[BUF_T, 0] = 0.0
    >>> status, nis = planar_step_entry()(buf, 0.1, 1, 1, 1.0, 0.0, 1.0, 1.0, math.inf)
    >>> status == ACCEPTED, round(nis, 3), float(buf[BUF_T, 0])
    (True, 0.5, 0.1)
    """
    dispatcher: Any = planar_step
    return cast(Callable[..., tuple[int, float]], dispatcher.compile(_step_types()))
