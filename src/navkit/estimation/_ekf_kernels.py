"""numba kernels of navkit.estimation.ExtendedKalmanFilter, the general EKF (private).

The filter keeps everything a predict needs in one float64 ``state`` array of
shape ``(6n + 3, n)`` (each array argument adds to a kernel call's cost):

* row ``STATE_X`` (0): the state x;
* rows ``STATE_P`` .. ``STATE_P + n - 1``: the covariance P;
* row ``n + 1``: 1.0 where a state component is an angle, else 0.0;
* rows ``n + 2`` .. ``3n + 1``: the process noise Q validated last time, as the
  caller passed it and symmetrised (NaN before the first predict);
* the rest: scratch space of the predict kernel.

Each measurement size m has an ``rbuf`` (:func:`new_rbuf`), a stack of
``(rows, max(n, m, 2))`` float64 blocks (``rbuf[k]`` is a C-contiguous 2-D
array, which slicing a flat buffer and reshaping it would cost a library call
each): the R validated last time, as passed and symmetrised (NaN until then),
and the scratch space of the update kernel. Matrices use the top-left corner
of their block.

The kernels are made per state dimension n (:func:`predict_kernel`) and per
pair (n, m) (:func:`update_kernel`), with n and m compile-time constants: at
these sizes (a few states) loop overhead, not arithmetic, is the cost, and
constant trip counts let LLVM unroll the loops (2-3 times faster kernels than
with run-time sizes). numba caches each on disk (the closure's constants are
part of the cache key). Each kernel is a thin shell: its shape checks, then a
call of :func:`_predict` or :func:`_update`, which hold the work. Those and
the small helpers they call take the sizes as plain int64 arguments, so that
numba types and compiles each of them once for every size (the kernels pass
them ``np.int64`` constants, not Python ints, which numba would take as
literal types and compile once per value: issue 17), and LLVM inlines them
into each kernel (``njit_force_inline``), where the sizes are constants again
and the loops unroll as before. A new size thus costs the compilation of a
shell, not of the whole update. (numba's IR inlining instead re-typed each
body at every call site, a third more compile time.)

Each kernel does one predict or one update. It checks what the public layer
did not: the shapes (``BAD_SHAPE``: the caller then converts and checks its
arguments in full, or picks the kernel of another measurement size), the
finiteness of the user's arrays, and whether Q or R still equals the matrix
validated last time or is plainly valid, which it then keeps as validated
(:func:`_adopt_dominant`: diagonally dominant, e.g. a diagonal ``Q_c dt``); else
``NOISE_CHANGED``: the caller validates it and calls again. Then it computes
the step into scratch space, makes the new covariance exactly symmetric,
checks it positive definite (an LDLᵀ factorisation, which also fails on
non-finite entries) and only then commits it. Every outcome is a status
code: the kernels never raise, never allocate (they are compiled without
reference counting, which alone took a tenth of a call) and never leave
``state`` half-written.

An update whose Joseph form cancelled (a variance shrank more than 4096-fold:
a measurement far more precise than the estimate) commits nothing and returns
``CANCELLED``; the public layer finishes it with :func:`finish_cancelled`,
which may take the information form instead (in NumPy: the case is rare, and
compiled into every update kernel it would cost compile time).

They are compiled for C-contiguous, writeable, aligned float64 arrays only,
when first requested, after which their dispatchers compile nothing more: an
argument of any other type raises at dispatch, which the public layer takes as
"convert this argument and check it in full". Its fast path therefore needs no
type checks of its own.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, cast

import numpy as np

from navkit._shared.angles import wrap_float
from navkit._shared.jit import njit_force_inline, njit_no_refcount
from navkit._shared.se2 import wrap_scalar
from navkit._shared.types import FloatArray, IntArray

__all__ = [
    "BAD_F",
    "BAD_FX",
    "BAD_H",
    "BAD_HX",
    "BAD_SHAPE",
    "BAD_TYPE",
    "BAD_Z",
    "CANCELLED",
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
    "PredictKernel",
    "UpdateKernel",
    "compile_kernels",
    "finish_cancelled",
    "new_rbuf",
    "new_state",
    "predict_kernel",
    "rbuf_gate",
    "rbuf_nis",
    "set_nis",
    "set_options",
    "set_q",
    "set_r",
    "update_kernel",
]

STATE_X = 0
STATE_P = 1

_SMALLEST_NORMAL = 2.2250738585072014e-308  # sys.float_info.min
_EPS = 2.0**-53  # the unit roundoff of float64

# A kernel takes the public layer's arguments as they come: its dispatcher checks
# their types (and raises on any other than the compiled ones).
PredictKernel = Callable[..., int]  # (state, f(x), F, Q) -> status
UpdateKernel = Callable[..., float]  # (state, z, h(x), H, R, rbuf, y) -> NIS|-status

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
BAD_SHAPE = 15  # an argument's shape does not fit (or rbuf is another m's): check in full
BAD_TYPE = 16  # set by the public layer: an argument is not of the compiled type
CANCELLED = 17  # the Joseph form cancelled (a variance shrank > 4096-fold): finish_cancelled

# What ekf_update returns for a status other than OK: -status.
_FAIL_SHAPE = -float(BAD_SHAPE)
_FAIL_Z = -float(BAD_Z)
_FAIL_H = -float(BAD_H)
_FAIL_NOISE = -float(NOISE_CHANGED)
_FAIL_HX = -float(BAD_HX)
_FAIL_S_NOT_FINITE = -float(S_NOT_FINITE)
_FAIL_S_NOT_POSITIVE_DEFINITE = -float(S_NOT_POSITIVE_DEFINITE)
_FAIL_RESIDUAL = -float(RESIDUAL_OVERFLOW)
_FAIL_NIS = -float(NIS_OVERFLOW)
_FAIL_GATED = -float(GATED)
_FAIL_STATE = -float(STATE_OVERFLOW)
_FAIL_CANCELLED = -float(CANCELLED)

# The Joseph form's error in a posterior entry is about ε P (ε = 2⁻⁵³) where the exact
# entry is P⁺: relative to the posterior, at most about ε max(Pᵢᵢ / P⁺ᵢᵢ) (measured:
# 1.4e-16 times that ratio). Below this ratio it stays under 1e-12 relative (12 bits
# lost at most) and is kept; above it (a measurement far more precise than the
# estimate) finish_cancelled computes the posterior without the cancellation.
_SHRINK_LIMIT = 4096.0
# finish_cancelled trusts the information form only where ε times its error estimate
# is at most this (12 bits short of full precision): a bound, not noise.
_WELL_CONDITIONED = 2.0**-12
# The kernel's state, x + K y with K solved with S, is within about ε κ(S) of its
# scale: trusted when that is at most this (about 1e-9).
_STATE_TRUSTED = 2.0**-30
# An information form this accurate (times ε) is kept where the Joseph form's bound
# is larger: at most 4 times it off, 1e-12, never 10 times worse than the Joseph form.
_ACCURATE = 2.0**-42

# Blocks of an rbuf.
_R = 0  # R as passed
_RS = 1  # R symmetrised
_HP = 2  # H P (m x n)
_CHOL = 3  # the unit lower triangular L of S = L D Lᵀ (m x m)
_GAIN = 4  # K (n x m)
_KR = 5  # K R - (I - K H) P Hᵀ (n x m)
_PCHK = 6  # the LDLᵀ factor of the new P (n x n)
_TMP = 7  # (I - K H) P (n x n)
_PN = 8  # the new P (n x n)
_VEC = 9  # rows: 1 / diag(L), a solve vector, the new state, [status, NIS, gate], angle flags
_S = 10  # S (m x m)
_BLOCKS = 11
_INV_DIAG = 0
_U = 1
_XN = 2
_META = 3
_ANGLE = 4  # 1.0 where a measurement component is an angle, else 0.0
_JOSEPH = 0  # column of _META: with CANCELLED, the status of the Joseph-form P in _PN
_GATE = 2  # column of _META: the NIS threshold (inf: none)


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


def set_nis(rbuf: FloatArray, nis: float) -> None:
    """Leave ``nis`` in ``rbuf`` as the update kernel does with a status other than OK."""
    rbuf[_VEC, _META, 1] = nis


def rbuf_nis(rbuf: FloatArray) -> float:
    """The NIS the update kernel left in ``rbuf`` (with a status other than OK)."""
    return float(rbuf[_VEC, _META, 1])


def rbuf_gate(rbuf: FloatArray) -> float:
    """The NIS gate held in ``rbuf`` (inf: none)."""
    return float(rbuf[_VEC, _META, _GATE])


def new_rbuf(n: int, m: int) -> FloatArray:
    """The R-and-scratch buffer of ``m``-dimensional measurements (no R validated yet)."""
    big = max(n, m)
    rbuf = np.zeros((_BLOCKS, max(big, _ANGLE + 1), max(big, _GATE + 1)))
    rbuf[_R] = math.nan
    rbuf[_RS] = math.nan
    rbuf[_VEC, _META, _GATE] = math.inf  # no gate and (all flags 0) no angles
    return rbuf


def set_options(rbuf: FloatArray, angles: IntArray, gate: float) -> None:
    """Store the update options: ``angles`` the (valid) angle indices of z, ``gate`` (inf: none)."""
    flags = rbuf[_VEC, _ANGLE]
    flags[:] = 0.0
    flags[angles] = 1.0
    rbuf[_VEC, _META, _GATE] = gate


def set_r(rbuf: FloatArray, r: FloatArray, r_sym: FloatArray) -> None:
    """Store a validated R: as passed (``r``) and symmetrised (``r_sym``)."""
    m = r.shape[0]
    rbuf[_R, :m, :m] = r
    rbuf[_RS, :m, :m] = r_sym


@njit_force_inline
def _wrap(a: float) -> float:
    """:func:`~navkit._shared.se2.wrap_scalar` typed once for every kernel.

    numba inlines ``wrap_scalar``'s code into each caller it types; behind this
    call that is done once, not once per kernel size.
    """
    return wrap_scalar(a)


@njit_force_inline
def _finite_mat(a: FloatArray, rows: int, cols: int) -> bool:
    """Whether the top-left ``rows`` x ``cols`` block of ``a`` is finite."""
    for i in range(rows):
        for j in range(cols):
            if a[i, j] - a[i, j] != 0.0:
                return False
    return True


@njit_force_inline
def _equal(a: FloatArray, b: FloatArray, n: int) -> bool:
    """Whether the n x n ``a`` equals the top-left n x n block of ``b`` (NaN never does)."""
    for i in range(n):
        for j in range(n):
            if a[i, j] != b[i, j]:
                return False
    return True


@njit_force_inline
def _adopt_dominant(
    a: FloatArray, kept: FloatArray, kept_sym: FloatArray, n: int, factor: float, floor: float
) -> bool:
    """Store the n x n noise ``a`` as validated if it is plainly valid; whether it was.

    Plainly valid: finite, exactly symmetric, entries of magnitude at most 1e100,
    and each diagonal entry at least ``floor`` and ``factor`` times the sum of the
    magnitudes of the rest of its row. Q passes ``factor`` 1 and ``floor`` 0
    (Gershgorin: positive semi-definite), R ``factor`` 2 and ``floor`` 1e-300
    (the LDLᵀ pivots of a diagonally dominant matrix are at least its rows'
    margins, here half the diagonal: positive definite with normal pivots).
    The public layer's full check (``navkit.estimation._covariance.covariance``)
    accepts every such matrix, and this stores what it would store: ``a`` as
    passed and ``0.5 a + 0.5 aᵀ``. A Q or R that changes every step
    (``Q = Q_c dt`` with a varying ``dt``, a sensor's per-message covariance)
    thus costs no Python check; anything else is left to that check
    (``NOISE_CHANGED``). (Floats, not a bool: numba would compile a literal bool
    once per value.)
    """
    for i in range(n):
        d = a[i, i]
        if not floor <= d <= 1e100:  # NaN fails too
            return False
        off = 0.0
        for j in range(n):
            if j != i:
                v = a[i, j]
                if v != a[j, i] or not abs(v) <= 1e100:
                    return False
                off += abs(v)
        if not factor * off <= d:
            return False
    for i in range(n):
        for j in range(n):
            kept[i, j] = a[i, j]
            kept_sym[i, j] = 0.5 * a[i, j] + 0.5 * a[j, i]
    return True


@njit_force_inline
def _mul(a: FloatArray, b: FloatArray, out: FloatArray, rows: int, inner: int, cols: int) -> None:
    """``out = a @ b`` on the leading blocks (``rows`` x ``inner`` times ``inner`` x ``cols``).

    Loop order i, k, j: each ``out[i, j]`` still sums its products in k order
    (the order of a plain dot product), but the j loop runs independent sums
    side by side instead of one chain of dependent additions. A zero ``a[i, k]``
    adds exact zeros (``b`` is finite wherever this is used), so it is skipped:
    Jacobians and I - K H are mostly zeros.
    """
    for i in range(rows):
        for j in range(cols):
            out[i, j] = 0.0
        for k in range(inner):
            aik = a[i, k]
            if aik != 0.0:
                for j in range(cols):
                    out[i, j] += aik * b[k, j]


@njit_force_inline
def _mul_t_lower(a: FloatArray, b: FloatArray, out: FloatArray, rows: int, inner: int) -> None:
    """The lower triangle (j <= i < rows) of ``out = a @ b.T``, skipping the zeros of ``a``.

    For a symmetric product such as ``A P Aᵀ = A (A P)ᵀ`` (P symmetric): the
    upper triangle is its mirror image.
    """
    for i in range(rows):
        for j in range(i + 1):
            out[i, j] = 0.0
        for k in range(inner):
            aik = a[i, k]
            if aik != 0.0:
                for j in range(i + 1):
                    out[i, j] += aik * b[j, k]


@njit_force_inline
def _add_lower(p: FloatArray, q: FloatArray, n: int) -> None:
    """``p += q`` on the lower triangle (j <= i < n)."""
    for i in range(n):
        for j in range(i + 1):
            p[i, j] += q[i, j]


@njit_force_inline
def _positive_definite(a: FloatArray, work: FloatArray, inv_d: FloatArray, n: int) -> bool:
    """Whether the symmetric n x n ``a`` (lower triangle read) is positive definite.

    An LDLᵀ factorisation (Cholesky's without its square roots, which made up
    most of its latency): ``a`` is positive definite if and only if every pivot
    d is positive. Pivots must also be normal floats (at least about 2.2e-308,
    far below any covariance this filter can meet: entries are at most 1e100
    apart in magnitude from 1) so that 1 / d is finite. An inf or NaN entry makes
    some pivot inf or NaN, so non-finite matrices fail too. L goes to the strict
    lower triangle of ``work``, 1 / d to ``inv_d``.
    """
    for i in range(n):
        for j in range(i):
            t = a[i, j]
            for k in range(j):
                t -= work[i, k] * work[j, k]
            work[i, j] = t  # L[i, j] d[j], made L[i, j] below
        d = a[i, i]
        for k in range(i):
            w = work[i, k]
            lk = w * inv_d[k]
            d -= w * lk
            work[i, k] = lk
        if not _SMALLEST_NORMAL <= d < math.inf:
            return False
        inv_d[i] = 1.0 / d
    return True


@njit_force_inline
def _mirror_checked(p: FloatArray, work: FloatArray, inv_d: FloatArray, n: int) -> int:
    """Copy the lower triangle of the n x n ``p`` to the upper one and check ``p``.

    Returns OK, NOT_FINITE or NOT_POSITIVE_DEFINITE (``work`` and ``inv_d`` are
    scratch space). The factorisation fails on any non-finite entry, so the
    finiteness scan runs only then, to tell the two failures apart.
    """
    for i in range(n):
        for j in range(i):
            p[j, i] = p[i, j]
    if _positive_definite(p, work, inv_d, n):
        return OK
    return NOT_POSITIVE_DEFINITE if _finite_mat(p, n, n) else NOT_FINITE


@njit_force_inline
def _predict(state: FloatArray, x_new: FloatArray, jac: FloatArray, q: FloatArray, n: int) -> int:
    """The predict of :func:`_make_predict`'s kernel after its shape checks (see there).

    Typed once for every ``n`` (an int64), and inlined by LLVM into each
    kernel, where ``n`` is a constant.
    """
    if not _finite_mat(jac, n, n):
        return BAD_F
    if not _equal(q, state[n + 2 : 2 * n + 2], n) and not _adopt_dominant(
        q, state[n + 2 : 2 * n + 2], state[2 * n + 2 : 3 * n + 2], n, 1.0, 0.0
    ):
        return NOISE_CHANGED
    for i in range(n):
        if x_new[i] - x_new[i] != 0.0:
            return BAD_FX
    p = state[STATE_P : STATE_P + n]
    qs = state[2 * n + 2 : 3 * n + 2]
    fp = state[3 * n + 2 : 4 * n + 2]
    pn = state[4 * n + 2 : 5 * n + 2]
    work = state[5 * n + 2 : 6 * n + 2]
    inv_diag = state[6 * n + 2]
    # F P Fᵀ = F (F P)ᵀ, P being symmetric: both products skip the zeros of F.
    _mul(jac, p, fp, n, n, n)
    _mul_t_lower(jac, fp, pn, n, n)
    _add_lower(pn, qs, n)
    status = _mirror_checked(pn, work, inv_diag, n)
    if status != OK:
        return status
    angle = state[n + 1]
    for i in range(n):
        state[STATE_X, i] = _wrap(x_new[i]) if angle[i] != 0.0 else x_new[i]
        for j in range(n):
            p[i, j] = pn[i, j]
    return OK


def _constant(size: int) -> int:
    """``size`` as a kernel's constant that numba types as int64, not as a literal.

    numba types a closure's Python int as a literal (``Literal[int](3)``), and
    compiles every function called with it once per value; a NumPy int64 is
    typed int64, and LLVM still sees a constant. (Typed int for mypy: the
    kernels use it as one.)
    """
    return cast(int, np.int64(size))


def _make_predict(n: int) -> PredictKernel:
    """The predict kernel of ``n``-state filters (``n`` a compile-time constant)."""
    size = _constant(n)

    @njit_no_refcount
    def ekf_predict(state: FloatArray, x_new: FloatArray, jac: FloatArray, q: FloatArray) -> int:
        """x ← wrap(f(x)), P ← F P Fᵀ + Q in ``state``, or a status code leaving x and P unchanged.

        ``x_new`` (n,) is f(x), ``jac`` (n, n) the Jacobian F, ``q`` (n, n) the
        caller's Q. Returns ``BAD_SHAPE``, ``BAD_F``, ``NOISE_CHANGED`` or
        ``BAD_FX`` (checked in this order) before computing anything, then
        ``NOT_FINITE`` or ``NOT_POSITIVE_DEFINITE`` for the predicted covariance,
        else ``OK``.
        """
        if (x_new.shape[0] != size or jac.shape[0] != size or jac.shape[1] != size
                or q.shape[0] != size or q.shape[1] != size
                or state.shape[1] != size):  # fmt: skip
            return BAD_SHAPE
        status: int = _predict(state, x_new, jac, q, size)
        return status

    return ekf_predict


@njit_force_inline
def _update(
    state: FloatArray,
    z: FloatArray,
    hx: FloatArray,
    jac: FloatArray,
    r: FloatArray,
    rbuf: FloatArray,
    y: FloatArray,
    n: int,
    m: int,
) -> float:
    """The update of :func:`_make_update`'s kernel after its shape checks (see there).

    Typed once for every ``n`` and ``m`` (int64), and inlined by LLVM into each
    kernel, where they are constants.
    """
    vec = rbuf[_VEC]
    for i in range(m):
        if z[i] - z[i] != 0.0:
            return _FAIL_Z
    if not _finite_mat(jac, m, n):
        return _FAIL_H
    if not _equal(r, rbuf[_R], m) and not _adopt_dominant(
        r, rbuf[_R], rbuf[_RS], m, 2.0, 1e-300
    ):
        return _FAIL_NOISE
    for i in range(m):
        if hx[i] - hx[i] != 0.0:
            return _FAIL_HX
    rs = rbuf[_RS]
    hp = rbuf[_HP]
    s = rbuf[_S]
    chol = rbuf[_CHOL]
    inv_diag = vec[_INV_DIAG]
    u = vec[_U]
    x = state[STATE_X]
    p = state[STATE_P : STATE_P + n]
    for i in range(m):
        y[i] = z[i] - hx[i]
    flags = vec[_ANGLE]
    for i in range(m):
        if flags[i] != 0.0:
            a = y[i]
            if a - a != 0.0:
                # z - h(x) overflowed (angles near ±1.8e308): the difference of the
                # wrapped angles is the same angle, and finite (as angle_diff does).
                a = _wrap(z[i]) - _wrap(hx[i])
            y[i] = _wrap(a)

    _mul(jac, p, hp, m, n, n)  # H P = (P Hᵀ)ᵀ
    _mul_t_lower(jac, hp, s, m, n)  # H P Hᵀ = H (H P)ᵀ
    for i in range(m):
        for j in range(i + 1):
            s[i, j] += rs[i, j]
    # S = L D Lᵀ (L unit lower triangular, in chol; 1 / D in inv_diag).
    if not _positive_definite(s, chol, inv_diag, m):
        for i in range(m):
            for j in range(i + 1):
                if s[i, j] - s[i, j] != 0.0:
                    return _FAIL_S_NOT_FINITE
        return _FAIL_S_NOT_POSITIVE_DEFINITE

    for i in range(m):
        if y[i] - y[i] != 0.0:
            vec[_META, 1] = math.inf
            return _FAIL_RESIDUAL
    # NIS = Σ uᵢ² / dᵢ with u = L⁻¹ y (never negative), by forward substitution.
    nis = 0.0
    for i in range(m):
        t = y[i]
        for k in range(i):
            t -= chol[i, k] * u[k]
        u[i] = t
        # (t / d) t overflows only when t² / d does (d >= the smallest normal float);
        # t t / d could overflow first.
        nis += (t * inv_diag[i]) * t
    vec[_META, 1] = nis
    if not nis < math.inf:
        vec[_META, 1] = math.inf
        return _FAIL_NIS
    if nis > vec[_META, _GATE]:
        return _FAIL_GATED

    # K = P Hᵀ S⁻¹: row i of K solves S kᵢ = (P Hᵀ)ᵢ = (H P)ᵀᵢ (S is symmetric).
    gain = rbuf[_GAIN]
    for i in range(n):
        for j in range(m):  # L w = (H P)ᵀᵢ
            t = hp[j, i]
            for k in range(j):
                t -= chol[j, k] * u[k]
            u[j] = t
        for j in range(m - 1, -1, -1):  # Lᵀ kᵢ = D⁻¹ w
            t = u[j] * inv_diag[j]
            for k in range(j + 1, m):
                t -= chol[k, j] * u[k]
            u[j] = t
            gain[i, j] = t
    xn = vec[_XN]
    angle = state[n + 1]
    for i in range(n):
        acc = 0.0
        for j in range(m):
            acc += gain[i, j] * y[j]
        v = x[i] + acc
        if v - v != 0.0:
            return _FAIL_STATE
        xn[i] = _wrap(v) if angle[i] != 0.0 else v

    # Joseph form P ← A P Aᵀ + K R Kᵀ with A = I - K H, for any K (not only the
    # optimal one), evaluated as A P Aᵀ = A P - (A P Hᵀ) Kᵀ with A P = P - K (H P):
    # P ← A P + V Kᵀ with V = K R - A P Hᵀ. This is the Joseph form, not the short
    # form (I - K H) P: V is the rounding error of the gain (K S - P Hᵀ, zero in exact
    # arithmetic) and V Kᵀ takes it out to first order. A rounding error E in A P
    # enters the result as E Aᵀ, as it does in the product (I - K H) P (I - K H)ᵀ;
    # but this costs n²m + n²m/2 products instead of about 2n³.
    ap = rbuf[_TMP]
    for i in range(n):
        for j in range(n):
            ap[i, j] = p[i, j]
        for k in range(m):
            g = gain[i, k]
            if g != 0.0:
                for j in range(n):
                    ap[i, j] -= g * hp[k, j]
    v = rbuf[_KR]
    for i in range(n):
        for k in range(m):
            kr = 0.0
            for j in range(m):
                kr += gain[i, j] * rs[j, k]
            acc = 0.0
            for j in range(n):
                hkj = jac[k, j]
                if hkj != 0.0:
                    acc += ap[i, j] * hkj
            v[i, k] = kr - acc  # K R - A P Hᵀ
    pn = rbuf[_PN]
    for i in range(n):
        for j in range(i + 1):
            acc = 0.0
            for k in range(m):
                acc += v[i, k] * gain[j, k]
            pn[i, j] = ap[i, j] + acc
    status = _mirror_checked(pn, rbuf[_PCHK], inv_diag, n)
    # A variance that shrank more than _SHRINK_LIMIT-fold (or came out NaN or not
    # positive) lost more than 12 bits to the cancellation in P - K H P: the public
    # layer finishes the update with finish_cancelled, given this status.
    for i in range(n):
        if not pn[i, i] * _SHRINK_LIMIT >= p[i, i]:
            vec[_META, _JOSEPH] = status
            return _FAIL_CANCELLED
    if status != OK:
        return -float(status)
    for i in range(n):
        x[i] = xn[i]
        for j in range(n):
            p[i, j] = pn[i, j]
    return nis


def _make_update(n: int, m: int) -> UpdateKernel:
    """The update kernel of ``n``-state filters and ``m``-dimensional measurements.

    ``n`` and ``m`` are compile-time constants.
    """

    width = max(n, m, _GATE + 1)  # of rbuf's blocks
    n_states = _constant(n)
    m_meas = _constant(m)

    @njit_no_refcount
    def ekf_update(
        state: FloatArray,
        z: FloatArray,
        hx: FloatArray,
        jac: FloatArray,
        r: FloatArray,
        rbuf: FloatArray,
        y: FloatArray,
    ) -> float:
        """Joseph-form measurement update of ``state``; returns the NIS, or -status.

        ``z`` and ``hx`` (m,) are the measurement and h(x), ``jac`` (m, n) the
        Jacobian H, ``r`` (m, m) the caller's R, ``rbuf`` the buffer of this m
        (:func:`new_rbuf`), which also holds the options (:func:`set_options`:
        which components of ``z`` are angles, the NIS gate). The residual is
        written to ``y`` (m,). Checks, in order: ``BAD_SHAPE`` (any
        shape not fitting ``rbuf``'s m), ``BAD_Z``,
        ``BAD_H``, ``NOISE_CHANGED``, ``BAD_HX``; then S = H P Hᵀ + R
        (``S_NOT_FINITE``, ``S_NOT_POSITIVE_DEFINITE``), the residual
        (``RESIDUAL_OVERFLOW``), the NIS yᵀ S⁻¹ y (``NIS_OVERFLOW``, ``GATED``),
        the updated state (``STATE_OVERFLOW``) and the updated covariance
        (``CANCELLED`` when some variance shrank more than 4096-fold, whatever
        its own status: the caller finishes with :func:`finish_cancelled`;
        else ``NOT_FINITE``, ``NOT_POSITIVE_DEFINITE``). x and P change only with
        ``OK``; ``nis`` is NaN until computed, inf when it overflowed.
        """
        rbuf[_VEC, _META, 1] = math.nan  # the NIS a failure reports, until computed
        if (z.shape[0] != m_meas or hx.shape[0] != m_meas or y.shape[0] != m_meas
                or jac.shape[0] != m_meas or jac.shape[1] != n_states
                or r.shape[0] != m_meas or r.shape[1] != m_meas
                or state.shape[1] != n_states or rbuf.shape[2] != width):  # fmt: skip
            return _FAIL_SHAPE
        out: float = _update(state, z, hx, jac, r, rbuf, y, n_states, m_meas)
        return out

    return ekf_update


def _scaled_inverse(a: FloatArray) -> tuple[FloatArray, float] | None:
    """The inverse of the symmetric ``a`` (exactly symmetric) and a bound on κ(D a D).

    D scales the diagonal of ``a`` to ones; ``D a D = L Lᵀ`` (Cholesky) and the
    inverse is D L⁻ᵀ L⁻¹ D, whose error relative to ``sqrt(inv_ii inv_jj)`` is
    about ε κ(D a D) however badly ``a`` is scaled (entries from 1e-100 to
    1e100, where κ(a) could be 1e200). The condition number returned is the
    larger of κ₁ = ‖D a D‖₁ ‖(D a D)⁻¹‖₁ (within a factor n of κ₂) and 1 / the
    smallest pivot of L Lᵀ (never above κ₂, as D a D has a unit diagonal): the
    pivots, not the inverse, say when ``D a D`` is singular to working
    precision, where a computed inverse is noise and κ₁ from it no bound. None
    when ``a`` is not finite, its diagonal not positive or its Cholesky
    factorisation fails (not positive definite to working precision).
    """
    diag = a.diagonal()
    if not np.isfinite(a).all() or not (diag > 0.0).all():
        return None
    d = 1.0 / np.sqrt(diag)
    scaled = a * d * d[:, None]
    try:
        factor = np.linalg.cholesky(0.5 * (scaled + scaled.T))
    except np.linalg.LinAlgError:
        return None
    smallest_pivot = float(np.min(factor.diagonal() ** 2))
    if not smallest_pivot > 0.0:
        return None
    half = np.linalg.inv(factor)
    inv = half.T @ half
    kappa = float(np.abs(scaled).sum(0).max() * np.abs(inv).sum(0).max())
    kappa = max(kappa, 1.0 / smallest_pivot)
    inv *= d * d[:, None]
    return 0.5 * (inv + inv.T), kappa


def finish_cancelled(state: FloatArray, rbuf: FloatArray, jac: FloatArray, y: FloatArray) -> int:
    """Finish an update the kernel left with ``CANCELLED``; returns its status (OK or a failure).

    The kernel stopped because some variance of its Joseph-form posterior
    (``rbuf``'s ``_PN`` block, of status ``rbuf[_VEC, _META, _JOSEPH]``) shrank
    more than ``_SHRINK_LIMIT``-fold, a sign that ``A P = P - K (H P)`` cancelled.
    Its rounding error E enters the result as ``E Aᵀ`` (A = I - K H; see
    :func:`_update`), which is small where A is (all of H's directions measured
    precisely) but not in general: with a state measured far more precisely
    than it was known, entries came out wrong by up to 1e66 times the
    posterior's scale, or the update raised FilterError.

    The alternative is the information form,

        P⁺ = (P⁻¹ + Hᵀ R⁻¹ H)⁻¹,  x⁺ = x + P⁺ Hᵀ R⁻¹ y,

    equal in exact arithmetic to P - P Hᵀ (H P Hᵀ + R)⁻¹ H P = (I - K H) P and
    x + K y (the Woodbury identity). It subtracts nothing in P⁺, and needs no
    solve with S = H P Hᵀ + R, which a precise measurement of dependent
    directions makes singular to working precision (the kernel's gain, and
    its x, then have no correct digit). Its error estimate
    (:func:`_information_update`), in units of ε relative to
    ``sqrt(P⁺ᵢᵢ P⁺ⱼⱼ)``, bounded the measured error of P⁺ within a factor 4 in
    9000 random updates.

    It decides on evidence, not on the Joseph form's error bound (which can
    exceed its actual error by 1e14). Only where the information form is well
    conditioned, ε times its error estimate at most 2⁻¹² (else the kernel's
    result and status stand, as before this fallback):

    * P⁺ replaces the Joseph P where that failed its checks, or differs from
      P⁺ by more than 8 times P⁺'s error estimate (then the Joseph form's
      error is the larger of the two), or where ε times P⁺'s estimate is at
      most 2⁻⁴² (P⁺ then within 1e-12) and the Joseph form's bound is larger;
    * the two states are compared: where they differ by more than
      ``max(2⁻³³ (|x| + |x⁺ - x|), sqrt(P⁺ᵢᵢ))`` one of them is wrong. The
      kernel's x (off by about ε κ(S), κ of S scaled to a unit diagonal)
      stays where ε κ(S) ≤ 2⁻³⁰; else an update the Joseph form failed is
      refused (its status, as before), and otherwise x⁺ replaces the
      kernel's x where κ(S) exceeds P⁺'s error estimate.

    Commits x and P only with OK. ``jac`` (m, n) is the H and ``y`` (m,) the
    (wrapped) residual the kernel took. NumPy, not a kernel: this is rare, and
    compiling it into every kernel would cost compile time.
    """
    n = state.shape[1]
    m = jac.shape[0]
    x = state[STATE_X]
    p = state[STATE_P : STATE_P + n]
    joseph = rbuf[_PN, :n, :n]
    x_kernel = rbuf[_VEC, _XN, :n]
    status = int(rbuf[_VEC, _META, _JOSEPH])
    new_p, new_x = joseph, x_kernel
    with np.errstate(all="ignore"):
        found = _information_update(p, jac, rbuf[_RS, :m, :m], y)
        if found is not None and _EPS * found[2] <= _WELL_CONDITIONED:
            posterior, step, error = found
            deviation = np.sqrt(posterior.diagonal())
            gap = np.abs(posterior - joseph) / np.outer(deviation, deviation)
            # P⁺ where the Joseph form failed, or differs from it by more than P⁺'s
            # own error (8 times its estimate, which bounded it within 4), or is
            # accurate to 1e-12 (2⁻⁴² times 4) and the Joseph bound is the larger.
            take_p = (
                status != OK
                or not gap.max() <= 8.0 * _EPS * error
                or (_EPS * error <= _ACCURATE and error < _joseph_bound(p, jac, rbuf, deviation))
            )
            x_info = x + step
            apart = x_info - x_kernel
            for i in np.flatnonzero(state[n + 1]):  # the angles, wrapped
                x_info[i] = wrap_float(float(x_info[i]))
                apart[i] = wrap_float(float(apart[i]))
            tolerance = np.maximum(2.0**-33 * (np.abs(x) + np.abs(step)), deviation)
            if not (np.abs(apart) <= tolerance).all():
                # One state is wrong. The kernel's is within about ε κ(S) of its
                # scale: trusted to 2⁻³⁰ (1e-9), else x⁺ if S is the worse conditioned.
                s_kappa = _s_condition(rbuf[_S, :m, :m])
                if not _EPS * s_kappa <= _STATE_TRUSTED:
                    if status != OK:
                        take_p = False  # no state to trust: refused, as before
                    elif np.isfinite(x_info).all() and error < s_kappa:
                        new_x = x_info
            if take_p:
                new_p, status = posterior, OK
    if status != OK:
        return status
    state[STATE_X] = new_x
    p[...] = new_p
    return OK


def _joseph_bound(p: FloatArray, jac: FloatArray, rbuf: FloatArray, scale: FloatArray) -> float:
    """A bound on the Joseph form's error, in units of ε relative to ``scale_i scale_j``.

    The error E of ``A P = P - K (H P)`` is at most about ε (|P| + |K| |H P|)
    and enters the result as ``E Aᵀ`` (see :func:`_update`); |A| takes the
    rounding of its entries into account. ``scale`` is sqrt(diag P⁺) of a
    posterior known to be accurate (not the Joseph form's own, which may be noise).
    """
    n = p.shape[0]
    m = jac.shape[0]
    gain = rbuf[_GAIN, :n, :m]
    abs_gain = np.abs(gain)
    a = np.abs(np.eye(n) - gain @ jac) + _EPS * (abs_gain @ np.abs(jac))
    bound = (np.abs(p) + abs_gain @ np.abs(rbuf[_HP, :m, :n])) @ a.T
    return float(np.tril(bound / np.outer(scale, scale)).max())


def _s_condition(s_lower: FloatArray) -> float:
    """κ of S scaled to a unit diagonal, from the kernel's lower triangle of S (inf: singular)."""
    lower = np.tril(s_lower)
    found = _scaled_inverse(lower + np.tril(lower, -1).T)
    return math.inf if found is None else found[1]


def _information_update(
    p: FloatArray, jac: FloatArray, r: FloatArray, y: FloatArray
) -> tuple[FloatArray, FloatArray, float] | None:
    """``P⁺ = (P⁻¹ + Hᵀ R⁻¹ H)⁻¹`` (exactly symmetric), the step ``P⁺ Hᵀ R⁻¹ y`` and P⁺'s error.

    The estimate is in units of ε relative to ``sqrt(P⁺ᵢᵢ P⁺ⱼⱼ)``: κ of the
    scaled information matrix J = P⁻¹ + Hᵀ R⁻¹ H (its inverse's own error)
    plus the errors of J's two terms, each about ε κ times its scale (κ of the
    scaled P, of the scaled R), carried through J⁻¹ to first order
    (|P⁺| δJ |P⁺|). P and R are positive definite (checked by the kernels and
    the public layer). None when a factorisation fails (a matrix singular to
    working precision) or P⁺ fails the kernels' test of a covariance
    (:func:`_positive_definite`: finite, the pivots of its LDLᵀ
    factorisation, those of D P⁺ D over dᵢ², normal floats).
    """
    prior = _scaled_inverse(p)
    noise = _scaled_inverse(r)
    if prior is None or noise is None:
        return None
    p_inv, r_inv = prior[0], noise[0]
    information = p_inv + jac.T @ r_inv @ jac
    found = _scaled_inverse(information)
    if found is None:
        return None
    posterior, kappa = found
    diag = posterior.diagonal()
    if not np.isfinite(posterior).all() or not (diag > 0.0).all():
        return None
    d = 1.0 / np.sqrt(diag)
    try:
        factor = np.linalg.cholesky(posterior * d * d[:, None])
    except np.linalg.LinAlgError:
        return None
    if not ((factor.diagonal() / d) ** 2 >= _SMALLEST_NORMAL).all():
        return None
    abs_jac = np.abs(jac)
    p_scale = np.sqrt(p_inv.diagonal())
    perturbation = prior[1] * np.outer(p_scale, p_scale)
    perturbation += noise[1] * (abs_jac.T @ np.abs(r_inv) @ abs_jac)
    abs_post = np.abs(posterior)
    carried = (abs_post @ perturbation @ abs_post) * d * d[:, None]
    error = kappa + float(carried.max())
    # P⁺ Hᵀ R⁻¹ y as (P⁺ Hᵀ Dᵣ) (Dᵣ R⁻¹ Dᵣ) (Dᵣ⁻¹ y)... with Dᵣ = diag(R)^½: each
    # factor near the scale of the result's, so a tiny R does not overflow R⁻¹ y.
    r_scale = np.sqrt(r.diagonal())
    scaled_r_inv = r_inv * r_scale * r_scale[:, None]
    step = ((posterior @ jac.T) / r_scale) @ (scaled_r_inv @ (y / r_scale))
    return posterior, step, error


def _freeze(kernel: Any) -> None:
    """Let ``kernel`` compile nothing more: other argument types raise at dispatch."""
    # A plain function when numba's JIT is disabled: nothing to freeze.
    disable = getattr(kernel, "disable_compile", None)
    if disable is not None:
        disable()


_PREDICT: dict[int, PredictKernel] = {}
_UPDATE: dict[tuple[int, int], UpdateKernel] = {}


def predict_kernel(n: int) -> PredictKernel:
    """The predict kernel of ``n``-state filters, compiled on first request.

    Compiled (or loaded from numba's cache) for the types the filter passes
    only, after which it compiles nothing more.
    """
    kernel = _PREDICT.get(n)
    if kernel is None:
        kernel = _make_predict(n)
        x = np.zeros(n)
        eye = np.eye(n)
        state = new_state(x, eye, ())
        set_q(state, eye, eye)
        kernel(state, x, eye, eye)
        _freeze(kernel)
        _PREDICT[n] = kernel
    return kernel


def update_kernel(n: int, m: int) -> UpdateKernel:
    """The update kernel of ``n``-state filters and ``m``-dimensional measurements.

    Compiled on first request, as :func:`predict_kernel`.
    """
    kernel = _UPDATE.get((n, m))
    if kernel is None:
        kernel = _make_update(n, m)
        state = new_state(np.zeros(n), np.eye(n), ())
        rbuf = new_rbuf(n, m)
        eye = np.eye(m)
        set_r(rbuf, eye, eye)
        z = np.zeros(m)
        kernel(state, z, z, np.zeros((m, n)), eye, rbuf, np.empty(m))
        _freeze(kernel)
        _UPDATE[(n, m)] = kernel
    return kernel


def compile_kernels(n: int = 1, m: int = 1) -> None:
    """Compile (or load from numba's cache) the kernels of ``n`` states and ``m``-D measurements.

    The filter only ever passes C-contiguous, writeable, aligned float64 arrays,
    so these are the only specialisations; afterwards the kernels compile nothing more.
    """
    predict_kernel(n)
    update_kernel(n, m)
