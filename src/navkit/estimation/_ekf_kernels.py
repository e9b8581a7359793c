"""numba kernels of navkit.estimation.ExtendedKalmanFilter, the general EKF (private).

The filter keeps everything a predict needs in one float64 ``state`` array of
shape ``(state_rows(n), n)`` (each array argument adds to a kernel call's cost):

* row ``STATE_X`` (0): the state x;
* rows ``STATE_P`` .. ``STATE_P + n - 1``: the covariance P;
* row ``n + 1``: 1.0 where a state component is an angle, else 0.0;
* rows ``n + 2`` .. ``3n + 1``: the process noise Q validated last time, as the
  caller passed it and symmetrised (NaN before the first predict);
* the rest: scratch space of :func:`ekf_predict`.

Each measurement size m has an ``rbuf`` (1-D, ``rbuf_size(n, m)``): the R
validated last time, as passed and symmetrised (NaN until then), then the
scratch space of :func:`ekf_update`.

The two kernels do one predict or one update each: they check what the public
layer did not (finiteness of the user's arrays; whether Q or R still equals the
matrix validated last time, else they return ``NOISE_CHANGED`` and the caller
validates it and calls again), compute the step into scratch space, make the new
covariance exactly symmetric, check it positive definite (a Cholesky
factorisation, which also fails on non-finite entries) and only then commit
it. Every outcome is a status code: the kernels never raise, never allocate
(they are compiled without reference counting, which alone took a tenth of a
call) and never leave ``state`` half-written. They are compiled for
C-contiguous float64 arrays (and an int64 index array) only: the public layer
passes nothing else. :func:`compile_kernels` compiles them ahead.
"""

from __future__ import annotations

import math

import numpy as np

from navkit._shared.jit import njit_inline_no_refcount, njit_no_refcount
from navkit._shared.se2 import wrap_scalar
from navkit._shared.types import FloatArray, IntArray
from navkit.estimation._fusion_kernels import _cho_solve_vec, _cholesky_inplace

__all__ = [
    "BAD_F",
    "BAD_FX",
    "BAD_H",
    "BAD_HX",
    "BAD_Z",
    "GATED",
    "NIS_OVERFLOW",
    "NOISE_CHANGED",
    "NOT_FINITE",
    "NOT_POSITIVE_DEFINITE",
    "OK",
    "RESIDUAL_OVERFLOW",
    "STATE_OVERFLOW",
    "STATE_P",
    "STATE_X",
    "S_NOT_FINITE",
    "S_NOT_POSITIVE_DEFINITE",
    "compile_kernels",
    "ekf_predict",
    "ekf_update",
    "new_rbuf",
    "new_state",
    "set_q",
    "set_r",
]

STATE_X = 0
STATE_P = 1

# Status codes shared with the public layer (one set for both kernels).
OK = 0
NOISE_CHANGED = 1  # Q or R differs from the validated copy: validate it, call again
BAD_F = 2  # F has a non-finite entry
BAD_FX = 3  # f(x) has a non-finite entry
BAD_Z = 4  # z has a non-finite entry
BAD_H = 5  # H has a non-finite entry
BAD_HX = 6  # h(x) has a non-finite entry
NOT_FINITE = 7  # the new covariance is not finite
NOT_POSITIVE_DEFINITE = 8  # the new covariance is not positive definite
S_NOT_FINITE = 9  # the innovation covariance is not finite
S_NOT_POSITIVE_DEFINITE = 10  # the innovation covariance is not positive definite
RESIDUAL_OVERFLOW = 11  # z - h(x) overflowed
NIS_OVERFLOW = 12  # the NIS overflowed
GATED = 13  # NIS above the gate
STATE_OVERFLOW = 14  # the updated state overflowed


def new_state(x: FloatArray, p: FloatArray, angles: tuple[int, ...]) -> FloatArray:
    """The ``state`` array of a filter at ``x`` (n,) with covariance ``p`` (n, n).

    ``x`` must already be wrapped; ``angles`` are the angle components.
    """
    n = x.shape[0]
    state = np.zeros((6 * n + 3, n))
    state[STATE_X] = x
    state[STATE_P : STATE_P + n] = p
    state[n + 1, list(angles)] = 1.0
    state[n + 2 : 3 * n + 2] = math.nan
    return state


def set_q(state: FloatArray, q: FloatArray, q_sym: FloatArray) -> None:
    """Store a validated Q: as passed (``q``) and symmetrised (``q_sym``)."""
    n = state.shape[1]
    state[n + 2 : 2 * n + 2] = q
    state[2 * n + 2 : 3 * n + 2] = q_sym


def new_rbuf(n: int, m: int) -> FloatArray:
    """The R-and-scratch buffer of ``m``-dimensional measurements (no R validated yet)."""
    big = max(n, m)
    rbuf = np.empty(3 * n * n + 3 * n * m + 4 * m * m + 2 * big + 2 * n)
    rbuf[: 2 * m * m] = math.nan
    return rbuf


def set_r(rbuf: FloatArray, r: FloatArray, r_sym: FloatArray) -> None:
    """Store a validated R: as passed (``r``) and symmetrised (``r_sym``)."""
    mm = r.size
    rbuf[:mm] = r.ravel()
    rbuf[mm : 2 * mm] = r_sym.ravel()


@njit_inline_no_refcount
def _finite_vec(v: FloatArray) -> bool:
    """Whether every entry of the 1-D ``v`` is finite (``a - a`` is 0 only when ``a`` is)."""
    for i in range(v.shape[0]):  # noqa: SIM110 - numba compiles no generator into all()
        if v[i] - v[i] != 0.0:
            return False
    return True


@njit_inline_no_refcount
def _finite_mat(a: FloatArray) -> bool:
    """Whether every entry of the 2-D ``a`` is finite."""
    for i in range(a.shape[0]):
        for j in range(a.shape[1]):
            if a[i, j] - a[i, j] != 0.0:
                return False
    return True


@njit_inline_no_refcount
def _equal(a: FloatArray, b: FloatArray) -> bool:
    """Whether the 2-D ``a`` and ``b`` hold equal values (NaN is never equal)."""
    for i in range(a.shape[0]):
        for j in range(a.shape[1]):
            if a[i, j] != b[i, j]:
                return False
    return True


@njit_no_refcount
def _mul(a: FloatArray, b: FloatArray, out: FloatArray) -> None:
    """``out = a @ b``, skipping the zeros of ``a``.

    Loop order i, k, j: each ``out[i, j]`` still sums its products in k order
    (the order of a plain dot product), but the j loop runs independent sums
    side by side instead of one chain of dependent additions. A zero ``a[i, k]``
    adds exact zeros (``b`` is finite wherever this is used), so it is skipped:
    Jacobians and I - K H are mostly zeros.
    """
    rows, inner, cols = a.shape[0], a.shape[1], b.shape[1]
    for i in range(rows):
        for j in range(cols):
            out[i, j] = 0.0
        for k in range(inner):
            aik = a[i, k]
            if aik != 0.0:
                for j in range(cols):
                    out[i, j] += aik * b[k, j]


@njit_no_refcount
def _mul_t_lower(a: FloatArray, b: FloatArray, out: FloatArray) -> None:
    """The lower triangle (j <= i) of ``out = a @ b.T``, skipping the zeros of ``a``.

    For a symmetric product such as ``A P Aᵀ = A (A P)ᵀ`` (P symmetric): the
    upper triangle is its mirror image.
    """
    rows, inner = a.shape[0], a.shape[1]
    for i in range(rows):
        for j in range(i + 1):
            out[i, j] = 0.0
        for k in range(inner):
            aik = a[i, k]
            if aik != 0.0:
                for j in range(i + 1):
                    out[i, j] += aik * b[j, k]


@njit_inline_no_refcount
def _add_lower(p: FloatArray, q: FloatArray) -> None:
    """``p += q`` on the lower triangle (j <= i)."""
    for i in range(p.shape[0]):
        for j in range(i + 1):
            p[i, j] += q[i, j]


@njit_no_refcount
def _mirror_checked(p: FloatArray, chol: FloatArray, inv_diag: FloatArray) -> int:
    """Copy the lower triangle of ``p`` to the upper one and check ``p``.

    Returns OK, NOT_FINITE or NOT_POSITIVE_DEFINITE. ``chol`` receives the
    Cholesky factor in its lower triangle (and 1 / its diagonal ``inv_diag``).
    The factorisation fails on any non-finite entry, so the finiteness scan runs
    only then, to tell the two failures apart.
    """
    n = p.shape[0]
    for i in range(n):
        for j in range(i + 1):
            v = p[i, j]
            p[j, i] = v
            chol[i, j] = v
    if _cholesky_inplace(chol, n, inv_diag):
        return OK
    return NOT_POSITIVE_DEFINITE if _finite_mat(p) else NOT_FINITE


@njit_no_refcount
def ekf_predict(state: FloatArray, x_new: FloatArray, jac: FloatArray, q: FloatArray) -> int:
    """x ← wrap(f(x)), P ← F P Fᵀ + Q in ``state``, or a status code leaving x and P unchanged.

    ``x_new`` (n,) is f(x), ``jac`` (n, n) the Jacobian F, ``q`` (n, n) the
    caller's Q (shapes checked by the caller). Returns ``BAD_F``,
    ``NOISE_CHANGED`` or ``BAD_FX`` (checked in this order) before computing
    anything, then ``NOT_FINITE`` or ``NOT_POSITIVE_DEFINITE`` for the predicted
    covariance, else ``OK``.
    """
    n = x_new.shape[0]
    if not _finite_mat(jac):
        return BAD_F
    if not _equal(q, state[n + 2 : 2 * n + 2]):
        return NOISE_CHANGED
    if not _finite_vec(x_new):
        return BAD_FX
    p = state[STATE_P : STATE_P + n]
    qs = state[2 * n + 2 : 3 * n + 2]
    fp = state[3 * n + 2 : 4 * n + 2]
    pn = state[4 * n + 2 : 5 * n + 2]
    chol = state[5 * n + 2 : 6 * n + 2]
    inv_diag = state[6 * n + 2]
    # F P Fᵀ = F (F P)ᵀ, P being symmetric: both products skip the zeros of F.
    _mul(jac, p, fp)
    _mul_t_lower(jac, fp, pn)
    _add_lower(pn, qs)
    status = _mirror_checked(pn, chol, inv_diag)
    if status != OK:
        return status
    angle = state[n + 1]
    for i in range(n):
        state[STATE_X, i] = wrap_scalar(x_new[i]) if angle[i] != 0.0 else x_new[i]
        for j in range(n):
            p[i, j] = pn[i, j]
    return OK


@njit_no_refcount
def ekf_update(
    state: FloatArray,
    z: FloatArray,
    hx: FloatArray,
    jac: FloatArray,
    r: FloatArray,
    rbuf: FloatArray,
    angles: IntArray,
    gate: float,
    y: FloatArray,
) -> tuple[int, float]:
    """Joseph-form measurement update of ``state``; returns ``(status, nis)``.

    ``z`` and ``hx`` (m,) are the measurement and h(x), ``jac`` (m, n) the
    Jacobian H, ``r`` (m, m) the caller's R, ``rbuf`` the buffer of this m
    (:func:`new_rbuf`), ``angles`` the indices of the angle components of ``z``,
    ``gate`` the NIS threshold (inf for none). The residual is written to ``y``
    (m,). Checks, in order: ``BAD_Z``, ``BAD_H``, ``NOISE_CHANGED``, ``BAD_HX``;
    then S = H P Hᵀ + R (``S_NOT_FINITE``, ``S_NOT_POSITIVE_DEFINITE``), the
    residual (``RESIDUAL_OVERFLOW``), the NIS yᵀ S⁻¹ y (``NIS_OVERFLOW``,
    ``GATED``), the updated state (``STATE_OVERFLOW``) and the updated
    covariance (``NOT_FINITE``, ``NOT_POSITIVE_DEFINITE``). x and P change only
    with ``OK``; ``nis`` is NaN until computed, inf when it overflowed.
    """
    n = state.shape[1]
    m = z.shape[0]
    nn = n * n
    nm = n * m
    mm = m * m
    big = max(n, m)
    if not _finite_vec(z):
        return BAD_Z, math.nan
    if not _finite_mat(jac):
        return BAD_H, math.nan
    if not _equal(r, rbuf[:mm].reshape((m, m))):
        return NOISE_CHANGED, math.nan
    if not _finite_vec(hx):
        return BAD_HX, math.nan
    rs = rbuf[mm : 2 * mm].reshape((m, m))
    x = state[STATE_X]
    p = state[STATE_P : STATE_P + n]
    for i in range(m):
        y[i] = z[i] - hx[i]
    for k in range(angles.shape[0]):
        a = y[angles[k]]
        if a - a == 0.0:  # an overflowed residual stays as it is
            y[angles[k]] = wrap_scalar(a)

    # Scratch, cut into C-contiguous blocks (reshaped 1-D slices keep numba's C
    # layout, which 2-D slices of a wider array would not).
    o = 2 * mm
    hp = rbuf[o : o + nm].reshape((m, n))  # H P = (P Hᵀ)ᵀ
    o += nm
    s = rbuf[o : o + mm].reshape((m, m))  # S
    o += mm
    chol = rbuf[o : o + mm].reshape((m, m))
    o += mm
    gain = rbuf[o : o + nm].reshape((n, m))  # K
    o += nm
    kr = rbuf[o : o + nm].reshape((n, m))  # K R
    o += nm
    ikh = rbuf[o : o + nn].reshape((n, n))  # I - K H
    o += nn
    tmp = rbuf[o : o + nn].reshape((n, n))  # (I - K H) P, then K R Kᵀ
    o += nn
    pn = rbuf[o : o + nn].reshape((n, n))
    o += nn
    inv_diag = rbuf[o : o + big]
    o += big
    u = rbuf[o : o + big]  # a solve vector
    o += big
    xn = rbuf[o : o + n]  # the new state

    _mul(jac, p, hp)
    _mul_t_lower(jac, hp, s)  # H P Hᵀ
    _add_lower(s, rs)
    status = _mirror_checked(s, chol, inv_diag)
    if status == NOT_FINITE:
        return S_NOT_FINITE, math.nan
    if status == NOT_POSITIVE_DEFINITE:
        return S_NOT_POSITIVE_DEFINITE, math.nan

    if not _finite_vec(y):
        return RESIDUAL_OVERFLOW, math.inf
    # NIS = |L⁻¹ y|² (never negative), by forward substitution.
    nis = 0.0
    for i in range(m):
        t = y[i]
        for k in range(i):
            t -= chol[i, k] * u[k]
        u[i] = t * inv_diag[i]
        nis += u[i] * u[i]
    if not nis < math.inf:
        return NIS_OVERFLOW, math.inf
    if nis > gate:
        return GATED, nis

    # K = P Hᵀ S⁻¹: row i of K solves S kᵢ = (P Hᵀ)ᵢ = (H P)ᵀᵢ (S is symmetric).
    for i in range(n):
        for j in range(m):
            u[j] = hp[j, i]
        _cho_solve_vec(chol, inv_diag, m, u)
        for j in range(m):
            gain[i, j] = u[j]
    angle = state[n + 1]
    for i in range(n):
        acc = 0.0
        for j in range(m):
            acc += gain[i, j] * y[j]
        v = x[i] + acc
        xn[i] = wrap_scalar(v) if angle[i] != 0.0 and v - v == 0.0 else v
    if not _finite_vec(xn):
        return STATE_OVERFLOW, nis

    # Joseph form: P ← (I - K H) P (I - K H)ᵀ + K R Kᵀ.
    _mul(gain, jac, ikh)
    for i in range(n):
        for j in range(n):
            ikh[i, j] = -ikh[i, j]
        ikh[i, i] += 1.0
    # (I - K H) P (I - K H)ᵀ = A (A P)ᵀ with A = I - K H, P being symmetric.
    _mul(ikh, p, tmp)
    _mul_t_lower(ikh, tmp, pn)
    _mul(gain, rs, kr)
    _mul_t_lower(kr, gain, tmp)
    _add_lower(pn, tmp)
    status = _mirror_checked(pn, ikh, inv_diag)
    if status != OK:
        return status, nis
    for i in range(n):
        x[i] = xn[i]
        for j in range(n):
            p[i, j] = pn[i, j]
    return OK, nis


def compile_kernels() -> None:
    """Compile (or load from numba's cache) both kernels for the types the filter passes.

    The filter only ever passes C-contiguous, writeable float64 arrays (and a
    C-contiguous int64 index array), so these are the only specialisations.
    """
    x = np.zeros(1)
    one = np.ones((1, 1))
    state = new_state(x, one, ())
    set_q(state, one, one)
    ekf_predict(state, x, one, one)
    rbuf = new_rbuf(1, 1)
    set_r(rbuf, one, one)
    ekf_update(state, x, x, one, one, rbuf, np.zeros(0, dtype=np.int64), math.inf, np.empty(1))
