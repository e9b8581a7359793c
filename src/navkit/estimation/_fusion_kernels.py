"""numba kernels of the planar odometry + IMU filter, navkit.estimation.PlanarFusion (private).

State layout (6,): ``[x, y, theta, v, omega, a]`` — world position (m), heading
(rad, wrapped to (-pi, pi]), forward speed (m/s), yaw rate (rad/s) and forward
acceleration (m/s^2). Measurements use the "component" layout (4,):
``[theta, v, omega, a]`` (the observation vector [θ, ẋ, θ̇, ẍ]); component ``k``
observes state ``k + 2``, so every measurement model is linear.

The kernels never allocate: scratch space is a caller-owned ``work`` array of
shape ``(WORK_ROWS, 6)``, because at this size heap
allocations would cost more than the arithmetic. The public layer
(:mod:`navkit.estimation._fusion`) validates input; these kernels assume finite,
well-shaped arrays and never raise. They never return a non-finite state either:
a prediction that would overflow float64 (a huge time gap) is undone
(``TIME_GAP``), and an update that would overflow (a measurement absurdly far
from the state for its variance) is not applied (``OVERFLOW``).
"""

from __future__ import annotations

import math

import numpy as np

from navkit._shared.jit import njit_cached, njit_inline
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
WORK_ROWS = 45

# Rows of the online filter buffer of :func:`planar_step`: everything in one array,
# because numba's per-call dispatch cost grows with every array argument.
BUF_X = 0  # 1 row: state x
BUF_P = 1  # 6 rows: covariance P
BUF_Q = 7  # 6 rows: process noise per second Q
BUF_MEAS = 13  # 3 rows: values, variances, residuals (columns 0-3, component layout)
BUF_WORK = 16  # WORK_ROWS rows: scratch
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
def _symmetrize(p: np.ndarray) -> None:
    for i in range(p.shape[0]):
        for j in range(i + 1, p.shape[0]):
            m = 0.5 * (p[i, j] + p[j, i])
            p[i, j] = m
            p[j, i] = m


@njit_inline
def planar_predict(
    x: np.ndarray, p: np.ndarray, q: np.ndarray, dt: float, work: np.ndarray
) -> None:
    """Propagate state ``x`` (6,) and covariance ``p`` (6, 6) by ``dt`` >= 0 s, in place.

    Constant-acceleration unicycle: the distance s = v·dt + a·dt²/2 is travelled
    along the mid-step heading θ + ω·dt/2 (second order in dt), then
    θ += ω·dt, v += a·dt; ω and a are random walks. ``q`` (6, 6) is the process
    noise per second, so P = F P Fᵀ + Q·dt.
    """
    if dt == 0.0:
        return
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
    fp[:, :] = p
    for i in range(4):
        for j in range(N_STATE):
            t = 0.0
            for k in range(2, N_STATE):
                t += e[i, k] * p[k, j]
            fp[i, j] += t
    for i in range(N_STATE):
        for j in range(N_STATE):
            t = fp[i, j]
            if j < 4:
                for k in range(2, N_STATE):
                    t += fp[i, k] * e[j, k]
            p[i, j] = t + q[i, j] * dt
    _symmetrize(p)


@njit_inline
def planar_update(
    x: np.ndarray, p: np.ndarray, meas: np.ndarray, gate: float, work: np.ndarray, comp: np.ndarray
) -> tuple[int, float]:
    """Kalman update with one measurement, in place.

    ``meas`` (3, 4) packs the measurement in component layout: row 0 the values
    ``z``, row 1 the noise variances (> 0 for the observed components, 0 for the
    others; the noise is independent between components), row 2 receives the
    residuals of the observed components (others untouched). The yaw residual
    is wrapped. The covariance uses the Joseph form
    P = (I - KH) P (I - KH)ᵀ + K R Kᵀ, then is symmetrised and checked positive
    definite. Returns ``(status, nis)``; ``x`` and ``p`` change only when the
    status is ``ACCEPTED``. ``comp`` (4,) int64 is scratch space for the indices
    of the observed components (allocated once by the batch loop). ``OVERFLOW``
    (with ``nis`` inf when the NIS itself overflowed) means the residual, the NIS
    or the updated state is not finite.
    """
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
        t = x[i]
        for a in range(m):
            t += gain[i, a] * y[a]
        xn[i] = t
    xn[THETA] = wrap_scalar(xn[THETA])
    # Joseph form with H selecting the observed states: A = I - K H differs from I only in
    # those columns, so A P = P - K (H P) and (A P) Aᵀ = A P - (A P Hᵀ) Kᵀ; then + K R Kᵀ.
    ap = work[_FP : _FP + N_STATE]
    for i in range(N_STATE):
        for j in range(N_STATE):
            t = p[i, j]
            for a in range(m):
                t -= gain[i, a] * p[comp[a] + 2, j]
            ap[i, j] = t
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
            t = 0.5 * (t1 + t2)
            pn[i, j] = t
            pn[j, i] = t
    # The state may overflow (then it is inf or NaN); the covariance is checked finite
    # by the Cholesky factorisation below.
    z = 0.0
    if ((xn[0] * z + xn[1] * z) + (xn[2] * z + xn[3] * z)) + (xn[4] * z + xn[5] * z) != 0.0:
        return OVERFLOW, nis
    check = work[_CHECK : _CHECK + N_STATE]
    check[:, :] = pn
    if not _cholesky_inplace(check, N_STATE, work[_VEC + 4]):
        return NOT_POSITIVE_DEFINITE, nis
    x[:] = xn
    p[:, :] = pn
    return ACCEPTED, nis


@njit_cached
def planar_step(
    buf: np.ndarray,
    dt: float,
    first: int,
    count: int,
    z0: float,
    z1: float,
    var0: float,
    var1: float,
    gate: float,
) -> tuple[int, float]:
    """Predict by ``dt`` then update with one measurement (see :func:`planar_update`).

    ``buf`` (BUF_ROWS, 6) holds x, P, Q, the measurement and the scratch space
    (layout ``BUF_*`` above). The measurement observes ``count`` (1 or 2)
    consecutive components starting at ``first``, with values ``z0``, ``z1`` and
    variances ``var0``, ``var1`` (the second ones unused when ``count`` is 1);
    passing scalars is cheaper than writing them into ``buf`` from Python. x and
    P are overwritten with the result unless the status is
    ``NOT_POSITIVE_DEFINITE`` or ``TIME_GAP`` (the prediction over ``dt``
    overflowed; no update was tried): then they are restored. A gated or
    overflowing measurement keeps the prediction. The residuals are left in the
    measurement block.
    """
    meas = buf[BUF_MEAS : BUF_MEAS + 3]
    for k in range(N_COMP):
        meas[1, k] = 0.0
    meas[0, first] = z0
    meas[1, first] = var0
    if count == 2:
        meas[0, first + 1] = z1
        meas[1, first + 1] = var1
    work = buf[BUF_WORK:]
    state = buf[BUF_X : BUF_P + N_STATE]
    saved = work[_SAVED : _SAVED + 1 + N_STATE]
    saved[:, :] = state
    x = buf[BUF_X]
    p = buf[BUF_P : BUF_P + N_STATE]
    planar_predict(x, p, buf[BUF_Q : BUF_Q + N_STATE], dt, work)
    if not _finite(x, p):
        state[:, :] = saved
        return TIME_GAP, math.nan
    status, nis = planar_update(x, p, meas, gate, work, np.empty(N_COMP, dtype=np.int64))
    if status == NOT_POSITIVE_DEFINITE:
        state[:, :] = saved
    return status, nis


@njit_cached
def planar_run(
    x: np.ndarray,
    p: np.ndarray,
    t0: float,
    times: np.ndarray,
    values: np.ndarray,
    variances: np.ndarray,
    q: np.ndarray,
    gates: np.ndarray,
    out_x: np.ndarray,
    out_p: np.ndarray,
    out_status: np.ndarray,
    out_nis: np.ndarray,
) -> float:
    """Fuse a log; returns the filter time after the last row.

    Row ``i`` is a measurement at ``times[i]`` with values ``values[i]`` (4,) and
    independent variances ``variances[i]`` (4,), 0 marking components it does
    not observe. ``gates[m]`` is the NIS threshold for an m-component
    measurement (``inf`` disables gating). ``x`` (6,) and ``p`` (6, 6) are
    updated in place; the state after each row goes to ``out_x[i]``,
    ``out_p[i]``. Rows older than the filter time are not applied
    (``OUT_OF_ORDER``); nor are rows whose prediction would overflow
    (``TIME_GAP``: the state and time stay as they were). A row whose update
    fails numerically keeps the prediction and is marked
    ``NOT_POSITIVE_DEFINITE`` or ``OVERFLOW``.

    The caller stores the initial ``x`` and ``p`` in ``out_x[-1]`` and
    ``out_p[-1]`` too: a ``TIME_GAP`` in row 0 restores them from there (a copy
    made here would slow the loop down measurably).
    """
    t = t0
    meas = np.zeros((3, N_COMP))
    work = np.zeros((WORK_ROWS, N_STATE))
    comp = np.empty(N_COMP, dtype=np.int64)
    for i in range(times.shape[0]):
        ti = times[i]
        if ti < t:
            out_status[i] = OUT_OF_ORDER
            out_nis[i] = math.nan
        else:
            planar_predict(x, p, q, ti - t, work)
            if not _finite(x, p):
                # Undo the prediction: back to the state after the previous row (for
                # row 0, index -1: the caller's copy of the initial state).
                x[:] = out_x[i - 1]
                p[:, :] = out_p[i - 1]
                out_status[i] = TIME_GAP
                out_nis[i] = math.nan
                out_x[i, :] = x
                out_p[i, :, :] = p
                continue
            t = ti
            m = 0
            for k in range(N_COMP):
                meas[0, k] = values[i, k]
                meas[1, k] = variances[i, k]
                if variances[i, k] > 0.0:
                    m += 1
            status, nis = planar_update(x, p, meas, gates[m], work, comp)
            out_status[i] = status
            out_nis[i] = nis
        out_x[i, :] = x
        out_p[i, :, :] = p
    return t
