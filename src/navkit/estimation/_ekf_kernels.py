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
``NOISE_CHANGED``: the caller validates it and calls again (a Q first by
:func:`adopt_positive_q`, a kernel compiled when first needed: exactly
symmetric and positive definite by an LDLᵀ factorisation, e.g. a
constant-velocity model's; then in Python). Then it computes
the step into scratch space, makes the new covariance exactly symmetric,
checks it positive definite (an LDLᵀ factorisation, which also fails on
non-finite entries) and only then commits it. Every outcome is a status
code: the kernels never raise, never allocate (they are compiled without
reference counting, which alone took a tenth of a call) and never leave
``state`` half-written.

An update whose Joseph form cancelled (a variance shrank more than 4096-fold:
a measurement far more precise than the estimate; or a first-order estimate
of the Joseph P's error exceeds 2⁻⁴⁰ of its scale, :func:`_joseph_in_doubt`),
whose Joseph P failed its check, or whose S (of any size since review 41, before it
of at most ``_EXACT_ELIMINATION_MAX`` components) is ill-conditioned for its rounding error
(its pivots, against a bound on that error, give ε κ(S) > 2⁻³⁰, so that its
NIS and x are not to be trusted; H P Hᵀ cancelling counts), commits nothing
and returns ``CANCELLED``; the public layer finishes it with :func:`finish_cancelled`,
which may take the information form instead, chosen by residuals computed
exactly, and commits a state only with a bound on its error within 2⁻²⁰ of a
posterior deviation or a few ulps, else the posterior mean in exact rational
arithmetic, and a covariance only with a measured error within 2⁻⁴⁰ of its
scale, else the exact posterior covariance, rounded once (from S's elimination
or, above ``_EXACT_CANCELLED_MAX_M`` (12) components where cheaper, the
information form's in exact arithmetic: :class:`_ExactUpdate`; an update whose
exact arithmetic would eliminate more than ``_EXACT_ELIMINATION_MAX`` rows is
refused there), where float64 holds it as a covariance (in
NumPy: the case is rare, and compiled into every update kernel it would cost
compile time).

Each kernel is compiled, when first requested, for one signature: the
filter's own arrays (``state``, ``rbuf``, ``y``) as numba arrays and the
user's (f(x), F, Q; z, h(x), H, R) as :data:`~navkit._shared.array_objects.OBJECT`,
any object. The public layer calls its compiled entry directly, skipping
numba's dispatcher, and the kernel tests those objects in C first
(:func:`~navkit._shared.array_objects.float_vector`, ``float_matrix``):
anything but an ndarray (exactly) of native float64 of the right ndim,
C-contiguous and writeable (what the dispatcher typed as the one type the
kernels were compiled for, aligned or not) returns ``BAD_TYPE``, which the
public layer takes as "convert the arguments and check them in full", as it
took a dispatch failure before. Issue 17: the dispatcher's typing of the
arguments and the Python type tests that kept masked arrays from it cost
about 0.45 µs of a 7.3 µs step of the benchmark's 6-state model.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, cast

import numpy as np

from navkit._shared.angles import wrap_float
from navkit._shared.jit import bind_numba_names, njit_force_inline, njit_no_refcount
from navkit._shared.se2 import wrap_scalar
from navkit._shared.types import FloatArray, IntArray
from navkit.errors import FilterError

# (review 51: se2.wrap_scalar/exp_body compiled once and inlined by LLVM; see _wrap.)

# numba's min and max builtins, without an overload compiled per argument types
# (navkit._shared.selects: intrinsics, so bound when numba loads; issue 17).
min2: Any = None
max2: Any = None
bind_numba_names(
    globals(), "navkit._shared.selects", python={"min2": min, "max2": max}, min2="min2", max2="max2"
)

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
    "GATED_AT_LEAST",
    "GATE_PASSED",
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
    "adopt_positive_q",
    "compile_kernels",
    "finish_cancelled",
    "finish_singular_s",
    "gated_s_ill",
    "is_positive_definite",
    "kernel_dispatchers",
    "new_rbuf",
    "new_state",
    "predict_kernel",
    "rbuf_gate",
    "rbuf_nis",
    "retry_gated",
    "set_gate",
    "set_nis",
    "set_options",
    "set_q",
    "set_r",
    "update_kernel",
]

STATE_X = 0
STATE_P = 1

_NO_FLOATS = np.zeros(0)


def _float_view_python(obj: object, ndim: int) -> tuple[bool, Any]:
    """The check of :func:`navkit._shared.array_objects.float_vector` in Python."""
    if (
        type(obj) is np.ndarray
        and obj.ndim == ndim
        and obj.dtype.num == np.dtype(np.float64).num
        and obj.dtype.byteorder == "="
        and obj.flags.c_contiguous
        and obj.flags.writeable
    ):
        return True, obj
    return False, _NO_FLOATS.reshape((0,) * ndim)


# navkit._shared.array_objects's intrinsics (it imports numba): bound when numba
# loads; with the JIT disabled (NUMBA_DISABLE_JIT=1), the same checks in Python.
float_vector: Any = None
float_matrix: Any = None
bind_numba_names(
    globals(), "navkit._shared.array_objects",
    python={
        "float_vector": lambda obj: _float_view_python(obj, 1),
        "float_matrix": lambda obj: _float_view_python(obj, 2),
    },
    float_vector="float_vector", float_matrix="float_matrix",
)  # fmt: skip

_SMALLEST_NORMAL = 2.2250738585072014e-308  # sys.float_info.min
_EPS = 2.0**-53  # the unit roundoff of float64

# A kernel's compiled entry takes the public layer's arguments as they come and
# checks their types itself (BAD_TYPE for any but a writeable float64 C array).
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
CANCELLED = 17  # the Joseph form cancelled (a variance shrank > 4096-fold, or its P's
# estimated error exceeds 2⁻⁴⁰) or failed its check, or S is ill-conditioned
# for its rounding error (ε max cₖ / Dₖ > 2⁻³⁰; of any m since review 41, before it
# m <= _EXACT_ELIMINATION_MAX): finish_cancelled
# From retry_gated only: the exact NIS passes the gate the kernel's NIS failed: run the
# kernel again without the gate.
GATE_PASSED = 18
# From finish_singular_s only: rejected by the gate on a lower bound of the exact NIS
# (left in rbuf as the NIS), the exact one beyond the exact arithmetic's limit.
GATED_AT_LEAST = 19

# What ekf_update returns for a status other than OK: -status.
_FAIL_SHAPE = -float(BAD_SHAPE)
_FAIL_TYPE = -float(BAD_TYPE)
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
# (measured from residuals, see _information_update) is at most this (12 bits short).
_WELL_CONDITIONED = 2.0**-12
# The kernel's state, x + K y with K solved with S, is within about ε κ(S) of its
# scale: trusted when that is at most this (about 1e-9).
_STATE_TRUSTED = 2.0**-30
# A pivot ratio max cₖ / Dₖ of S = L D Lᵀ above this (ε times it above _STATE_TRUSTED),
# cₖ >= Sₖₖ bounding the size of the terms of Sₖₖ (see _update), marks S as that
# ill-conditioned (retry_gated, the update kernel).
_PIVOT_LIMIT = _STATE_TRUSTED / _EPS
# finish_cancelled and finish_singular_s trust a state where the bound on its error is at
# most this fraction of the state's size (|x| + |x⁺ - x|),
# as closely as float64 holds that state: the bound counts every rounding of the step
# at its worst (23 ε |x⁺ - x| measured with well-conditioned solves); the errors are
# below 2 ulps of the size (measured on 9000 updates), as a float64 square-root or
# information-form update's.
_STEP_RESOLUTION = 32.0 * _EPS
# ... or within this many of the posterior's deviations (about 1e-6; a quarter before
# review 33, which kept the kernel's x up to 1.5e-3 deviations off where x⁺ was exact,
# κ(R) 1e8 to 1e18, and for more than 12 components until review 40): a state is
# committed only with a bound within that or
# _STEP_RESOLUTION of its size, else the exact one: 2⁵ above the largest bound of the
# vouched states of 960 precise position or speed measurements of a 6-state filter,
# which thus still compute no exact state (at 2⁻³⁰, 16 of them did).
_STEP_EXACT_SURE = 2.0**-20
# The fallbacks commit a covariance they computed only where its measured error
# (relative to sqrt(P⁺ᵢᵢ P⁺ⱼⱼ)) is at most this, as accurate as an ordinary update's
# Joseph P (no variance shrinking more than _SHRINK_LIMIT-fold: about 4096 ε); else,
# for measurements of at most _EXACT_CANCELLED_MAX_M components, the exact posterior
# rounded once (_exact_posterior). The measured errors run 10-100 times above the
# true ones: 7 of 300 precise measurements of a 6-state filter (P of scaled
# condition 1.9e3 to 1.8e7) take the exact posterior, their P⁺ 5e-15 to 1.6e-11 off.
_P_SURE = 2.0**-40
# The update kernel commits its Joseph P only where a first-order estimate of its error
# is within _P_SURE (see _joseph_in_doubt): that estimate over ε is at most this.
_JOSEPH_LIMIT = _P_SURE / _EPS
# Where float64 holds no covariance at the exact posterior rounded (its scaled
# condition beyond about 1e16), a computed covariance that passed its checks is
# committed within this of it (measured against it), else the update is refused.
_P_NEAR = 2.0**-20
# The largest measurement size whose exact fallbacks (finish_cancelled,
# finish_singular_s) always eliminate S; above it they take the cheaper exact route
# within _EXACT_ELIMINATION_MAX (_exact_route). (Before review 40, 8 for the
# ill-conditioned S and for finish_singular_s, which refused larger measurements, and 12
# for finish_cancelled, which kept the Joseph P and kernel's x above it, unmeasured.
# Measured 2026-12 with the elimination, posterior, state and NIS together: 2-23 ms for
# m = 9-12 with 4 states, 10-72 ms with 15, up to 0.46 s where P and R lie 1e280 apart;
# with 64 states 0.25 s, 3.4 s that far apart, where m = 8 takes 0.12 and 0.9 s; the
# exact NIS alone 0.8-2.6 ms for m = 8 with 15 states, 3.6-20 ms for m = 12.)
_EXACT_CANCELLED_MAX_M = 12
# The largest elimination the exact fallback of a measurement of more than
# _EXACT_CANCELLED_MAX_M components makes, and the largest measurement whose S the
# update kernel tests for ill-conditioning and retry_gated checks a gated update's with
# (S's m, or the information route's n and R's largest block; see _exact_route):
# measured 2026-12 on a loaded 2-core machine, 0.25 s for 24 components of 15 states
# with a dense R 1e-12 of P, 1.0 s with 64 states (10 s with P and R 1e280 apart, as 12
# components of 128 states took before); a 360-beam scan with a diagonal R, 0.07 s with
# 6 states, 0.17 s with 15, 0.9 s with 24 (3.3 s with 32; 81 s with 64). It bounds the
# elimination, not the exact posterior's work on the states (review 41, 24 components
# of a dense R, _ExactUpdate alone: 0.5 s with 64 states, 1.2 s with 128, 3.0 s with
# 256; capped since review 42 by _EXACT_POSTERIOR_WORK_MAX), nor the float64
# information form's refinement of a dense R block's inverse (m³ exact terms in
# Python: 0.4 s for m = 100, 1.9 s for 200, 10 s for 400; review 42, loaded: 3.9 s, 21.5
# s and 140 s for 800, which preceded the refusal of such an update; capped from sizes
# since review 43, _RESIDUAL_TERM_WORK).
_EXACT_ELIMINATION_MAX = 24
# The largest work of an exact posterior from S's elimination (_exact_posterior): its
# replay of S's elimination on H P's n columns and back substitution, about m² n
# divisions of integers of up to b bits (b, det S's size, grows with m and with how far
# apart P and R lie), and the n (n + 1) / 2 entries' m products of H P's integers (h
# bits) by those: work = m² n b² + 2.7 m h b n (n + 1) / 2, about 1.7e-12 s a unit
# (measured 2026-12 on a loaded 2-core machine, 24 components of a dense R, P and R
# 1e280 apart, b = 23932: 46 s with 64 states, 96 s with 128, 197 s with 256, linear in
# n without end; review 41's docs said 7, 14 and 32 s). Past it the update raises
# FilterError (review 42, EKFREV3): about a minute of wall time there. That unit is wall time at a
# load of about 10 on 2 cores: in CPU time the unit is 4-6 times less (EKFREV4, same
# machine, load 10: b = 23969 with 64 states, estimate 39 s, 7.3 s CPU, 21 s wall; 48
# states 28.8 s for 5.6 s CPU), and b² overstates the growth in b (CPython multiplies by
# Karatsuba: b = 70845, 24 states, estimate 123 s for 19 s CPU): an idle machine would
# finish some refused updates within 20 s. The error message counts in CPU time
# (_EXACT_POSTERIOR_WORK_SECONDS, the largest of those units: 4.3e-13 with 12 components
# and 96 states): the limit is then about 15 s of CPU.
_EXACT_POSTERIOR_WORK_MAX = 3.5e13
_EXACT_POSTERIOR_WORK_SECONDS = 4.3e-13
# The same cap on the other Python-level work a precise update does past the exact
# posterior's (review 43, EKFREV5; before, unlimited): CPU seconds per operation, in
# _EXACT_POSTERIOR_WORK_SECONDS's units. The information form's refinement of a dense
# R block's inverse sums b³ exact terms (_exact_residual): measured 2-3e-7 s CPU a term
# for b = 100-200 on a loaded 2-core machine (review 42: 140 s wall for m = 800, now
# refused from its size; the cap allows blocks up to about 370 components).
_RESIDUAL_TERM_WORK = 3e-7 / _EXACT_POSTERIOR_WORK_SECONDS
# The information route of _ExactUpdate: per component about (n + 2)² products of
# integers of H's and R's bits, measured 0.14-0.6 µs CPU per m (n + 2)² (n = 6-24,
# 500-10,000 beams of a diagonal R), and b³ / 3 for a block of b components'
# elimination: 24 states allow about 37,000 beams.
_INFORMATION_OP_WORK = 6e-7 / _EXACT_POSTERIOR_WORK_SECONDS
# The largest n whose Q the predict kernel accepts by its LDLᵀ factorisation
# (_adopt_positive): its backward error, about n² ε max|Q|, is then below 1e-12 max|Q|.
_PSD_MAX_N = 64

# Blocks of an rbuf. Each is used by the update kernel and reused where its
# contents are dead, so that none can go (review 47: the size is 10 max(n, m)²,
# was 11): R and R symmetrised are the validated noise between updates; S's
# lower triangle, the new P and _VEC are read by finish_cancelled and the other
# fallbacks after the kernel returns; H P is read until the new P is made, then
# holds the LDLᵀ factor of its check (was a block of its own) and is scratch of
# _joseph_in_doubt, as are L (σ, u, sqrt(Rₖₖ), ρᵢ² in its rows 0-3), (I - K H) P
# and V, while K and the new P are read there. Only the blocks' common size wastes
# room (n x n and n x m blocks of an update with m far above n, and _VEC's 5 rows:
# about half of a 360-beam update's 10 MB); blocks of their own sizes would take
# another layout (bands of rows of one 2-D array), not tried.
_R = 0  # R as passed
_RS = 1  # R symmetrised
_HP = 2  # H P (m x n); then the LDLᵀ factor of the new P (n x n)
_CHOL = 3  # the unit lower triangular L of S = L D Lᵀ (m x m)
_GAIN = 4  # K (n x m)
_KR = 5  # K R - (I - K H) P Hᵀ (n x m)
_TMP = 6  # (I - K H) P (n x n)
_PN = 7  # the new P (n x n)
_VEC = 8  # rows: 1 / diag(L), a solve vector, the new state, [status, NIS, gate], angle flags
_S = 9  # S (m x m)
_BLOCKS = 10
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


def kept_q(state: FloatArray) -> FloatArray:
    """The validated Q kept in ``state``, symmetrised (a view; NaN before the first)."""
    n = state.shape[1]
    return state[2 * n + 2 : 3 * n + 2]


def set_nis(rbuf: FloatArray, nis: float) -> None:
    """Leave ``nis`` in ``rbuf`` as the update kernel does with a status other than OK."""
    rbuf[_VEC, _META, 1] = nis


def set_gate(rbuf: FloatArray, gate: float) -> None:
    """Set the NIS gate held in ``rbuf`` (inf: none), leaving the other options."""
    rbuf[_VEC, _META, _GATE] = gate


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
def _keep(a: FloatArray, kept: FloatArray, kept_sym: FloatArray, n: int) -> None:
    """Store ``a`` and ``0.5 a + 0.5 aᵀ`` as the validated noise, as the Python check does."""
    for i in range(n):
        for j in range(n):
            kept[i, j] = a[i, j]
            kept_sym[i, j] = 0.5 * a[i, j] + 0.5 * a[j, i]


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
    _keep(a, kept, kept_sym, n)
    return True


@njit_force_inline
def _adopt_positive(
    a: FloatArray,
    kept: FloatArray,
    kept_sym: FloatArray,
    work: FloatArray,
    inv_d: FloatArray,
    n: int,
) -> bool:
    """Store the n x n process noise ``a`` as validated if it is plainly positive definite.

    For a Q that is not diagonally dominant (:func:`_adopt_dominant`), such as
    a constant-velocity model's ``[[dt³/3, dt²/2], [dt²/2, dt]]``: exactly
    symmetric, entries of magnitude at most 1e100, the largest at least 1e-150,
    n at most ``_PSD_MAX_N``, and its LDLᵀ factorisation (:func:`_positive_definite`,
    into the scratch ``work`` and ``inv_d``) succeeds with normal pivots. The
    public layer's check (``covariance(..., semidefinite=True)``) accepts every
    such matrix: a factorisation that succeeds in floating point is exact for
    ``a + δa`` with ``‖δa‖₂`` at most about n² ε max|a| (its backward error;
    no underflow above 1e-150), so the smallest eigenvalue of ``a``, and the
    one ``numpy.linalg.eigvalsh`` computes (within about n² ε max|a| too), are
    above -1e-12 max|a|, far inside that check's -1e-9 max|a|. It stores what
    that check would: ``a`` as passed and ``0.5 a + 0.5 aᵀ``. Anything else is
    left to that check (``NOISE_CHANGED``), which is what decides for the
    positive semi-definite but singular Q it also accepts.
    """
    if n > _PSD_MAX_N:
        return False
    largest = 0.0
    for i in range(n):
        for j in range(i + 1):
            v = a[i, j]
            if v != a[j, i] or not abs(v) <= 1e100:  # NaN fails too
                return False
            largest = max2(largest, abs(v))
    if not largest >= 1e-150:
        return False
    if not _positive_definite(a, work, inv_d, n):
        return False
    _keep(a, kept, kept_sym, n)
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
def _joseph_in_doubt(
    p: FloatArray,
    jac: FloatArray,
    gain: FloatArray,
    pn: FloatArray,
    w: FloatArray,
    e: FloatArray,
    a: FloatArray,
    work: FloatArray,
    rs: FloatArray,
    n: int,
    m: int,
) -> bool:
    """Whether the Joseph P ``pn`` (positive definite) may be more than ``_P_SURE`` off.

    Its error is, to first order, the rounding error E of ``A P = P - K (H P)``
    carried as ``E Aᵀ`` (A = I - K H; an error of K cancels to first order), E
    about ε (|P| + |K| |H| |P|): ε Pᵢᵢ / P⁺ᵢᵢ (the shrink) for a measured state,
    but far more where H P cancels (states correlated so that the measured
    combination's terms exceed it) or K and H do (an ill-conditioned S): with no
    variance shrinking 4096-fold the Joseph P was more than 2⁻⁴⁰ (the fallbacks'
    bound on a covariance) off the exact posterior in 8 of 18,000 random updates,
    up to 2.8e-11 (review 27). So ``ε (E Aᵀ)ᵢⱼ`` with E = |P| + |K| |H| |P| and
    ``|A|``, relative to ``sqrt(P⁺ᵢᵢ P⁺ⱼⱼ)``, is held to ``_P_SURE`` (measured
    on those updates and 2000 of random filters: the error at most 0.85 times
    this). It costs O(n³), so it is computed only where its bound
    ``ε max(Pᵢᵢ / P⁺ᵢᵢ) (1 + β)²`` exceeds that, β = maxᵢ Σₖ |Kᵢₖ| uₖ / σᵢ
    with σᵢ = sqrt(Pᵢᵢ) and uₖ = Σⱼ |Hₖⱼ| σⱼ (|Pᵢⱼ| <= σᵢ σⱼ), which costs O(nm):
    β <= 1 where one state is measured, so that with no variance shrinking
    2048-fold nothing more is computed. σ and u are read from rows 0 and 1 of
    ``work``, where :func:`_update` left them for its test of S (computed here
    before review 28); ``w``, ``e``, ``a`` and ``work`` are scratch blocks.

    Plus the rounding of ``K R`` in ``V = K R - A P Hᵀ``, carried as ``V Kᵀ``:
    ``ε |K| |R| |K|ᵀ``, far above ``K R Kᵀ`` where R is ill-conditioned (its
    entries cancel in ``K R``). Before review 33 it was not counted: of the 1083
    of 3357 random updates with κ(R) from 1e8 to 1e18 that the kernel committed,
    191 had a P more than ``_P_SURE`` off the exact posterior, up to 1.6e-6
    (each within 4 times this term, none within the first-order estimate above);
    now none of the 849 it commits. Its cheap bound is ``ρᵢ² = (Σₖ |Kᵢₖ|
    sqrt(Rₖₖ))²`` against ``P⁺ᵢᵢ`` (|Rₖₗ| <= sqrt(Rₖₖ Rₗₗ)), at most m times
    ``(K R Kᵀ)ᵢᵢ <= P⁺ᵢᵢ`` for a diagonal R, far below 2¹³ P⁺ᵢᵢ: no ordinary
    update is made suspect by it alone. ``rs`` is the symmetrised R; ``work``'s
    rows 2 and 3 hold sqrt(Rₖₖ) and ρᵢ².
    """
    sigma = work[0]
    reach = work[1]
    r_dev = work[2]
    rho2 = work[3]
    for k in range(m):
        r_dev[k] = math.sqrt(rs[k, k])
    beta = 0.0
    for i in range(n):
        acc = 0.0
        rho = 0.0
        for k in range(m):
            g = abs(gain[i, k])
            acc += g * reach[k]
            rho += g * r_dev[k]
        rho2[i] = rho * rho
        b = acc / sigma[i]
        if not b <= beta:  # NaN too
            beta = b
    bound = (1.0 + beta) * (1.0 + beta)
    suspect = False
    for i in range(n):
        if not p[i, i] * bound + rho2[i] <= _JOSEPH_LIMIT * pn[i, i]:
            suspect = True
    if not suspect:
        return False
    for k in range(m):  # W = |H| |P|
        for j in range(n):
            w[k, j] = 0.0
        for q in range(n):
            hkq = abs(jac[k, q])
            if hkq != 0.0:
                for j in range(n):
                    w[k, j] += hkq * abs(p[q, j])
    for i in range(n):  # E = |P| + |K| W and |A| = |I - K H|
        for j in range(n):
            acc = abs(p[i, j])
            kh = 1.0 if i == j else 0.0
            for k in range(m):
                acc += abs(gain[i, k]) * w[k, j]
                kh -= gain[i, k] * jac[k, j]
            e[i, j] = acc
            a[i, j] = abs(kh)
    for i in range(n):  # |K| |R| (n x m), in w (|H| |P| is in E now)
        for k in range(m):
            acc = 0.0
            for q in range(m):
                acc += abs(gain[i, q]) * abs(rs[q, k])
            w[i, k] = acc
    for i in range(n):
        sigma[i] = math.sqrt(pn[i, i])  # the posterior's deviations now
    for i in range(n):
        for j in range(i + 1):  # the lower triangle, the one computed (and mirrored)
            acc = 0.0
            for q in range(n):
                acc += e[i, q] * a[j, q]
            for k in range(m):
                acc += w[i, k] * abs(gain[j, k])
            if not acc <= _JOSEPH_LIMIT * sigma[i] * sigma[j]:
                return True
    return False


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
    def ekf_predict(state: FloatArray, x_obj: object, jac_obj: object, q_obj: object) -> int:
        """x ← wrap(f(x)), P ← F P Fᵀ + Q in ``state``, or a status code leaving x and P unchanged.

        ``x_obj`` (n,) is f(x), ``jac_obj`` (n, n) the Jacobian F, ``q_obj``
        (n, n) the caller's Q, each as the caller has it (any object, see
        :data:`OBJECT`). Returns ``BAD_TYPE`` (one is not a writeable
        C-contiguous ndarray of native float64, exactly, of its ndim),
        ``BAD_SHAPE``, ``BAD_F``, ``NOISE_CHANGED`` or ``BAD_FX`` (checked in
        this order) before computing anything, then ``NOT_FINITE`` or
        ``NOT_POSITIVE_DEFINITE`` for the predicted covariance, else ``OK``.
        """
        x_ok, x_new = float_vector(x_obj)
        jac_ok, jac = float_matrix(jac_obj)
        q_ok, q = float_matrix(q_obj)
        if not (x_ok and jac_ok and q_ok):
            return BAD_TYPE
        if (x_new.shape[0] != size or jac.shape[0] != size or jac.shape[1] != size
                or q.shape[0] != size or q.shape[1] != size
                or state.shape[1] != size):  # fmt: skip
            return BAD_SHAPE
        status: int = _predict(state, x_new, jac, q, size)
        return status

    return ekf_predict


@njit_no_refcount
def adopt_positive_q(state: FloatArray, q: FloatArray) -> bool:
    """Keep ``q`` in ``state`` as the validated Q if :func:`_adopt_positive` takes it.

    Returns whether it did.

    Called by the public layer when the predict kernel returned
    ``NOISE_CHANGED``, before the Python check: a Q that is positive definite
    but not diagonally dominant (a constant-velocity model's, with a ``dt``
    that changes every step) then costs a few microseconds instead of that
    check's 0.06-0.2 ms. A kernel of its own, typed once for every n (a
    run-time size) and compiled only when first needed, so that the predict
    kernels, which every filter compiles, are as before. ``q`` must have
    ``state``'s n x n shape (else False).
    """
    n = state.shape[1]
    if q.shape[0] != n or q.shape[1] != n:
        return False
    kept: bool = _adopt_positive(
        q, state[n + 2 : 2 * n + 2], state[2 * n + 2 : 3 * n + 2],
        state[5 * n + 2 : 6 * n + 2], state[6 * n + 2], n,
    )  # fmt: skip
    return kept


@njit_no_refcount
def is_positive_definite(a: FloatArray, work: FloatArray, inv_d: FloatArray) -> bool:
    """Whether :func:`_positive_definite` takes the square ``a`` (lower triangle read).

    The filters' own check of every covariance they commit, for the public
    layer (``_covariance.covariance``'s test of a ``P0`` NumPy's Cholesky
    refuses, beyond the rows it replays in Python): a kernel of its own,
    compiled only when first needed. ``work`` (n x n) and ``inv_d`` (n) are
    scratch space; shapes that do not fit give False.
    """
    n = a.shape[0]
    if a.shape[1] != n or work.shape[0] < n or work.shape[1] < n or inv_d.shape[0] < n:
        return False
    taken: bool = _positive_definite(a, work, inv_d, n)
    return taken


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
    if not _equal(r, rbuf[_R], m) and not _adopt_dominant(r, rbuf[_R], rbuf[_RS], m, 2.0, 1e-300):
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
    # Whether S is ill-conditioned for its rounding error (retry_gated's test, read
    # before the check of the new P reuses inv_diag): the NIS, K and x above are then
    # off by about ε κ(S), with no variance cancelling where a combination of states is
    # measured precisely (rows of H alike but not a single state's). With σⱼ = sqrt(Pⱼⱼ)
    # and uₖ = Σⱼ |Hₖⱼ| σⱼ, cₖ = uₖ² + Rₖₖ >= (|H| |P| |H|ᵀ + |R|)ₖₖ (|Pᵢⱼ| <= σᵢ σⱼ):
    # the rounding error of S's entry (k, l) is within about n ε sqrt(cₖ cₗ), however
    # far H P Hᵀ cancels, so max cₖ / Dₖ (1 / the smallest pivot of C⁻¹ S C⁻¹, C =
    # diag(sqrt(cₖ))) bounds from below how far that error reaches the NIS and K, as max
    # Sₖₖ / Dₖ does for an error relative to S's own diagonal. Where H P Hᵀ cancels
    # (rows of H nearly orthogonal to the main direction of a strongly correlated P) cₖ
    # is far above Sₖₖ: in review 28's case cₖ / Sₖₖ was 2.7e12 and max Sₖₖ / Dₖ 2.8e4
    # (ε max cₖ / Dₖ 8.7, the limit 2⁻³⁰), the NIS 298.8 for an exact 4.18 and the
    # Joseph P 1.27e-11 off (the gain's second-order error, which _joseph_in_doubt does
    # not see). The larger of cₖ and Sₖₖ, so that no S the diagonal's test flags escapes
    # this one by a rounding of uₖ². m = 1 too: the one pivot is S itself, but S's error
    # is its terms' (review 29: a scalar S with c / S 1.1e15 gave a NIS of 1.827 for an
    # exact 1.911). Every m: before review 40 it stopped at 8 components (NIS up to
    # 5e-9 relative off for m = 10 and 9.1 % for 16), before review 41 at
    # _EXACT_ELIMINATION_MAX, though a diagonal or block-diagonal R has an exact route
    # for any m (_exact_route): 25 readings with a diagonal R, NIS 4.1e-8 relative off
    # and a gate between it and the exact one deciding wrongly. Where no exact route
    # exists finish_cancelled keeps the kernel's NIS and commits its x and P only
    # where the information form vouches for them. σ and u are needed by
    # _joseph_in_doubt anyway (here since review 28; L of S, in chol, is not needed
    # any more).
    sigma = chol[0]
    reach = chol[1]
    for j in range(n):
        sigma[j] = math.sqrt(p[j, j])
    for k in range(m):
        acc = 0.0
        for j in range(n):
            hkj = jac[k, j]
            if hkj != 0.0:
                acc += abs(hkj) * sigma[j]
        reach[k] = acc
    ill = False
    for k in range(m):
        uk = reach[k]
        c = uk * uk + rs[k, k]
        if c < s[k, k]:
            c = s[k, k]
        if c * inv_diag[k] > _PIVOT_LIMIT:
            ill = True
    status = _mirror_checked(pn, hp, inv_diag, n)  # H P is not read any more
    # A variance that shrank more than _SHRINK_LIMIT-fold (or came out NaN or not
    # positive) lost more than 12 bits to the cancellation in P - K H P; a new P that
    # failed its check may still be the rounding of a covariance (review 27: 5 of 43
    # such updates of a 3000-update draw were); where S is ill-conditioned the NIS and
    # x are in doubt. The public layer finishes each with finish_cancelled, given the
    # new P's status (it gates on the exact NIS where S is ill-conditioned, and takes
    # the information form's or the exact x and P where they are the more accurate).
    for i in range(n):
        if not pn[i, i] * _SHRINK_LIMIT >= p[i, i]:
            vec[_META, _JOSEPH] = status
            return _FAIL_CANCELLED
    if (
        ill
        or status != OK
        or _joseph_in_doubt(
            p, jac, gain, pn, rbuf[_HP], rbuf[_TMP], rbuf[_KR], rbuf[_CHOL], rs, n, m
        )
    ):
        vec[_META, _JOSEPH] = status
        return _FAIL_CANCELLED
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
        z_obj: object,
        hx_obj: object,
        jac_obj: object,
        r_obj: object,
        rbuf: FloatArray,
        y: FloatArray,
    ) -> float:
        """Joseph-form measurement update of ``state``; returns the NIS, or -status.

        ``z_obj`` and ``hx_obj`` (m,) are the measurement and h(x), ``jac_obj``
        (m, n) the Jacobian H, ``r_obj`` (m, m) the caller's R, each as the
        caller has it (any object, see :data:`OBJECT`), ``rbuf`` the buffer of
        this m (:func:`new_rbuf`), which also holds the options
        (:func:`set_options`: which components of ``z`` are angles, the NIS
        gate). The residual is written to ``y`` (m,). Checks, in order:
        ``BAD_TYPE`` (as the predict kernel's), ``BAD_SHAPE`` (any
        shape not fitting ``rbuf``'s m), ``BAD_Z``,
        ``BAD_H``, ``NOISE_CHANGED``, ``BAD_HX``; then S = H P Hᵀ + R
        (``S_NOT_FINITE``, ``S_NOT_POSITIVE_DEFINITE``), the residual
        (``RESIDUAL_OVERFLOW``), the NIS yᵀ S⁻¹ y (``NIS_OVERFLOW``, ``GATED``),
        the updated state (``STATE_OVERFLOW``) and the updated covariance
        (``CANCELLED`` when some variance shrank more than 4096-fold, when a
        first-order estimate of its error exceeds 2⁻⁴⁰ of the posterior's
        scale (:func:`_joseph_in_doubt`), when S's pivots say it is
        ill-conditioned for its rounding error (``max cₖ / Dₖ`` above
        2⁻³⁰ / ε, ``cₖ = max(uₖ² + Rₖₖ, Sₖₖ)``, ``uₖ = Σⱼ |Hₖⱼ| sqrt(Pⱼⱼ)``,
        any m), whatever its own status, or when it
        is not finite or not positive definite (its status kept for the
        caller, which finishes with :func:`finish_cancelled`; before review
        27 these were returned, refusing updates whose exact posterior is a
        covariance). x and P change only with ``OK``; ``nis`` is NaN until
        computed, inf when it overflowed.
        """
        z_ok, z = float_vector(z_obj)
        hx_ok, hx = float_vector(hx_obj)
        jac_ok, jac = float_matrix(jac_obj)
        r_ok, r = float_matrix(r_obj)
        if not (z_ok and hx_ok and jac_ok and r_ok):
            return _FAIL_TYPE  # as a dispatch failure was: nothing written
        rbuf[_VEC, _META, 1] = math.nan  # the NIS a failure reports, until computed
        if (z.shape[0] != m_meas or hx.shape[0] != m_meas or y.shape[0] != m_meas
                or jac.shape[0] != m_meas or jac.shape[1] != n_states
                or r.shape[0] != m_meas or r.shape[1] != m_meas
                or state.shape[1] != n_states or rbuf.shape[2] != width):  # fmt: skip
            return _FAIL_SHAPE
        out: float = _update(state, z, hx, jac, r, rbuf, y, n_states, m_meas)
        return out

    return ekf_update


class _PastTheLimit(FilterError):
    """An update refused because its exact arithmetic would eliminate too many rows.

    Raised inside the finishing functions, before anything is committed; the
    decorator :func:`_gated_before_refusal` gates the update on a lower bound of its
    exact NIS first (:func:`_nis_lower_bound`) and lets it through only where that
    does not reject it. ``tried``: the exact NIS, or bounds of it, were tried on the
    gate already (:func:`_gate_past_the_cap`).
    """

    tried = False


Finisher = Callable[[FloatArray, FloatArray, FloatArray, FloatArray], int]


def _gated_before_refusal(finish: Finisher) -> Finisher:
    """``finish`` (state, rbuf, jac, y), with its refusals past the limit gated first.

    A refusal for the 24-row limit (:class:`_PastTheLimit`) becomes ``NIS_OVERFLOW``
    where a lower bound of the exact NIS is beyond float64 and ``GATED_AT_LEAST``
    (the bound left in ``rbuf`` as the NIS) where it exceeds the gate, as a
    measurement the gate rejects is rejected, not refused. Review 41 did so for
    :func:`finish_singular_s` only; the kernel's NIS unvouched in
    :func:`finish_cancelled` and an R block singular in exact arithmetic
    (:class:`_ExactUpdate`, from :func:`retry_gated` too) still raised where the
    bound rejects (review 42, EKFREV3: a reading 1000 deviations off, gate 100).
    """

    def gated(state: FloatArray, rbuf: FloatArray, jac: FloatArray, y: FloatArray) -> int:
        try:
            return finish(state, rbuf, jac, y)
        except _PastTheLimit as refusal:
            n, m = state.shape[1], jac.shape[0]
            if np.isfinite(y).all():
                p = state[STATE_P : STATE_P + n]
                least = _nis_lower_bound(p, jac, rbuf[_RS, :m, :m], y)
                if least == math.inf:  # the exact NIS too, gate or not
                    rbuf[_VEC, _META, 1] = least
                    return NIS_OVERFLOW
                gate = rbuf[_VEC, _META, _GATE]
                if least > gate:
                    rbuf[_VEC, _META, 1] = least
                    return GATED_AT_LEAST
                r = rbuf[_RS, :m, :m]
                if gate < math.inf and not getattr(refusal, "tried", False):
                    # The exact NIS alone where its work is within the cap, else bounds
                    # of it (review 44, EKFREV6): a measurement the gate rejects is
                    # rejected, not refused (before review 43, EKFREV5, only where the
                    # lower bound rejected it: 16 of 240 draws of 25-30 components at
                    # gates 0.9-1.1 times the exact NIS were refused).
                    gated = _gate_past_the_cap(p, jac, r, y, rbuf, refuse=False)
                    if gated != OK:
                        return gated
            # The user sees the public class (the private one only marks the refusal).
            raise FilterError(*refusal.args) from None

    gated.__name__ = finish.__name__
    gated.__qualname__ = finish.__qualname__
    gated.__doc__ = finish.__doc__
    return gated


@_gated_before_refusal
def finish_cancelled(state: FloatArray, rbuf: FloatArray, jac: FloatArray, y: FloatArray) -> int:
    """Finish an update the kernel left with ``CANCELLED``; returns its status (OK or a failure).

    The kernel stopped because some variance of its Joseph-form posterior
    (``rbuf``'s ``_PN`` block, of status ``rbuf[_VEC, _META, _JOSEPH]``) shrank
    more than ``_SHRINK_LIMIT``-fold, a sign that ``A P = P - K (H P)`` cancelled,
    or a first-order estimate of the Joseph P's error exceeds ``_P_SURE``
    (:func:`_joseph_in_doubt`: H P cancelling, or K and H), or the Joseph P
    failed its check (which the exact posterior may still pass). (Or because
    S's pivots say S is ill-conditioned, ε κ(S) > 2⁻³⁰, of any size (before
    review 41 at most ``_EXACT_ELIMINATION_MAX`` components, before review 40 8;
    without an exact route the kernel's x and P only where the information form
    vouches for them, and, without a gate, its NIS where bounds of the exact one
    (:func:`_nis_interval`) are not within 2⁻²⁰ of each other, else their
    midpoint; review 44, before which the kernel's NIS always stood): a linear combination of states
    measured twice far more precisely than it is known, or H P Hᵀ
    cancelling (for one component too, since review 29), where no variance
    need shrink, but the kernel's NIS and x, from its solve with S, are off
    by about ε κ(S). Here κ(S) is
    :func:`_s_amplification`, which counts that cancellation: with S's
    condition alone, before review 28, an NIS of 298.8 for an exact 4.18
    was reported.) The cancellation's rounding error E enters the result
    as ``E Aᵀ`` (A = I - K H; see
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
    its x, then have no correct digit). :func:`_information_update` computes
    it with residuals of the defining equations evaluated exactly (each
    product's terms summed with one rounding): P⁻¹ and R⁻¹ get one step of
    iterative refinement, P⁺ one step against J = P⁻¹ + Hᵀ R⁻¹ H, and its
    error is estimated from the residual J P⁺ - I left after that step plus
    a bound on J's own rounding, carried through J⁻¹. The Joseph result's
    error is then measured, not bounded: it is P⁺ (J P_Joseph - I), the
    same residual, to within P⁺'s error.

    It chooses P by these measured errors (relative to ``sqrt(P⁺ᵢᵢ P⁺ⱼⱼ)``),
    where P⁺'s estimate is at most 2⁻¹² (else the Joseph P and status are
    what there is, unmeasured):

    * P⁺ replaces the Joseph P where that failed its checks, or where the
      Joseph result's measured error exceeds twice P⁺'s (the Joseph form is
      then the less accurate; otherwise both are within 3 times P⁺'s error
      and the Joseph result stays);
    * the two states are compared: where they differ by more than
      ``max(2⁻³³ (|x| + |x⁺ - x|), sqrt(P⁺ᵢᵢ))`` one of them is wrong. x⁺
      (whose solves are refined too) replaces the kernel's x where a bound
      on its error (the roundings of g = Hᵀ R⁻¹ y and J's error, carried
      through P⁺) is within that tolerance; else the kernel's x (off by
      about ε κ(S), κ of S with its diagonal scaled) is kept for now;
    * where S is that ill-conditioned (ε κ(S) > 2⁻³⁰) and the two states
      agree, x⁺ replaces the kernel's where its bound is within
      ``_STEP_EXACT_SURE`` deviations or ``_STEP_RESOLUTION`` of
      ``|x| + |x⁺ - x|``;
    * where the kernel's x was replaced by x⁺ because they disagree, or
      where S is that ill-conditioned, the kernel's NIS, from the same solve
      with S, is replaced by the exact one (:class:`_ExactUpdate`) and the
      update gated again on it (``GATED``, the state unchanged, where it
      exceeds the gate); so too where the information form is not trusted
      and S is that ill-conditioned (measured: the kernel's NIS 7.14 for an
      exact 9.07, accepted at a gate of 8.1). (Before review 26 an
      ill-conditioned S whose states disagreed, x⁺ not trusted, kept the
      kernel's NIS: 4.61 for an exact 2128.)

    Then the state: the one chosen above only where a bound on its error is
    within ``_STEP_EXACT_SURE`` deviations (2⁻²⁰; before review 33 a quarter,
    which kept the kernel's x up to 1.5e-3 deviations off where x⁺ was within
    1e-7 of one, and before review 38 still a quarter for measurements of more
    than 8 components, which had no exact state: the
    kernel's x up to 0.013 deviations off where x⁺'s bound was 1.4e-4) or
    ``_STEP_RESOLUTION`` of ``|x| + |x⁺ - x|`` (x⁺'s own bound; for the
    kernel's x, ``|x_kernel - x⁺|`` plus x⁺'s bound, the only bound it has:
    ε κ(S) of its scale says nothing where the posterior's deviations lie far
    below it); else (and always where the information form
    is not trusted: nothing bounds the kernel's x there; and wherever the
    exact NIS was computed, from whose elimination the exact state costs
    about 0.02 ms more: before review 27 a vouched x⁺ was committed there,
    1.25 ulps off where the kernel's x was exact) the exact posterior mean
    ``x + P Hᵀ S⁻¹ y`` in rational arithmetic, rounded once
    (:class:`_ExactUpdate`; ``STATE_OVERFLOW`` where it is beyond float64).
    (Before review 40, measurements of more than ``_EXACT_CANCELLED_MAX_M``
    components took x⁺ where its bound was within a quarter deviation,
    else kept the chosen state.) (Before review 26 the kernel's x
    was committed, with status OK, up to 1e38 posterior deviations off: in
    a case with ε κ(S) 0.35, 315 deviations, 45,000 ulps; and updates the
    Joseph form failed with no state trusted were refused.)

    And the covariance: the one chosen above only where its measured error
    is at most ``_P_SURE`` (2⁻⁴⁰, an ordinary update's accuracy); else the
    exact posterior ``P - (H P)ᵀ S⁻¹ (H P)``, rounded once (:class:`_ExactUpdate`,
    the same exact computation as the exact state and NIS), where it passes
    the kernels' test of a covariance (:func:`_is_covariance`; an update the
    Joseph form failed is then applied). Where it does not (float64 holds no
    covariance there: a scaled condition beyond about 1e16), a covariance
    that passed its checks (the Joseph P or P⁺) is committed where it lies
    within ``_P_NEAR`` (2⁻²⁰) of it, else the update is refused
    (``NOT_POSITIVE_DEFINITE``, or the Joseph form's failure).

    The exact arithmetic (:class:`_ExactUpdate`) eliminates S for at most
    ``_EXACT_CANCELLED_MAX_M`` components; above, S or R's blocks and
    ``I + P Hᵀ R⁻¹ H`` (the information form, exactly), whichever is the
    cheaper with at most ``_EXACT_ELIMINATION_MAX`` rows (:func:`_exact_route`).
    Where neither is, an update that needs it (no state or covariance vouched
    for) raises ``FilterError``, nothing committed. (Before review 26 the Joseph P
    stood wherever the information form was not trusted, its error
    unmeasured: up to 3.7e20 of the posterior's scale in 3000 random
    updates, 2.3e93 in 18,000 of another kind; and P⁺ was committed with an
    estimated error up to 2⁻¹², 1e-5 off. Before review 39 that was still so
    for every measurement of more than 8 components:
    in 600 random precise updates of 9 and 10 components the Joseph P was
    committed up to 10.7 % and the kernel's x 0.21 of the posterior's
    deviations off, 3.2 deviations where a trusted x⁺'s bound exceeded a
    quarter; measurements of 9 to ``_EXACT_CANCELLED_MAX_M`` components now
    take the exact posterior, state and NIS as the smaller ones do, at
    2-25 ms for up to 4 states. Before review 40 measurements above it were
    as before: of 97 random precise updates of 13 to 16 components 53 were
    committed with P more than 2⁻⁴⁰ (up to 53 %) or x more than 2⁻²⁰
    deviations off (up to 0.98), of 39 of 17 to 24 components 17 (P up to
    0.76 %, x up to 5.4 deviations).)

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
    regate = False
    # Whether new_x has no bound within _STEP_EXACT_SURE deviations or _STEP_RESOLUTION
    # of its size: then the exact state replaces it (refused where there is none).
    unvouched = True
    # The measured error of new_p in units of ε (inf: none), and the covariances
    # that passed their checks, for where the exact one does not.
    p_error = math.inf
    checked = [joseph] if status == OK else []
    route = _exact_route(n, rbuf[_RS, :m, :m])
    exact = route is not None
    if route is None:
        # Without the information form nothing can vouch for the update: refused from
        # sizes where it exceeds the cap (review 43, EKFREV5; before, made first: 140 s
        # for a dense R of 800 components, then refused).
        work = _refinement_work(p, _r_blocks(rbuf[_RS, :m, :m]))
        if work > _EXACT_POSTERIOR_WORK_MAX:
            raise _PastTheLimit(
                f"the information form of a measurement of {m} components far more precise "
                f"than the estimate would take about {work * _EXACT_POSTERIOR_WORK_SECONDS:.0f}"
                f" s to refine, more than the "
                f"{_EXACT_POSTERIOR_WORK_MAX * _EXACT_POSTERIOR_WORK_SECONDS:.0f} s allowed, "
                f"and its exact arithmetic would eliminate more than {_EXACT_ELIMINATION_MAX} "
                "rows (update with fewer components at a time, or with a diagonal R)"
            )
    with np.errstate(all="ignore"):
        found = _information_update(p, jac, rbuf[_RS, :m, :m], y)
        if found is None or not _EPS * found.error <= _WELL_CONDITIONED:
            # The information form is not trusted: the Joseph P (and status) stand, but
            # not the kernel's NIS where S is ill-conditioned (measured 7.14 for an
            # exact 9.07, passing a gate of 8.1): the exact one, gated again; nor its
            # x, which nothing bounds: the exact state.
            regate = exact and not _EPS * _s_amplification(rbuf, p, jac) <= _STATE_TRUSTED
        else:
            posterior = found.posterior
            deviation = np.sqrt(posterior.diagonal())
            # P⁺ where the Joseph form failed, or where its measured error is more
            # than twice P⁺'s: the Joseph result is then the less accurate.
            joseph_error = found.error_of(joseph) if status == OK else math.inf
            take_p = status != OK or not joseph_error <= 2.0 * found.error
            p_error = found.error if take_p else joseph_error
            checked.append(posterior)
            step = found.step
            x_info = x + step
            apart = x_info - x_kernel
            for i in np.flatnonzero(state[n + 1]):  # the angles, wrapped
                x_info[i] = wrap_float(float(x_info[i]))
                apart[i] = wrap_float(float(apart[i]))
            size = np.abs(x) + np.abs(step)
            tolerance = np.maximum(2.0**-33 * size, deviation)
            within = np.maximum(_STEP_EXACT_SURE * deviation, _STEP_RESOLUTION * size)
            info_bound = found.step_error if np.isfinite(x_info).all() else np.full(n, math.inf)
            # The kernel's x is no further from the posterior mean than from x⁺ plus x⁺'s
            # bound: the only bound it has (ε κ(S) of its scale can be 1e38 posterior
            # deviations, where those are far below an ulp of the state; review 26).
            kernel_bound = np.abs(apart) + info_bound
            if not (np.abs(apart) <= tolerance).all():
                # One state is wrong: x⁺ where its error bound is within the
                # tolerance. Else the kernel's, within about ε κ(S) of its scale:
                # an update the Joseph form failed is refused where that exceeds
                # 2⁻³⁰ (1e-9) and no exact state replaces it.
                if (info_bound <= tolerance).all():
                    new_x = x_info
                    # The kernel's x more than a deviation off: its NIS, from the
                    # same solve with S, is as suspect (measured 21.0 for an exact 9.38).
                    regate = exact
                else:
                    ill = not _EPS * _s_amplification(rbuf, p, jac) <= _STATE_TRUSTED
                    regate = exact and ill
                    if status != OK and ill and not exact:
                        take_p = False  # no state to trust: refused, after the gate
            elif exact:
                ill = not _EPS * _s_amplification(rbuf, p, jac) <= _STATE_TRUSTED
                if ill:
                    # Within the tolerance of each other, but the kernel's x and NIS
                    # come from an S too ill-conditioned to trust (ε κ(S) > 2⁻³⁰;
                    # measured with κ(S) 5e16: x 0.4 deviations off, NIS 0.079 for an
                    # exact 0.555): the exact NIS, and x⁺ where its bound is well
                    # below a deviation or at the state's float64 resolution. "Agree"
                    # is within 2⁻³³ of the state's size, which says nothing where
                    # the posterior's deviation is far below that: committed with P⁺,
                    # the kernel's x was 8.7e5 deviations off (ε κ(S) 5.5; x⁺'s bound
                    # 4.1e3 deviations; review 25), and with the Joseph P 315
                    # deviations (45,000 ulps; ε κ(S) 0.35; review 26).
                    regate = True
                    if (info_bound <= within).all():
                        new_x = x_info
            # The state committed is one whose bound is within _STEP_EXACT_SURE
            # deviations or the state's float64 resolution: the one chosen above, else
            # the exact state (refused where there is none). (Not x⁺ before the exact
            # one: where the kernel's x is unvouched but 1e-16 deviations off, x⁺ within
            # 2⁻²⁰ was 2.5e-9 off; review 33. Vouched within a quarter deviation for more
            # than 8 components, the kernel's x was up to 0.245 deviations off where x⁺
            # was 3e-7 off; review 38; x⁺ within a quarter, 0.65 deviations off for 13
            # components; review 39.)
            bound = info_bound if new_x is x_info else kernel_bound
            unvouched = not (bound <= within).all()
            if take_p:
                new_p, status = posterior, OK
    if route is None:
        if status == OK and (unvouched or not _EPS * p_error <= _P_SURE):
            # Before review 40 the unmeasured P and an x within a quarter deviation
            # stood here (9.4 % and 0.65 deviations off in draws of 13 components).
            raise _PastTheLimit(
                f"a measurement of {m} components far more precise than the estimate: "
                "no float64 posterior is vouched for, and its exact arithmetic would "
                f"eliminate more than {_EXACT_ELIMINATION_MAX} rows (use a diagonal R, or "
                "update with fewer components at a time)"
            )
        r = rbuf[_RS, :m, :m]
        # The gate again on the exact NIS alone, within the cap, else on bounds of it
        # (review 44, EKFREV6): where the update fails (a measurement the gate rejects
        # is rejected, not refused; before review 43, EKFREV5, the kernel's NIS stood),
        # and where the kernel's NIS passed the gate from an S too ill-conditioned to
        # trust it (refused where neither decides: _gate_past_the_cap).
        if rbuf[_VEC, _META, _GATE] < math.inf and (
            status != OK or not _EPS * _s_amplification(rbuf, p, jac) <= _STATE_TRUSTED
        ):
            gated = _gate_past_the_cap(p, jac, r, y, rbuf, refuse=status == OK)
            if gated != OK:
                return gated
        elif status == OK and not _EPS * _s_amplification(rbuf, p, jac) <= _STATE_TRUSTED:
            # No gate: the kernel's NIS, from an S too ill-conditioned to trust, was
            # reported (up to 10 % off): the midpoint of bounds of the exact NIS where
            # they are within 2⁻²⁰ of each other (review 44, EKFREV6), else it stands.
            bounds = _nis_interval(p, jac, r, y)
            if bounds is not None and bounds[1] - bounds[0] <= 2.0**-20 * bounds[0]:
                rbuf[_VEC, _META, 1] = _midpoint(*bounds)
        if status != OK:
            return status
    found_exact = None
    if regate:
        # The exact NIS (as finish_singular_s), gated again, before any failure is
        # reported (a measurement the gate rejects is rejected): the kernel gated
        # with its own.
        found_exact = _ExactUpdate(p, jac, rbuf[_RS, :m, :m], y, route or [])
        gated = _gate_on(rbuf, found_exact.nis())
        if gated != OK:
            return gated
    if exact and not _EPS * p_error <= _P_SURE:
        # No covariance is vouched for: the exact posterior, where float64 holds it
        # as a covariance; else one that passed its checks within _P_NEAR of it.
        if found_exact is None:
            found_exact = _ExactUpdate(p, jac, rbuf[_RS, :m, :m], y, route or [])
        p_exact = found_exact.posterior(p)
        if p_exact is not None and _is_covariance(p_exact):
            new_p, status = p_exact, OK
        else:
            ordered = sorted(checked, key=lambda c: c is not new_p)  # new_p first
            near = [c for c in ordered if _error_against(c, p_exact) <= _P_NEAR]
            if not near:
                return status if status != OK else NOT_POSITIVE_DEFINITE
            new_p, status = near[0], OK
    if status != OK:
        return status
    # The exact state where no bound vouches for one, and wherever the exact NIS was
    # computed (S ill-conditioned): from its elimination the exact state costs about
    # 0.02 ms more, and a vouched state may still be a few ulps off where the kernel's
    # was exact (the information form's 1.25 ulps off; review 27).
    if exact and (unvouched or regate):
        if found_exact is None:
            found_exact = _ExactUpdate(p, jac, rbuf[_RS, :m, :m], y, route or [])
        x_exact = found_exact.state(x)
        if x_exact is None:  # the posterior mean is beyond float64
            return STATE_OVERFLOW
        for i in np.flatnonzero(state[n + 1]):  # the angles, wrapped
            x_exact[i] = wrap_float(float(x_exact[i]))
        new_x = x_exact
    state[STATE_X] = new_x
    p[...] = new_p
    return OK


def _regate(
    p: FloatArray, jac: FloatArray, rbuf: FloatArray, y: FloatArray, route: list[list[int]]
) -> int:
    """Leave the exact NIS of the update in ``rbuf`` and gate on it: OK, NIS_OVERFLOW or GATED.

    ``route`` is :func:`_exact_route`'s (not None).
    """
    m = jac.shape[0]
    return _gate_on(rbuf, _ExactUpdate(p, jac, rbuf[_RS, :m, :m], y, route).nis())


def _gate_on(rbuf: FloatArray, nis: float) -> int:
    """Leave the exact ``nis`` in ``rbuf`` and gate on it: OK, NIS_OVERFLOW or GATED."""
    rbuf[_VEC, _META, 1] = nis
    if not nis < math.inf:
        return NIS_OVERFLOW
    if nis > rbuf[_VEC, _META, _GATE]:
        return GATED
    return OK


@_gated_before_refusal
def finish_singular_s(state: FloatArray, rbuf: FloatArray, jac: FloatArray, y: FloatArray) -> int:
    """Finish an update the kernel left with ``S_NOT_POSITIVE_DEFINITE``; returns its status.

    P and R are positive definite (the kernels and the public layer check them),
    so the exact S = H P Hᵀ + R always is: a kernel finding the computed S not
    positive definite has met its rounding, e.g. a state measured twice (two
    rows of H alike) each far more precisely than it is known (R/P below about
    1e-16: S = [[p + r, p], [p, p + r]] rounds to a singular matrix), where the
    posterior is well determined. This takes the information form of
    :func:`finish_cancelled` (:func:`_information_update`, no solve with S) for
    x and P, and the NIS yᵀ S⁻¹ y from S in exact rational arithmetic
    (:func:`_exact_nis`, rounded once: any float form of it loses every digit
    here). The update is gated first, on that NIS, then committed as the
    kernel's would be: ``RESIDUAL_OVERFLOW``, ``NIS_OVERFLOW``, ``GATED``,
    ``STATE_OVERFLOW`` or ``OK``, the NIS left in ``rbuf``. The state is the
    exact posterior mean (:func:`_exact_state`, from the same elimination as
    the NIS). (Before review 27: x⁺ where the bound on its step was within
    a quarter deviation or ``_STEP_RESOLUTION`` of ``|x| + |s|``,
    193,586 ulps off in one case. Before review 26: x⁺ within
    ``max(2⁻³³ (|x| + |s|), sqrt(P⁺ᵢᵢ))``, which let it be 8.1e4 deviations
    off where those lie far below 2⁻³³ of its size, and the update was
    refused beyond that.) P is P⁺ where its estimated error
    is at most ``_P_SURE``, else the exact posterior (:func:`_exact_posterior`)
    where it passes the kernels' test of a covariance, else P⁺ where that is
    trusted (its error estimate at most 2⁻¹², as in :func:`finish_cancelled`)
    and within ``_P_NEAR`` of the exact one. It stays ``S_NOT_POSITIVE_DEFINITE``
    (the state unchanged) where a measurement the gate passes has none of
    these (before review 26: wherever the information form was not trusted;
    and P⁺ was committed up to 1e-5 off). Where the exact arithmetic would
    eliminate more than ``_EXACT_ELIMINATION_MAX`` rows (:func:`_exact_route`;
    before review 40, for every measurement of more than 8 components) it
    gates on a lower bound of the exact NIS (:func:`_nis_lower_bound`):
    ``GATED_AT_LEAST`` (the bound left in ``rbuf`` as the NIS) where that exceeds
    the gate, so that readings far apart are rejected by a gate, not refused
    (before review 41 it raised), and ``NIS_OVERFLOW`` where the bound is beyond
    float64, with or without a gate (as the kernel's; before review 41 REVEKF, it
    raised without one); else it
    raises ``FilterError`` saying so, nothing changed (before review 40 the
    caller's "innovation covariance S is not positive definite" alone).
    Above ``_EXACT_CANCELLED_MAX_M`` components the exact NIS, state and posterior may come from the
    information form in exact arithmetic (:class:`_ExactUpdate`).
    """
    n = state.shape[1]
    m = jac.shape[0]
    r = rbuf[_RS, :m, :m]
    route = _exact_route(n, r)
    x = state[STATE_X]
    p = state[STATE_P : STATE_P + n]
    if not np.isfinite(y).all():
        rbuf[_VEC, _META, 1] = math.inf
        return RESIDUAL_OVERFLOW
    if route is None:
        # The exact S is positive definite; only the size limit refuses it (before
        # review 40 the message was "innovation covariance S is not positive definite"
        # alone, as if P or R were at fault), after the gate on a lower bound of the
        # exact NIS (_gated_before_refusal; before review 41 a measurement any gate
        # rejects, readings 1e150 deviations apart, raised).
        raise _PastTheLimit(
            "innovation covariance S is not positive definite as computed in float64 "
            f"(a measurement of {m} components far more precise than the estimate), "
            f"and its exact arithmetic would eliminate more than {_EXACT_ELIMINATION_MAX} "
            "rows (use a diagonal R, or update with fewer components at a time)"
        )
    # The gate first: the exact NIS needs no update, so a measurement the gate
    # rejects is rejected whether or not the information form is trusted for it
    # (readings 1e150 deviations apart raised FilterError instead).
    exact = _ExactUpdate(p, jac, r, y, route)
    gated = _gate_on(rbuf, exact.nis())
    if gated != OK:
        return gated
    with np.errstate(all="ignore"):
        found = _information_update(p, jac, r, y)
        if found is None or not _EPS * found.error <= _WELL_CONDITIONED:
            found = None
        if found is not None and _EPS * found.error <= _P_SURE:
            posterior = found.posterior
        else:
            # No covariance is vouched for: the exact posterior, where float64 holds
            # it as a covariance, else P⁺ within _P_NEAR of it.
            p_exact = exact.posterior(p)
            if p_exact is not None and _is_covariance(p_exact):
                posterior = p_exact
            elif found is not None and _error_against(found.posterior, p_exact) <= _P_NEAR:
                posterior = found.posterior
            else:
                return S_NOT_POSITIVE_DEFINITE
    # The exact state, from the elimination made for the NIS (about 0.02 ms more): a
    # state the information form's bound vouched for was up to 32 ε of its size off
    # (before review 27), and 8.1e4 deviations with the looser bound before review 26.
    x_new = exact.state(x)
    if x_new is None:  # the posterior mean is beyond float64
        return STATE_OVERFLOW
    for i in np.flatnonzero(state[n + 1]):  # the angles, wrapped
        x_new[i] = wrap_float(float(x_new[i]))
    if not np.isfinite(x_new).all():
        return STATE_OVERFLOW
    state[STATE_X] = x_new
    p[...] = posterior
    return OK


def _nis_lower_bound(p: FloatArray, jac: FloatArray, r: FloatArray, y: FloatArray) -> float:
    """A lower bound on the exact NIS ``yᵀ S⁻¹ y``, S = H P Hᵀ + R: ``maxₖ yₖ² / dₖ``.

    For a positive definite S and any k, ``yᵀ S⁻¹ y >= yₖ² / Sₖₖ`` (Cauchy-Schwarz in
    the inner product of S⁻¹: ``yₖ² = (eₖᵀ y)² <= (eₖᵀ S eₖ)(yᵀ S⁻¹ y)``), so any
    upper bound dₖ of the exact Sₖₖ gives one: the least of ``cₖ = uₖ² + Rₖₖ``, ``uₖ =
    Σⱼ |Hₖⱼ| sqrt(Pⱼⱼ)`` (``|Pᵢⱼ| <= sqrt(Pᵢᵢ Pⱼⱼ)``), and the computed Hₖ P Hₖᵀ + Rₖₖ
    plus a bound on its rounding (2⁻³¹ cₖ, more than the (2n + 3) ε cₖ of a product of
    n terms for n up to 2²⁰ states, and, among subnormal numbers, where roundings are
    absolute, (n + 2) 2⁻¹⁰⁷³ (1 + Σⱼ |Hₖⱼ|)); the largest quotient is taken in exact
    rational arithmetic and rounded down, inf where it is beyond float64 (the exact
    NIS is then too). For a gate where the exact NIS would eliminate too many rows:
    readings far apart (1e150 deviations) are rejected by it. The mean
    ``Σₖ yₖ² / (m cₖ)`` of review 41 (S <= m C) is never above it: a combination of
    correlated states (Hₖ P Hₖᵀ far below cₖ) or one reading far off among m gave a
    bound up to m cₖ / Sₖₖ times lower, refusing with ``FilterError`` updates whose
    exact NIS a gate rejects (review 42, EKFREV3). Review 41 (REVEKF) found that bound
    22 % above the exact NIS among subnormal numbers, a cₖ of 2.44 × 2⁻¹⁰⁷⁴ rounded to
    2 × 2⁻¹⁰⁷⁴: the margins here are absolute there.
    """
    from fractions import Fraction

    n = p.shape[0]
    with np.errstate(all="ignore"):  # overflows give inf, a weaker (still true) bound
        reach = np.abs(jac) @ np.sqrt(p.diagonal())
        r_diag = r.diagonal()
        c_up = (reach * reach + r_diag) * (1.0 + 2.0**-31) + 2.0**-1072
        s_diag = np.einsum("kj,kj->k", jac @ p, jac)
        slack = (n + 2) * 2.0**-1073 * (np.abs(jac).sum(axis=1) + 1.0)
        # 2⁻³⁰ uₖ² + 2⁻³¹ Rₖₖ >= 2⁻³¹ cₖ, and finite where S is though cₖ is not.
        margin = (reach * 2.0**-15) ** 2 + 2.0**-31 * r_diag
        s_up = s_diag + r_diag + margin + slack
        # cₖ where s_up is NaN (inf - inf where H P overflowed), or not positive.
        d = np.where(s_up > 0.0, np.minimum(c_up, s_up), c_up)
        approx = (y / np.sqrt(d)) ** 2
    top = float(approx.max())
    # The quotients within 2⁻²⁰ of the largest as rounded, exactly (every one is a bound).
    candidates = np.flatnonzero(approx >= top * (1.0 - 2.0**-20)) if top > 0.0 else ()
    best = Fraction(0)
    for k in candidates:
        yk = Fraction(float(y[k]))
        best = max(best, yk * yk / Fraction(float(d[k])))
    try:
        out = float(best)
    except OverflowError:
        return math.inf
    return math.nextafter(out, 0.0) if Fraction(out) > best else out


@njit_no_refcount
def gated_s_ill(state: FloatArray, rbuf: FloatArray, jac: FloatArray) -> bool:
    """Whether the S of a gated update is ill-conditioned for its rounding error.

    The update kernel's test (see :func:`_update`), on the S and the pivots it
    left in ``rbuf`` where it gated: ``max cₖ / Dₖ`` above ``_PIVOT_LIMIT``,
    ``cₖ = max(uₖ² + Rₖₖ, Sₖₖ)``, ``uₖ = Σⱼ |Hₖⱼ| sqrt(Pⱼⱼ)``, with the same
    floats. A kernel of its own, typed once for every n and m (run-time sizes)
    and compiled only when first needed, as :func:`adopt_positive_q`: in the
    update kernels the test cost every filter's first use 3 % more compile
    time, and in NumPy 2.2 µs of a gated update's 5.5. ``jac`` (m, n) is the H
    the kernel took.
    """
    n = state.shape[1]
    m = jac.shape[0]
    s = rbuf[_S]
    rs = rbuf[_RS]
    inv_diag = rbuf[_VEC, _INV_DIAG]
    for k in range(m):
        acc = 0.0
        for j in range(n):
            hkj = jac[k, j]
            if hkj != 0.0:
                acc += abs(hkj) * math.sqrt(state[STATE_P + j, j])
        c = acc * acc + rs[k, k]
        if c < s[k, k]:
            c = s[k, k]
        if c * inv_diag[k] > _PIVOT_LIMIT:
            return True
    return False


@_gated_before_refusal
def retry_gated(state: FloatArray, rbuf: FloatArray, jac: FloatArray, y: FloatArray) -> int:
    """Check a kernel's ``GATED`` verdict where its S is ill-conditioned; returns the status.

    The kernel's NIS comes from its LDLᵀ factorisation of the computed S, off
    by about ε κ(S) relative (measured 21.0 for an exact 9.38 at κ(S) 3e16: a
    measurement that passes a gate of 11.3 was rejected). Where the pivots say
    S is that ill-conditioned for its rounding error, the update kernel's test
    (``max cₖ / Dₖ`` above 2⁻³⁰ / ε, ``cₖ = max(uₖ² + Rₖₖ, Sₖₖ)`` with
    ``uₖ = Σⱼ |Hₖⱼ| sqrt(Pⱼⱼ)``: a lower bound on how far S's rounding error,
    within about n ε sqrt(cₖ cₗ) in entry (k, l), reaches the NIS; read from
    the kernel's factorisation by :func:`gated_s_ill`. With Sₖₖ for cₖ, before
    review 28, S's own condition only, which missed H P Hᵀ cancelling: the NIS
    298.8 for an exact 4.18, rejected at a gate of 13.28) and the measurement
    has an exact route (:func:`_exact_route`: at most
    :data:`_EXACT_ELIMINATION_MAX` components, or a diagonal or block-diagonal
    R; before review 41 only the former, before review 40 at most 8
    components), it is gated again on the exact NIS (:class:`_ExactUpdate`, left
    in ``rbuf``): ``GATED`` or ``NIS_OVERFLOW`` where that rejects it, else
    ``GATE_PASSED``: the caller runs the kernel again without the gate
    (:func:`set_gate`), as an ungated update, and reports the exact NIS
    (before, ``GATED`` stood with the kernel's NIS: measured 11.16 for an
    exact 11.01, rejected at a gate of 11.12). So a measurement the gate
    passes is the ungated update, bit for bit (finishing it here as
    :func:`finish_singular_s` does, with the information form's P⁺ where the
    ungated update keeps the Joseph form's, gave a P 5.8e-8 relative away
    from it; review 25). With no exact route (more than
    :data:`_EXACT_ELIMINATION_MAX` components of a dense R) the same is done with
    the exact NIS alone (:func:`_exact_nis`, S's elimination) where its work,
    bounded from sizes (:func:`_exact_nis_work`), is within
    ``_EXACT_POSTERIOR_WORK_MAX``; past it on rigorous bounds of the exact NIS
    (:func:`_gate_past_the_cap`, review 44: passed where they lie wholly at or below
    the gate, the NIS reported their midpoint, rejected where wholly above), and
    where they straddle it rejected where a lower bound exceeds the gate
    (``GATED_AT_LEAST``, see :func:`_gated_before_refusal`) and refused with
    ``FilterError`` otherwise, the state unchanged (before review 44 every update
    past the cap that lower bound did not reject was refused; before review 43 the
    kernel's ``GATED`` stood there: NIS
    28.28, or 26.11 by BLAS kernel, for an exact 25.81, rejected at a gate between;
    EKFREV3, EKFREV5). Elsewhere (S well-conditioned) ``GATED`` stands. About 3 µs
    for a well-conditioned S (the whole gated update).
    """
    m = jac.shape[0]
    # m = 1 too, as in the update kernel: a scalar S whose H P Hᵀ cancels is as far off
    # as its terms are large against it (review 29: NIS 1.4266 for an exact 1.4040,
    # rejected at a gate of 1.415; before, m = 1 was not tested, κ(S) being 1).
    if not gated_s_ill(state, rbuf, jac):
        return GATED
    n = state.shape[1]
    # Any m with an exact route (before review 41 at most _EXACT_ELIMINATION_MAX
    # components, a diagonal R's too: 25 readings rejected at a gate their exact NIS
    # passes).
    r = rbuf[_RS, :m, :m]
    route = _exact_route(n, r)
    p = state[STATE_P : STATE_P + n]
    if route is None:
        # No exact route: the exact NIS alone (S's elimination, no posterior) where its
        # work, bounded from sizes before any, is within the exact posterior's cap; else
        # bounds of it (review 44), and where they straddle the gate refused, after the
        # gate on a lower bound (_gated_before_refusal). Before
        # review 43 the kernel's GATED stood: NIS 28.28 (26.11 by BLAS kernel) for an
        # exact 25.81, rejected at a gate between them (EKFREV3, EKFREV5).
        status = _gate_past_the_cap(p, jac, r, y, rbuf, refuse=True)
    else:
        status = _regate(p, jac, rbuf, y, route)
    # The exact NIS (left in rbuf) passed the gate: the kernel's update without the
    # gate, as an ungated update.
    return GATE_PASSED if status == OK else status


def _gate_past_the_cap(
    p: FloatArray, jac: FloatArray, r: FloatArray, y: FloatArray, rbuf: FloatArray, refuse: bool
) -> int:
    """Gate an update whose kernel NIS (in ``rbuf``) cannot decide it, with no exact route.

    The exact NIS alone (:func:`_exact_nis`) where its work, bounded from sizes before
    any (:func:`_exact_nis_work`), is within ``_EXACT_POSTERIOR_WORK_MAX``: OK, GATED
    or NIS_OVERFLOW (:func:`_gate_on`). Past it, rigorous bounds of it
    (:func:`_nis_interval`, review 44, EKFREV6; before, the update was refused
    unless :func:`_nis_lower_bound` rejected it): wholly at or below the gate, OK
    with the interval's midpoint left as the NIS; wholly above, GATED with the
    midpoint where the bounds are within 2⁻²⁰ of each other, else GATED_AT_LEAST
    with the lower one. Where they straddle the gate (or there are none: the float
    S not positive definite) it raises :class:`_PastTheLimit` (``refuse``; the
    gate is then tried on :func:`_nis_lower_bound`, :func:`_gated_before_refusal`),
    or returns OK with ``rbuf`` unchanged (not ``refuse``: the update fails anyway).
    """
    work = _exact_nis_work(p, jac, r, y)
    if work <= _EXACT_POSTERIOR_WORK_MAX:
        return _gate_on(rbuf, _exact_nis(p, jac, r, y))
    gate = float(rbuf[_VEC, _META, _GATE])
    found = _nis_interval(p, jac, r, y)
    bounds = ""
    if found is not None:
        low, high = found
        middle = _midpoint(low, high)
        if high <= gate or (low > gate and high - low <= 2.0**-20 * low):
            return _gate_on(rbuf, middle)
        if low > gate:
            rbuf[_VEC, _META, 1] = low
            return GATED_AT_LEAST
        bounds = f", bounds of it ({low:.6g} to {high:.6g}) straddle the gate"
    else:
        bounds = ", no bounds of it were found (S not positive definite in float64)"
    if not refuse:
        return OK
    refusal = _PastTheLimit(
        f"the gate cannot decide on a measurement of {jac.shape[0]} components: its "
        "innovation covariance S is too ill-conditioned for the NIS computed in "
        f"float64 ({rbuf[_VEC, _META, 1]:.6g}) to be trusted, its exact NIS would take "
        f"about {work * _EXACT_POSTERIOR_WORK_SECONDS:.0f} s of exact arithmetic, more "
        f"than the {_EXACT_POSTERIOR_WORK_MAX * _EXACT_POSTERIOR_WORK_SECONDS:.0f} s "
        f"allowed{bounds}, and a lower bound of it does not exceed the gate (update with "
        "fewer components at a time, or with a diagonal R)"
    )
    refusal.tried = True
    raise refusal


def _midpoint(low: float, high: float) -> float:
    """The midpoint of ``low <= high``, rounded into them.

    ``0.5 * low + 0.5 * high`` alone left subnormal bounds: halving 3 and 5 times
    2⁻¹⁰⁷⁴ rounds to even, (3, 3) gave 4 and (5, 5) gave 4 (times 2⁻¹⁰⁷⁴), a NIS
    outside the bounds the gate decided on (review 44, EKFCHECK).
    """
    return min(max(0.5 * low + 0.5 * high, low), high)


def _exact_nis(p: FloatArray, jac: FloatArray, r: FloatArray, y: FloatArray) -> float:
    """``yᵀ S⁻¹ y``, S = H P Hᵀ + R, in exact arithmetic rounded once (inf beyond float64).

    float64 values are dyadic rationals: as integers over a common power of two
    (:func:`_dyadic`) S is an exact integer matrix, and Bareiss's fraction-free
    elimination of ``[S | y]`` (:func:`_eliminated`) gives, with ``Dₖ`` the
    leading principal minors of S (``D₋₁ = 1``), the NIS ``Σ cₖ² / (Dₖ₋₁ Dₖ)``,
    ``cₖ`` the eliminated right-hand side (the LDLᵀ form ``Σ uₖ² / dₖ``,
    ``dₖ = Dₖ / Dₖ₋₁``). S is positive definite in exact arithmetic (P and R
    are), so no minor is zero. Used only where the computed S lost its
    definiteness, and so every digit of its NIS: measured 0.1 ms for
    m = n = 2, 0.3 ms for m = 3, n = 6, and for n = 15 0.8-2.6 ms for m = 8,
    3.6-20 ms for m = 12 (the cost grows as m³ times the size of the minors,
    which grows with how far apart the matrices' exponents lie; see
    :data:`_EXACT_CANCELLED_MAX_M`).
    """
    return _nis_of(_eliminated(p, jac, r, y))


def _denominator_bits(a: FloatArray) -> int:
    """An upper bound on :func:`_dyadic`'s k for ``a`` (``a = A / 2**k``), from exponents only.

    A nonzero float ``f 2**e`` (``0.5 <= |f| < 1``) is an integer over at most
    ``2**(53 - e)`` (over ``2**1074`` for a subnormal: ``e >= -1073``), so k is at most
    ``53 - min e``, and 0 for integers; O(size) in NumPy, no Python integers.
    """
    nonzero = a[a != 0.0]
    if nonzero.size == 0:
        return 0
    return max(0, 53 - int(np.frexp(nonzero)[1].min()))


def _integer_bits(a: FloatArray) -> int:
    """An upper bound on the bit length of :func:`_dyadic`'s integers for ``a``.

    ``|a| < 2**max e`` (frexp's exponents), so ``|A| = |a| 2**k < 2**(max e + k)``,
    k at most :func:`_denominator_bits`.
    """
    nonzero = a[a != 0.0]
    if nonzero.size == 0:
        return 0
    return max(0, _denominator_bits(a) + int(np.frexp(nonzero)[1].max()))


def _exact_nis_work(p: FloatArray, jac: FloatArray, r: FloatArray, y: FloatArray) -> float:
    """An upper estimate of :func:`_exact_nis`'s work, in ``_EXACT_POSTERIOR_WORK_MAX``'s units.

    Decided from sizes and exponents alone, before any exact arithmetic (a few
    O(m² + m n + n²) NumPy passes). The elimination of ``[S | y]`` makes about m³ / 3
    products and exact divisions of integers of up to b bits, the size of a minor of
    the integer S (or one with y's column): for a positive definite S every minor's
    magnitude is at most the product of the diagonal entries of its rows and of its
    columns' square roots (Hadamard, and ``|det S[I, J]|² <= det S[I, I] det S[J, J]``),
    so b is at most ``Σₖ bits(Sₖₖ 2**scale)`` plus y's bits, each ``Sₖₖ`` at most
    ``uₖ² + Rₖₖ`` (``uₖ = Σⱼ |Hₖⱼ| sqrt(Pⱼⱼ)``, as :func:`_nis_lower_bound`'s cₖ).
    work = m³ b², as the posterior's m² n b² counts a product of b-bit integers
    (b² overstates Karatsuba's growth: an upper estimate), plus the integer S's own
    m n (n + m) products (H P, then by H). Measured 2026-12: 28
    components of a dense R (EKFREV3's draw), b = 3874 as eliminated, estimate
    b <= 5.3e3 (y's column included) and 0.27 s at _EXACT_POSTERIOR_WORK_SECONDS,
    0.05-0.07 s CPU.
    inf where a bound overflows.
    """
    m = jac.shape[0]
    scale = max(2 * _denominator_bits(jac) + _denominator_bits(p), _denominator_bits(r))
    with np.errstate(all="ignore"):
        reach = np.abs(jac) @ np.sqrt(p.diagonal())
        c = (reach * reach + r.diagonal()) * (1.0 + 2.0**-20)
        y_top = float(np.max(np.abs(y)))
    if not (np.isfinite(c).all() and math.isfinite(y_top)):
        return math.inf
    # bits(Sₖₖ 2**scale) <= log2 Sₖₖ + scale + 1; y's integers (over 2**ky) likewise.
    bits = float(np.sum(np.floor(np.log2(c)) + 1.0)) + m * (scale + 1)
    if y_top > 0.0:
        bits += math.log2(y_top) + _denominator_bits(y) + 2.0 + math.log2(m)
    # And the integer S itself, before any elimination: H P's m n² products and their
    # m² n by H (review 43, EKFREV5: before, made before any cap was checked, m n² of
    # them unbounded in n), at _INFORMATION_OP_WORK a product plus their bits' square.
    return float(m) ** 3 * float(bits) ** 2 + _integer_s_work(p, jac)


def _integer_s_work(p: FloatArray, jac: FloatArray) -> float:
    """The work of :func:`_integer_s` from sizes: H P's m n² products and their m² n by H."""
    m, n = jac.shape
    h_bits = float(_integer_bits(jac))
    products = m * n * (n + m) * (_INFORMATION_OP_WORK + h_bits * (h_bits + _integer_bits(p)))
    return float(products)


def _integer_s(
    p: FloatArray, jac: FloatArray, r: FloatArray
) -> tuple[list[list[int]], list[list[int]], int, int]:
    """S = H P Hᵀ + R as integers over ``2**scale``, exactly; with H P over ``2**k_hp``.

    Returns ``(s, hp, scale, k_hp)``: :func:`_eliminated`'s integer S, shared with
    :func:`_nis_interval`.
    """
    m, n = jac.shape
    h_int, kh = _dyadic(jac)
    p_int, kp = _dyadic(p)
    r_int, kr = _dyadic(r)
    hp = [[sum(h[k] * p_int[k][j] for k in range(n) if h[k]) for j in range(n)] for h in h_int]
    scale = max(2 * kh + kp, kr)  # S = s / 2**scale
    up_hph = scale - 2 * kh - kp
    up_r = scale - kr
    s = [
        [
            (sum(hp[a][k] * h_int[b][k] for k in range(n) if h_int[b][k]) << up_hph)
            + (r_int[a][b] << up_r)
            for b in range(m)
        ]
        for a in range(m)
    ]
    return s, hp, scale, kh + kp


def _powers_of_two_scale(diag: FloatArray) -> FloatArray:
    """D (powers of two) taking the positive ``diag`` to [0.5, 2) in ``D a D``."""
    d: FloatArray = np.ldexp(1.0, -(np.frexp(diag)[1] // 2))
    return d


def _least_eigenvalue_bound(a: FloatArray, slack: FloatArray) -> float:
    """A rigorous lower bound on λmin of every symmetric ``a + E``, ``|E| <= slack``; 0 if none.

    A float Cholesky factor L of ``a - α I`` (α half of LAPACK's estimate of
    λmin(a)) with its residual bounded entry by entry: ``a - α I - L Lᵀ`` is
    within ``|fl(a - α I) - fl(L Lᵀ)|`` (rounded up), ``ε |a - α I|`` on the
    diagonal, and ``γₘ |L| |L|ᵀ`` (the error of any order of summation of m
    products, fused or not; BLAS's blocking changes the order only) plus
    ``m 2⁻¹⁰⁷⁰`` for products underflowing. Its 2-norm, with E's, is at most the
    largest row sum e of those bounds, so ``λmin(a + E) >= α - e`` (Weyl; the
    factorisation makes ``a - α I - residual`` positive semidefinite). O(m³) in NumPy.
    """
    m = a.shape[0]
    with np.errstate(all="ignore"):
        try:
            estimate = float(np.linalg.eigvalsh(a)[0])
        except np.linalg.LinAlgError:
            return 0.0
        if not estimate > 0.0 or not np.isfinite(a).all():
            return 0.0
        alpha = 0.5 * estimate
        shifted = a.copy()
        shifted[np.diag_indices(m)] -= alpha
        try:
            factor = cast("FloatArray", np.linalg.cholesky(shifted))
        except np.linalg.LinAlgError:
            return 0.0
        gamma = (m + 2) * _EPS / (1.0 - (m + 2) * _EPS)
        product = factor @ factor.T
        magnitude = np.abs(factor) @ np.abs(factor).T
        bound = np.abs(shifted - product) * (1.0 + 2.0 * _EPS)
        bound += 2.0 * gamma * magnitude + m * 2.0**-1070
        least = _shifted_margin(alpha, bound, shifted, slack)
        if least == 0.0 and m**3 * _RESIDUAL_TERM_WORK <= _EXACT_POSTERIOR_WORK_MAX:
            # The residual itself, each entry rounded once from its exact value
            # (_exact_residual, m³ terms): far below the γₘ bound's m ε per entry
            # where λmin is within a few m² ε (κ(R) 1e13 for 30 components).
            # (Dekker's products are exact but where one underflows: m 2⁻¹⁰⁷⁰ for those.)
            exact = np.abs(_exact_residual(factor, factor.T, shifted))
            exact = exact * (1.0 + 2.0 * _EPS) + m * 2.0**-1070
            least = _shifted_margin(alpha, exact, shifted, slack)
    return least


def _shifted_margin(
    alpha: float, bound: FloatArray, shifted: FloatArray, slack: FloatArray
) -> float:
    """``α - e`` rounded down, e the largest row sum of ``bound``, the shift's and ``slack``, or 0.

    ``bound`` bounds the residual of a Cholesky factorisation of ``shifted`` (a - α I).
    """
    m = shifted.shape[0]
    with np.errstate(all="ignore"):
        total = bound + _EPS * np.diag(np.abs(shifted.diagonal())) + slack
        # ‖E‖₂ <= sqrt(‖E‖₁ ‖E‖∞): the larger of the column and row sums.
        sums = max(float(np.max(total.sum(axis=0))), float(np.max(total.sum(axis=1))))
        e = sums * (1.0 + (m + 8) * 2.0 * _EPS)
    if not e < math.inf:  # NaN too
        return 0.0
    least = (alpha - e) * (1.0 - 4.0 * _EPS)
    return least if least > 0.0 else 0.0


def _float_solvers(
    scaled: FloatArray, d_s: FloatArray, p: FloatArray, jac: FloatArray, r: FloatArray
) -> list[Callable[[FloatArray], FloatArray]]:
    """Float solvers of ``S c = v`` for :func:`_nis_interval`'s refinement, the likelier first.

    By a Cholesky factor of ``scaled`` (D S D, ``d_s`` D's diagonal), where it has
    one; and by the information form, ``c = R⁻¹ (v - H J⁻¹ Hᵀ R⁻¹ v)``,
    ``J = P⁻¹ + Hᵀ R⁻¹ H`` (each by Cholesky, scaled by powers of two), whose
    error follows R's, P's and J's conditions, not S's: it converges where S's float
    form lost R (R 1e-16 of H P Hᵀ). Empty where neither factorises.
    """
    solvers: list[Callable[[FloatArray], FloatArray]] = []
    with np.errstate(all="ignore"):
        try:
            factor = np.linalg.cholesky(scaled)
        except np.linalg.LinAlgError:
            pass
        else:

            def by_s(v: FloatArray) -> FloatArray:
                half = np.linalg.solve(factor, v * d_s)
                out: FloatArray = np.linalg.solve(factor.T, half) * d_s
                return out

            solvers.append(by_s)
        try:
            d_r = _powers_of_two_scale(r.diagonal())
            l_r = np.linalg.cholesky(r * d_r * d_r[:, None])
            g = np.linalg.solve(l_r, d_r[:, None] * jac)  # L_R⁻¹ D_R H
            d_p = _powers_of_two_scale(p.diagonal())
            inv_lp = np.linalg.inv(np.linalg.cholesky(p * d_p * d_p[:, None]))
            j = (inv_lp.T @ inv_lp) * d_p * d_p[:, None] + g.T @ g
            d_j = _powers_of_two_scale(j.diagonal())
            l_j = np.linalg.cholesky(j * d_j * d_j[:, None])
        except (np.linalg.LinAlgError, FloatingPointError, ValueError):
            return solvers
        if not (np.isfinite(g).all() and np.isfinite(l_j).all()):
            return solvers

        def by_information(v: FloatArray) -> FloatArray:
            rhs = g.T @ np.linalg.solve(l_r, d_r * v)  # Hᵀ R⁻¹ v
            step = d_j * np.linalg.solve(l_j.T, np.linalg.solve(l_j, d_j * rhs))  # J⁻¹ Hᵀ R⁻¹ v
            rest = np.linalg.solve(l_r, d_r * (v - jac @ step))
            out: FloatArray = d_r * np.linalg.solve(l_r.T, rest)
            return out

        solvers.append(by_information)
    return solvers


def _nis_interval(
    p: FloatArray, jac: FloatArray, r: FloatArray, y: FloatArray, steps: int = 8
) -> tuple[float, float] | None:
    """Rigorous bounds ``lo <= yᵀ S⁻¹ y <= hi`` (S = H P Hᵀ + R) from float solves; None if none.

    For any w, with ``ρ = y - S w`` exactly, ``S⁻¹ y = w + S⁻¹ ρ``, so
    ``NIS = yᵀ w + wᵀ ρ + ρᵀ S⁻¹ ρ``: the first two terms exact (S, y and w as
    integers over powers of two: :func:`_integer_s`), the last at least 0 and at
    most ``‖D ρ‖² / μ`` for a rigorous lower bound μ of λmin(D A D)
    (:func:`_least_eigenvalue_bound`; D powers of two) with A = S (its float
    rounding within ε) or A = R (``S ⪰ R``: ``S⁻¹ ⪯ R⁻¹``, which holds where S's
    float form lost R), the latter only where P is proven positive definite. w is a
    float Cholesky solve with D S D refined against the exact ρ up to ``steps``
    times, each correction added exactly (w a sum of floats,
    not rounded to one: a float w leaves ρ at ε |S| |w|, whose bound through μ is
    κ times the last term), until the bounds are within 2⁻⁴⁰ of each other. Where
    the float S is not positive definite to working precision there is no solve:
    None. Review 44 (EKFREV6): past the exact NIS's cap a gate decides on these.
    """
    from fractions import Fraction

    m = jac.shape[0]
    if not (np.isfinite(y).all() and np.isfinite(p).all() and np.isfinite(jac).all()):
        return None
    if _integer_s_work(p, jac) > _EXACT_POSTERIOR_WORK_MAX:
        return None
    s_int, _, scale, _ = _integer_s(p, jac, r)
    unit = 1 << scale
    try:
        s_float = np.array([[value / unit for value in row] for row in s_int])
    except OverflowError:
        return None
    diag = s_float.diagonal()
    if not (np.isfinite(s_float).all() and (diag > 0.0).all()):
        return None
    d_s = _powers_of_two_scale(diag)
    scaled = s_float * d_s * d_s[:, None]
    # S's rounding (correctly rounded from the exact integers), scaled: within ε.
    slack = (_EPS * np.abs(s_float) + 2.0**-1074) * d_s * d_s[:, None]
    mu_s = _least_eigenvalue_bound(scaled, slack)
    r_diag = r.diagonal()
    d_r = _powers_of_two_scale(r_diag)
    mu_r = _least_eigenvalue_bound(r * d_r * d_r[:, None], np.full((m, m), 2.0**-1074))
    if mu_r > 0.0:
        # S ⪰ R needs P ⪰ 0 exactly, which a float Cholesky's success (the kernels'
        # test of a covariance) does not prove: P within ε of singular can be
        # indefinite, S's least eigenvalue then below R's (R's bound 2.4 times too
        # small; review 44, EKFCHECK). R's bound only with P proven positive definite.
        p_diag = p.diagonal()
        if not (p_diag > 0.0).all():
            mu_r = 0.0
        else:
            d_p = _powers_of_two_scale(p_diag)
            n = p.shape[0]
            p_slack = np.full((n, n), 2.0**-1074)
            if not _least_eigenvalue_bound(p * d_p * d_p[:, None], p_slack) > 0.0:
                mu_r = 0.0
    # The last term's bound per unit of ‖ρ‖²: the least of S's and R's (inf: none).
    weights = [(d, mu) for d, mu in ((d_s, mu_s), (d_r, mu_r)) if mu > 0.0]
    solvers = _float_solvers(scaled, d_s, p, jac, r)
    if not weights or not solvers:
        return None
    y_int, ky = _dyadic(y[None, :])
    y_ints = y_int[0]
    w_ints = [0] * m
    kw = 0
    residual = [Fraction(v) for v in y.tolist()]  # ρ = y for w = 0
    s_bits = max(abs(v).bit_length() for row in s_int for v in row)
    work = _integer_s_work(p, jac)
    best: tuple[Fraction, Fraction] | None = None
    kept: tuple[list[int], int, list[Fraction]] = (w_ints, kw, residual)
    last = math.inf
    for _ in range(steps + 1):
        try:
            rho = np.array([float(v) for v in residual])
        except OverflowError:  # ρ beyond float64: the bounds so far
            break
        # yᵀ w + wᵀ ρ, exactly.
        low = Fraction(sum(a * b for a, b in zip(y_ints, w_ints, strict=True)), 1 << (ky + kw))
        for w, res in zip(w_ints, residual, strict=True):
            if w:
                low += Fraction(w, 1 << kw) * res
        # ρᵀ S⁻¹ ρ <= ‖D ρ‖² / μ, from the exact ρ (D powers of two): in floats the
        # squares of a ρ below 1e-162 underflowed to 0, bounds [0, 0] around a
        # positive NIS (review 44, EKFCHECK).
        bound: Fraction | None = None
        for d, mu in weights:
            term = sum(
                (Fraction(di) * res) ** 2 for di, res in zip(d.tolist(), residual, strict=True)
            ) / Fraction(mu)
            bound = term if bound is None or term < bound else bound
        assert bound is not None  # weights is not empty
        try:
            gap = float(bound)  # only for the convergence test below
        except OverflowError:
            gap = math.inf
        if best is None or bound < best[1] - best[0]:
            best = (low, low + bound)
            kept = (w_ints, kw, residual)
            if bound <= low / (1 << 40):
                break
        if not gap <= 0.5 * last:
            # The solve does not converge (the float S lost R: its Cholesky solve is
            # noise there): the next solver, from the best w so far.
            solvers = solvers[1:]
            if not solvers:
                break
            w_ints, kw, residual = kept
            rho = np.array([float(v) for v in residual])  # finite: it gave the best bounds
            gap = math.inf
        last = gap
        # A correction: the float solve of S c = ρ, added to w exactly.
        with np.errstate(all="ignore"):
            correction = solvers[0](rho)
        if not np.isfinite(correction).all():
            break
        c_int, kc = _dyadic(correction[None, :])
        if kc > kw:
            w_ints = [w << (kc - kw) for w in w_ints]
            kw = kc
        w_ints = [w + (c << (kw - kc)) for w, c in zip(w_ints, c_int[0], strict=True)]
        # ρ = y - S w exactly, its m² products counted first (from sizes, no clock).
        w_bits = max(abs(w).bit_length() for w in w_ints)
        work += m * m * (_INFORMATION_OP_WORK + s_bits * w_bits)
        if work > _EXACT_POSTERIOR_WORK_MAX:
            break
        top = scale + kw
        shift = top - ky
        residual = []
        for a in range(m):
            row = s_int[a]
            exact = sum(row[b] * w_ints[b] for b in range(m) if w_ints[b])
            num = (y_ints[a] << shift) - exact if shift >= 0 else y_ints[a] - (exact << -shift)
            residual.append(Fraction(num, 1 << max(top, ky)))
    if best is None:
        return None
    low, high = best
    low = max(low, Fraction(0))
    try:
        out_lo = float(low)
        out_hi = float(high)
    except OverflowError:
        return None
    if Fraction(out_lo) > low:
        out_lo = math.nextafter(out_lo, 0.0)
    if Fraction(out_hi) < high:
        out_hi = math.nextafter(out_hi, math.inf)
    return out_lo, out_hi


def _bareiss(rows: list[list[int]], size: int, first: int | None = None) -> int | None:
    """Bareiss's fraction-free elimination of ``[A | B]`` in place; the last pivot (±det A).

    ``rows`` are A's ``size`` rows (integers), each followed by B's columns. Step k
    replaces every entry (i, j), i, j > k, by ``(Aₖₖ Aᵢⱼ - Aᵢₖ Aₖⱼ) / previous
    pivot``, each division exact: afterwards row k holds in column k the leading
    principal minor of order k + 1 (with the rows as exchanged), and row i > k
    keeps in column k its multiplier of step k. A zero pivot takes the first row
    below with a nonzero entry in its column (never for a positive definite A); None
    where there is none (A singular). With ``first``, only the columns from
    ``first`` on are eliminated, on the pivots and multipliers the rows already
    hold: a replay on new columns of an elimination made before (no rows exchanged
    there). The one elimination of S (:func:`_eliminated`), its replay on H P
    (:func:`_exact_posterior`) and :func:`_bareiss_solve` (before review 41, three
    copies of this loop).
    """
    previous = 1
    for k in range(size):
        if not rows[k][k]:
            at = next((i for i in range(k + 1, size) if rows[i][k]), None)
            if at is None:
                return None
            rows[k], rows[at] = rows[at], rows[k]
        pivot_row = rows[k]
        pivot = pivot_row[k]
        start = k + 1 if first is None else first
        for i in range(k + 1, size):
            row = rows[i]
            lead = row[k]
            for j in range(start, len(row)):
                row[j] = (pivot * row[j] - lead * pivot_row[j]) // previous
        previous = pivot
    return previous


def _back_substituted(rows: list[list[int]], size: int, det: int) -> list[list[int]]:
    """``N`` with ``A X = B``, ``X = N / det``, from :func:`_bareiss`'s rows ``[A | B]``.

    Back substitution scaled by ``det`` (the last pivot): by Cramer's rule every
    ``Nᵢⱼ`` is an integer, and each division is exact.
    """
    width = len(rows[0]) - size
    solved = [[0] * width for _ in range(size)]
    for k in range(size - 1, -1, -1):
        row = rows[k]
        pivot = row[k]
        target = solved[k]
        for c in range(width):
            rest = sum(row[j] * solved[j][c] for j in range(k + 1, size))
            target[c] = (det * row[size + c] - rest) // pivot
    return solved


# [S | y] eliminated exactly (see _eliminated): rows, H P, and the powers of two.
_Elimination = tuple[list[list[int]], list[list[int]], int, int, int]


def _eliminated(p: FloatArray, jac: FloatArray, r: FloatArray, y: FloatArray) -> _Elimination:
    """``[S | y]``, S = H P Hᵀ + R, as integers, eliminated exactly by Bareiss; with H P.

    Returns ``(rows, hp, scale, k_hp, ky)``: S is the integer matrix of the
    rows before elimination over ``2**scale``, y their last column over
    ``2**ky`` and H P is ``hp`` over ``2**k_hp``. After the elimination row k
    holds the leading principal minor ``Dₖ`` of the integer S in column k
    (every division of the elimination is exact) and the eliminated y in
    column m, for :func:`_nis_of` and :func:`_exact_state`.
    """
    m = jac.shape[0]
    s, hp, scale, k_hp = _integer_s(p, jac, r)
    y_int, ky = _dyadic(y[None, :])
    rows = [[*row, y_int[0][a]] for a, row in enumerate(s)]
    _bareiss(rows, m)  # S is positive definite: no pivot is zero, no rows exchanged
    return rows, hp, scale, k_hp, ky


def _nis_of(elimination: _Elimination) -> float:
    """The exact NIS of an :func:`_eliminated` system, rounded once (inf beyond float64)."""
    from fractions import Fraction

    rows, _, scale, _, ky = elimination
    m = len(rows)
    previous = 1
    total = Fraction(0)
    for k in range(m):
        row = rows[k]
        total += Fraction(row[m] * row[m], previous * row[k])
        previous = row[k]
    try:
        return float(total * Fraction(2) ** (scale - 2 * ky))
    except OverflowError:
        return math.inf


def _exact_state(x: FloatArray, elimination: _Elimination) -> FloatArray | None:
    """``x + P Hᵀ S⁻¹ y`` exactly, each component rounded once, from an :func:`_eliminated` system.

    By Cramer's rule the solution of the integer system ``S w = y`` is
    ``N / det S`` with integer N: back substitution in the eliminated rows,
    scaled by ``det S`` (the last pivot), keeps every ``Nₖ`` an integer (each
    division exact). The step ``(H P)ᵀ w`` then has one denominator, and the
    sum with x is rounded once (Python's int division is correctly rounded).
    The exact posterior mean to half an ulp, whatever κ(S): about as costly
    as :func:`_exact_nis` (measured 55 µs median, 0.2 ms at the 90th
    percentile for n, m up to 6, up to 12 ms where P and R are 1e140 apart).
    None where a component is beyond float64.
    """
    from fractions import Fraction

    rows, hp, scale, k_hp, ky = elimination
    m = len(rows)
    det = rows[m - 1][m - 1]
    numerators = [row[0] for row in _back_substituted(rows, m, det)]
    unit = Fraction(2) ** (scale - ky - k_hp)
    out = np.empty(x.shape[0])
    for i in range(x.shape[0]):
        step = Fraction(sum(hp[a][i] * numerators[a] for a in range(m)), det) * unit
        try:
            out[i] = float(Fraction(float(x[i])) + step)
        except OverflowError:
            return None
    return out


def _exact_posterior(p: FloatArray, elimination: _Elimination) -> FloatArray | None:
    """``P - (H P)ᵀ S⁻¹ (H P)`` exactly, each entry rounded once, from an :func:`_eliminated` S.

    The columns of H P go through the elimination of S (each row i > k of the
    eliminated system still holds in column k its multiplier of step k), then
    back substitution scaled by ``det S`` as in :func:`_exact_state`, so that
    ``M = det S · S⁻¹ (H P)`` is an integer matrix (Cramer's rule) and every
    entry ``Pᵢⱼ - ((H P)ᵀ M)ᵢⱼ / det S`` one fraction, rounded once (Python's
    int division is correctly rounded). ``(H P)ᵀ M`` is exactly symmetric, so
    the result is too. The exact posterior covariance to half an ulp per
    entry, whatever κ(S) or κ(P⁺); whether float64 holds it as a positive
    definite matrix is the caller's check (:func:`_is_covariance`). None
    where an entry is beyond float64 (never, for a positive definite P: the
    exact ``|P⁺ᵢⱼ|`` is at most ``sqrt(Pᵢᵢ Pⱼⱼ)``). Raises ``FilterError``
    where its estimated work exceeds ``_EXACT_POSTERIOR_WORK_MAX`` (about 15 s
    of CPU; before review 42 unbounded, linear in n: 197 s for 256 states).
    """
    rows, hp, scale, k_hp, _ = elimination
    m = len(rows)
    n = p.shape[0]
    det_bits = abs(rows[m - 1][m - 1]).bit_length()
    hp_bits = max(abs(value).bit_length() for row in hp for value in row)
    work = m * m * n * det_bits**2 + 2.7 * m * hp_bits * det_bits * n * (n + 1) / 2
    if work > _EXACT_POSTERIOR_WORK_MAX:
        raise FilterError(
            f"the exact posterior covariance of {n} states from {m} components, with "
            f"det S of {det_bits} bits (P and R far apart), would take about "
            f"{work * _EXACT_POSTERIOR_WORK_SECONDS:.0f} s of exact arithmetic, more than the "
            f"{_EXACT_POSTERIOR_WORK_MAX * _EXACT_POSTERIOR_WORK_SECONDS:.0f} s allowed "
            "(update with fewer "
            "components at a time, or with fewer states)"
        )
    # [S | H P], S's part as eliminated (its pivots and each step's multipliers): the
    # elimination replayed on H P's columns only.
    system = [row[:m] + columns for row, columns in zip(rows, hp, strict=True)]
    det = _bareiss(system, m, first=m)
    assert det is not None  # S's pivots, none zero
    solved = _back_substituted(system, m, det)
    shift = scale - 2 * k_hp  # (H P)ᵀ S⁻¹ (H P) = hpᵀ M / det · 2**shift
    values = p.tolist()
    out = np.empty((n, n))
    for i in range(n):
        for j in range(i, n):
            reduced = sum(hp[a][i] * solved[a][j] for a in range(m))
            num, den = values[i][j].as_integer_ratio()
            if shift >= 0:
                top, bottom = num * det - (reduced << shift) * den, den * det
            else:
                top, bottom = (num * det << -shift) - reduced * den, (den * det) << -shift
            try:
                out[i, j] = out[j, i] = top / bottom
            except OverflowError:
                return None
    return out


def _bareiss_solve(a: list[list[int]], b: list[list[int]]) -> tuple[list[list[int]], int] | None:
    """``a X = b`` exactly for an integer ``a`` (k, k), ``b`` (k, q): ``(N, d)``, None if singular.

    ``X = N / d`` with integer N and ``d = ±det a`` (positive): :func:`_bareiss`
    on ``[a | b]`` (``a`` need not be symmetric: rows exchanged where a pivot is
    zero), then :func:`_back_substituted`, as for S.
    """
    k = len(a)
    rows = [a[i][:] + b[i][:] for i in range(k)]
    det = _bareiss(rows, k)
    if det is None:
        return None
    solved = _back_substituted(rows, k, det)
    if det < 0:
        return [[-v for v in row] for row in solved], -det
    return solved, det


def _r_blocks(r: FloatArray) -> list[list[int]]:
    """The diagonal blocks of the symmetric ``r``: its components' sets, each sorted.

    Components i and j share a block where a chain of nonzero entries joins them
    (one block each for a diagonal R: independent sensors, a scan's beams).
    """
    m = r.shape[0]
    parent = list(range(m))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    # A few rows at a time: np.triu(r, 1) of the whole R was an m x m copy (800 MB for
    # 10,000 beams; review 44, EKFREV6).
    step = max(1, _RESIDUAL_TERMS // max(m, 1))
    for first in range(0, m, step):
        rows, cols = np.nonzero(r[first : first + step])
        for i, j in zip((rows + first).tolist(), cols.tolist(), strict=True):
            if j > i:
                parent[root(i)] = root(j)
    blocks: dict[int, list[int]] = {}
    for i in range(m):
        blocks.setdefault(root(i), []).append(i)
    return list(blocks.values())


# The information route's (_ExactUpdate) rounding of 1 / det(R_B), where the exact
# common denominator of many blocks' determinants would be long (a scan's beams of
# distinct variances: 53 bits each, 19,000 bits for 360, and 85 s for 15 states): each
# to within 2**-_R_SCALED_BITS / (1 + sqrt(yᵀ R⁻¹ y)) relative. That is the exact
# update of an R' between R (1 - η) and R (1 + η) (η that bound): P⁺' between
# P⁺ / (1 + η) and P⁺ / (1 - η) (Loewner order), so within η / (1 - η) of
# sqrt(P⁺ᵢᵢ P⁺ⱼⱼ); the NIS within that relative; and x⁺' - x⁺ = P⁺' Hᵀ (R'⁻¹ - R⁻¹)
# (y - H (x⁺ - x)), within about η sqrt(yᵀ R⁻¹ y) posterior deviations (the posterior
# residual's yᵀ R⁻¹ y is at most the prior's): 2⁻⁸⁰.
_R_SCALED_BITS = 80


def _exact_route(n: int, r: FloatArray) -> list[list[int]] | None:
    """How :class:`_ExactUpdate` finishes an update of ``n`` states with noise ``r``.

    ``[]``: by S's elimination (measurements of at most ``_EXACT_CANCELLED_MAX_M``
    components, and where it is the cheaper); R's blocks (:func:`_r_blocks`): by
    the information form; None where each route's largest elimination exceeds
    ``_EXACT_ELIMINATION_MAX`` (the update is then refused where no float64
    result is vouched for).
    """
    m = r.shape[0]
    if m <= _EXACT_CANCELLED_MAX_M:
        return []
    blocks = _r_blocks(r)
    widest = max(n, max(len(b) for b in blocks))
    by_s = m**3 + m * m * n + m * n * n
    by_information = sum(len(b) ** 2 * (len(b) + n) for b in blocks) + m * n * n + 3 * n**3
    if widest <= _EXACT_ELIMINATION_MAX and (by_information < by_s or m > _EXACT_ELIMINATION_MAX):
        return blocks
    return [] if m <= _EXACT_ELIMINATION_MAX else None


class _ExactUpdate:
    """The exact posterior mean, covariance and NIS of a linear update, each rounded once.

    Two routes to the same rational numbers. With S (``_eliminated``: an m x m
    elimination of S = H P Hᵀ + R) for at most ``_EXACT_CANCELLED_MAX_M``
    components, or where it is the cheaper; else the information form in exact
    arithmetic (Woodbury's identity, exact for any m):

        A = Hᵀ R⁻¹ H,  g = Hᵀ R⁻¹ y,  P⁺ = (I + P A)⁻¹ P,  x⁺ = x + P⁺ g,
        NIS = yᵀ R⁻¹ y - gᵀ P⁺ g,

    R⁻¹ applied block by block (:func:`_r_blocks`: each block of R eliminated
    on its own, a diagonal R's at one division each) and one n x n elimination
    of ``I + P A``: about ``Σ b³ + m n² + n³`` operations on integers where S's
    elimination takes m³ (for a 360-beam scan with a diagonal R and 3 states,
    millions of times fewer). (Sequential scalar updates are the same exact
    posterior for a diagonal R, but in float64 each cancels as the joint one
    does, and exactly they carry a rational P through m steps.)
    """

    def __init__(
        self, p: FloatArray, jac: FloatArray, r: FloatArray, y: FloatArray, blocks: list[list[int]]
    ) -> None:
        n = jac.shape[1]
        self.elimination: _Elimination | None = None
        if not blocks:
            # S's elimination: its work from sizes and exponents before any (review 43,
            # EKFREV5; before, H P's m n² products preceded the exact posterior's cap).
            work = _exact_nis_work(p, jac, r, y)
            if work > _EXACT_POSTERIOR_WORK_MAX:
                raise _PastTheLimit(
                    f"the exact update of {n} states from {jac.shape[0]} components (S's "
                    f"elimination, with H P's {jac.shape[0] * n * n} products) would take "
                    f"about {work * _EXACT_POSTERIOR_WORK_SECONDS:.0f} s of exact "
                    "arithmetic, more than the "
                    f"{_EXACT_POSTERIOR_WORK_MAX * _EXACT_POSTERIOR_WORK_SECONDS:.0f} s "
                    "allowed (update with fewer components at a time, or with fewer states)"
                )
            self.elimination = _eliminated(p, jac, r, y)
            return
        # Its work from sizes and exponents before any (review 43, EKFREV5; before,
        # unlimited: 25 s for 10,000 beams, most of it R's m² integers).
        m = jac.shape[0]
        # A product of an integer of H (h bits) by one of a block's solution (h bits and
        # the block's other b - 1 rows of R's): a b² term, as the posterior's.
        h_bits, r_bits = _integer_bits(jac), _integer_bits(r)
        widest = max(len(b) for b in blocks)
        ops = m * (n + 2) ** 2 + sum(len(b) ** 3 // 3 for b in blocks)
        work = ops * (_INFORMATION_OP_WORK + float(h_bits) * (h_bits + widest * r_bits))
        if work > _EXACT_POSTERIOR_WORK_MAX:
            raise _PastTheLimit(
                f"the exact update of {n} states from {m} components (by R's blocks) would "
                f"take about {work * _EXACT_POSTERIOR_WORK_SECONDS:.0f} s of exact "
                f"arithmetic, more than the "
                f"{_EXACT_POSTERIOR_WORK_MAX * _EXACT_POSTERIOR_WORK_SECONDS:.0f} s allowed "
                "(update with fewer components at a time)"
            )
        h_int, kh = _dyadic(jac)
        p_int, kp = _dyadic(p)
        # R's blocks only, over their common power of two: the whole R took m² Python
        # integers (10,000 beams of a diagonal R: 1e8, about 25 s; review 43, EKFREV5).
        r_ints, kr = _dyadic_blocks(r, blocks)
        y_int = _dyadic(y[None, :])
        ky = y_int[1]
        y_row = y_int[0][0]
        # Σ over the blocks of Hᵀ R⁻¹ [H | y] and yᵀ R⁻¹ y, in integers over each
        # block's determinant, summed per determinant (a scan's beams share one).
        sums: dict[int, tuple[list[list[int]], list[int], list[int]]] = {}
        for block, r_int in zip(blocks, r_ints, strict=True):
            rhs = [h_int[a] + [y_row[a]] for a in block]
            if len(block) == 1:
                solved, det = rhs, r_int[0][0]
            else:
                found = _bareiss_solve([row[:] for row in r_int], rhs)
                if found is None:
                    # R's block is singular in exact arithmetic (its float64 check
                    # passed on a rounding): S, still positive definite, is not; but
                    # its elimination is limited as any (before review 41 a 60-row one
                    # took 2.9 s here, the limit bypassed).
                    if jac.shape[0] > _EXACT_ELIMINATION_MAX:
                        raise _PastTheLimit(
                            f"R's block of components {block} is singular in exact "
                            "arithmetic (positive definite only as rounded), so the "
                            "exact update needs S's elimination, of more than "
                            f"{_EXACT_ELIMINATION_MAX} rows (make R positive definite)"
                        )
                    self.elimination = _eliminated(p, jac, r, y)
                    return
                solved, det = found
            info, gain, nis = sums.setdefault(det, ([[0] * n for _ in range(n)], [0] * n, [0]))
            for row_h, row_w, a in zip((h_int[a] for a in block), solved, block, strict=True):
                for i in range(n):
                    hi = row_h[i]
                    if hi:
                        target = info[i]
                        for j in range(i, n):
                            target[j] += hi * row_w[j]
                        gain[i] += hi * row_w[n]
                nis[0] += y_row[a] * row_w[n]
        # Over one common denominator: their lcm where it is short (a scan's beams of
        # one variance: one determinant), else 2**bits, each 1 / d rounded to a
        # multiple of 2**-bits within 2⁻⁸⁰ / (1 + sqrt(yᵀ R⁻¹ y)) of itself
        # relative: the exact update of an R' whose blocks are R's scaled by factors
        # that close to one (_R_SCALED_BITS).
        common = math.lcm(*sums)
        size = len(sums).bit_length() + max(  # log2 yᵀ R⁻¹ y, rounded up
            nis[0].bit_length() - det.bit_length() + kr - 2 * ky + 1
            for det, (_, _, nis) in sums.items()
        )
        bits = max(det.bit_length() for det in sums) + _R_SCALED_BITS + max(0, size // 2 + 1)
        if common.bit_length() > bits:
            common = 1 << bits
        a_num = [[0] * n for _ in range(n)]
        g_num = [0] * n
        c_num = 0
        for det, (info, gain, nis) in sums.items():
            factor = (common + det // 2) // det
            for i in range(n):
                for j in range(i, n):
                    a_num[i][j] += info[i][j] * factor
                g_num[i] += gain[i] * factor
            c_num += nis[0] * factor
        for i in range(n):
            for j in range(i):
                a_num[i][j] = a_num[j][i]
        # I + P A = M / T: A = a_num 2**(kr - 2 kh) / common, P = p_int / 2**kp.
        e = kr - 2 * kh - kp
        up = max(0, -e)  # T = common 2**up
        pa = [
            [sum(p_int[i][k] * a_num[k][j] for k in range(n) if p_int[i][k]) << max(0, e)
             for j in range(n)]
            for i in range(n)
        ]  # fmt: skip
        for i in range(n):
            pa[i][i] += common << up
        # P⁺ = T M⁻¹ P = T N / (d 2**kp), M N = d P_int. M = T (I + P A) is
        # non-singular: P A's eigenvalues are those of P^½ A P^½, at least 0.
        found = _bareiss_solve(pa, p_int)
        assert found is not None
        self.solved, self.det = found
        self.top = common << up
        self.kp = kp
        self.g_num = g_num
        # x⁺ - x = P⁺ g = N g_num 2**(up + kr - kh - ky - kp) / d.
        self.step_shift = up + kr - kh - ky - kp
        # yᵀ R⁻¹ y = c_num 2**(kr - 2 ky) / common, gᵀ P⁺ g = g_numᵀ N g_num ·
        # 2**(2 (kr - kh - ky) + up - kp) / (common d).
        self.c_num, self.common = c_num, common
        self.c_shift = kr - 2 * ky
        self.q_shift = 2 * (kr - kh - ky) + up - kp

    def nis(self) -> float:
        """The exact NIS ``yᵀ S⁻¹ y``, rounded once (inf beyond float64)."""
        from fractions import Fraction

        if self.elimination is not None:
            return _nis_of(self.elimination)
        n = len(self.g_num)
        g = self.g_num
        quad = sum(g[i] * self.solved[i][j] * g[j] for i in range(n) for j in range(n))
        two = Fraction(2)
        total = (
            Fraction(self.c_num, self.common) * two**self.c_shift
            - Fraction(quad, self.common * self.det) * two**self.q_shift
        )
        try:
            return float(total)
        except OverflowError:
            return math.inf

    def state(self, x: FloatArray) -> FloatArray | None:
        """The exact posterior mean, each component rounded once (None beyond float64)."""
        from fractions import Fraction

        if self.elimination is not None:
            return _exact_state(x, self.elimination)
        n = x.shape[0]
        unit = Fraction(2) ** self.step_shift
        out = np.empty(n)
        for i in range(n):
            numerator = sum(v * g for v, g in zip(self.solved[i], self.g_num, strict=True))
            step = Fraction(numerator, self.det)
            try:
                out[i] = float(Fraction(float(x[i])) + step * unit)
            except OverflowError:
                return None
        return out

    def posterior(self, p: FloatArray) -> FloatArray | None:
        """The exact posterior covariance, each entry rounded once (None beyond float64)."""
        if self.elimination is not None:
            return _exact_posterior(p, self.elimination)
        n = p.shape[0]
        bottom = self.det << self.kp
        out = np.empty((n, n))
        for i in range(n):
            for j in range(i, n):
                try:
                    out[i, j] = out[j, i] = self.top * self.solved[i][j] / bottom
                except OverflowError:
                    return None
        return out


def _error_against(candidate: FloatArray, exact: FloatArray | None) -> float:
    """``max |Xᵢⱼ - Eᵢⱼ| / sqrt(Eᵢᵢ Eⱼⱼ)``, E the exact posterior rounded (inf: no bound)."""
    if exact is None:
        return math.inf
    with np.errstate(all="ignore"):
        unit = np.sqrt(np.abs(exact.diagonal()))
        error = float(np.max(np.abs(candidate - exact) / np.outer(unit, unit)))
    return error if error < math.inf else math.inf


def _is_covariance(a: FloatArray) -> bool:
    """Whether the symmetric ``a`` passes the kernels' test of a covariance.

    Finite, a positive diagonal, and the pivots of its LDLᵀ factorisation (those
    of D a D, D scaling its diagonal to one, over dᵢ²) normal floats, as
    :func:`_positive_definite` requires of every committed P.
    """
    diag = a.diagonal()
    if not np.isfinite(a).all() or not (diag > 0.0).all():
        return False
    with np.errstate(all="ignore"):  # a subnormal variance: D a D overflows, and fails
        d = 1.0 / np.sqrt(diag)
        try:
            factor = np.linalg.cholesky(a * d * d[:, None])
        except np.linalg.LinAlgError:
            return False
        return bool(((factor.diagonal() / d) ** 2 >= _SMALLEST_NORMAL).all())


def _dyadic(a: FloatArray) -> tuple[list[list[int]], int]:
    """The 2-D float array ``a`` as integers ``A`` and ``k`` with ``a = A / 2**k`` exactly."""
    ratios = [[value.as_integer_ratio() for value in row] for row in a.tolist()]
    k = max(den.bit_length() - 1 for row in ratios for _, den in row)
    return [[num << (k - den.bit_length() + 1) for num, den in row] for row in ratios], k


def _dyadic_blocks(r: FloatArray, blocks: list[list[int]]) -> tuple[list[list[list[int]]], int]:
    """Each diagonal block of ``r`` (``blocks``, index lists) as integers over one ``2**k``.

    :func:`_dyadic` of every block at once: ``r[block][:, block] = A_block / 2**k``
    exactly, k the least common to all blocks (the entries between blocks, zero, are
    not converted: O(Σ b²), not O(m²)).
    """
    ratios = [[[value.as_integer_ratio() for value in row] for row in r[np.ix_(b, b)].tolist()]
              for b in blocks]  # fmt: skip
    k = max(den.bit_length() - 1 for block in ratios for row in block for _, den in row)
    return [
        [[num << (k - den.bit_length() + 1) for num, den in row] for row in block]
        for block in ratios
    ], k


def _s_amplification(rbuf: FloatArray, p: FloatArray, jac: FloatArray) -> float:
    """How far the kernel's NIS and x may be off, over ε: S's condition for its rounding error.

    The larger of κ of S with its diagonal scaled (:func:`_scaled_inverse`) and
    ``max cₖ (S⁻¹)ₖₖ``, ``cₖ = max(uₖ² + Rₖₖ, Sₖₖ)`` with ``uₖ = Σⱼ |Hₖⱼ| sqrt(Pⱼⱼ)``:
    the computed S's rounding error is within about n ε sqrt(cₖ cₗ) in entry
    (k, l) however far H P Hᵀ cancels, and its effect is λmax(C S⁻¹ C) ε
    (C = diag(sqrt(cₖ))), of which ``max cₖ (S⁻¹)ₖₖ`` is a lower bound at least
    the update kernel's ``max cₖ / Dₖ`` (a pivot Dₖ of S = L D Lᵀ is at least
    ``1 / (S⁻¹)ₖₖ``). inf where S is singular to working precision. ``p`` is
    the prior P and ``jac`` the H of the update whose S ``rbuf`` holds.
    """
    m = jac.shape[0]
    lower = np.tril(rbuf[_S, :m, :m])
    found = _scaled_inverse(lower + np.tril(lower, -1).T)
    if found is None:
        return math.inf
    inverse, kappa = found
    reach = np.abs(jac) @ np.sqrt(p.diagonal())
    scale = np.maximum(reach * reach + rbuf[_RS, :m, :m].diagonal(), lower.diagonal())
    worst = float(np.max(scale * inverse.diagonal()))
    return max(kappa, worst) if worst - worst == 0.0 else math.inf


_SPLIT = 134217729.0  # 2²⁷ + 1: Dekker's splitting of a float64 into two 26-bit halves

#: The terms :func:`_exact_residual` holds at once (float64s: 16 MB).
_RESIDUAL_TERMS = 1 << 21


def _halves(a: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Dekker's split: ``a = high + low`` exactly, each with at most 26 significant bits."""
    c = _SPLIT * a
    high = c - (c - a)
    return high, a - high


def _product_minus_identity(a: FloatArray, b: FloatArray) -> FloatArray:
    """``a @ b - I`` (square ``a``, ``b``), each entry rounded once from its exact value."""
    return _exact_residual(a, b, np.eye(a.shape[0]))


def _exact_residual(a: FloatArray, b: FloatArray, c: FloatArray) -> FloatArray:
    """``a @ b - c`` (``a`` (n, k), ``b`` (k, q), ``c`` (n, q)), each entry rounded once.

    Every product ``a_ik b_kj`` is split exactly into its rounded value and its
    error (Dekker's TwoProduct; exact for entries of moderate size, as those of
    the matrices scaled by powers of two this is used on), and the 2k + 1
    terms of each entry are summed by :func:`math.fsum` (correctly rounded).
    All NaN where a product or a sum overflows (a garbage candidate): callers
    then find no error bound and reject what it was for.
    """
    n, k = a.shape
    q = b.shape[1]
    a_high, a_low = _halves(a)
    b_high, b_low = _halves(b)
    bh, bl = b_high[None, :, :], b_low[None, :, :]
    out = np.empty((n, q))
    # Rows a few at a time: the terms of all n q entries at once took 8 (2k + 1) n q
    # bytes, 1.2 GB for a 200-beam R and more than the machine for 1000 (review 40).
    step = max(1, _RESIDUAL_TERMS // ((2 * k + 1) * max(q, 1)))
    for first in range(0, n, step):
        rows_of = slice(first, min(n, first + step))
        rounded = a[rows_of, :, None] * b[None, :, :]
        ah, al = a_high[rows_of, :, None], a_low[rows_of, :, None]
        error = ((ah * bh - rounded) + ah * bl + al * bh) + al * bl
        terms = np.concatenate((rounded, error, -c[rows_of, None, :]), axis=1)
        if not np.isfinite(terms).all():  # a product or split overflowed: no residual
            return np.full((n, q), math.nan)
        rows = terms.transpose(0, 2, 1).reshape(-1, 2 * k + 1).tolist()
        try:
            out[rows_of] = np.array([math.fsum(row) for row in rows]).reshape(-1, q)
        except OverflowError:  # an exact sum beyond float64
            return np.full((n, q), math.nan)
    return out


def _scaled_inverse(a: FloatArray) -> tuple[FloatArray, float] | None:
    """The inverse of the symmetric ``a`` (exactly symmetric) and a bound on κ(D a D).

    D scales the diagonal of ``a`` to [0.5, 2) by powers of two; ``D a D = L Lᵀ``
    (Cholesky) and the inverse is D L⁻ᵀ L⁻¹ D, whose error relative to
    ``sqrt(inv_ii inv_jj)`` is about ε κ(D a D) however badly ``a`` is scaled
    (entries from 1e-100 to 1e100, where κ(a) could be 1e200). The condition
    number returned is the larger of κ₁ = ‖D a D‖₁ ‖(D a D)⁻¹‖₁ (within a factor
    n of κ₂) and 1 / the smallest pivot of L Lᵀ (at most 2 κ₂, as the diagonal of
    D a D is below 2): the
    pivots, not the inverse, say when ``D a D`` is singular to working
    precision, where a computed inverse is noise and κ₁ from it no bound. None
    when ``a`` is not finite, its diagonal not positive or its Cholesky
    factorisation fails (not positive definite to working precision).
    """
    found = _scaled_inverse_parts(a)
    if found is None:
        return None
    _, inv, d, kappa = found
    inv = inv * d * d[:, None]
    return 0.5 * (inv + inv.T), kappa


def _scaled_inverse_parts(
    a: FloatArray,
) -> tuple[FloatArray, FloatArray, FloatArray, float] | None:
    """``D a D``, its inverse (symmetric), D's diagonal and κ: :func:`_scaled_inverse`'s parts.

    D's entries are powers of two (the diagonal of ``D a D`` is in [0.5, 2)), so
    that ``D a D`` holds ``a``'s values exactly and a residual computed with it
    is ``a``'s (scaling by ``1 / sqrt(aᵢᵢ)`` rounds, an error of ε κ).
    """
    diag = a.diagonal()
    if not np.isfinite(a).all() or not (diag > 0.0).all():
        return None
    # Powers of two, so that D a D is a's values exactly (its residuals are a's).
    d = np.ldexp(1.0, -(np.frexp(diag)[1] // 2))
    scaled = a * d * d[:, None]
    scaled = 0.5 * (scaled + scaled.T)
    try:
        factor = np.linalg.cholesky(scaled)
    except np.linalg.LinAlgError:
        return None
    smallest_pivot = float(np.min(factor.diagonal() ** 2))
    if not smallest_pivot > 0.0:
        return None
    half = np.linalg.inv(factor)
    inv = half.T @ half
    inv = 0.5 * (inv + inv.T)
    kappa = float(np.abs(scaled).sum(0).max() * np.abs(inv).sum(0).max())
    return scaled, inv, d, max(kappa, 1.0 / smallest_pivot)


def _refined_inverse(
    a: FloatArray,
) -> tuple[FloatArray, FloatArray, float, tuple[FloatArray, FloatArray, FloatArray, float]] | None:
    """The inverse of the symmetric positive definite ``a``, refined once; its error bound.

    :func:`_scaled_inverse`'s inverse of ``D a D`` (error about ε κ) with one
    step of iterative refinement, ``X ← X - X (D a D X - I)``, the residual
    exact to one rounding (:func:`_product_minus_identity`): the error drops to
    about ε + (ε κ)², as if solved in twice the precision. Returns the inverse,
    a bound on the magnitude of its error entry by entry (``(4 ε + 2 (ε κ)²)``
    times ``sqrt(inv_ii inv_jj)``, at least the entry's magnitude), κ, and the
    scaled parts
    (:func:`_scaled_inverse_parts`, the inverse refined); None as
    :func:`_scaled_inverse`.
    """
    found = _scaled_inverse_parts(a)
    if found is None:
        return None
    scaled, inv, d, kappa = found
    refined = inv - inv @ _product_minus_identity(scaled, inv)
    refined = 0.5 * (refined + refined.T)
    inv = refined * d * d[:, None]
    inv = 0.5 * (inv + inv.T)
    relative = 4.0 * _EPS + 2.0 * (_EPS * kappa) ** 2
    unit = np.sqrt(inv.diagonal())
    return inv, relative * np.outer(unit, unit), kappa, (scaled, refined, d, kappa)


class _BlockInverse:
    """R⁻¹ refined one diagonal block at a time, held as its blocks: O(Σ b²) memory, not m².

    :func:`_refined_block_inverse`'s result. Blocks of one size k are stacked
    (``index`` (c, k): their components; ``inv``, ``bound``, ``scaled``, ``refined``
    (c, k, k): each block's :func:`_refined_inverse` parts), ``d`` (m,) is D's
    diagonal and ``kappa`` the largest block's κ. Before review 44 (EKFREV6) the
    parts were four dense m x m arrays, zero between blocks: 3.2 GB for a diagonal R
    of 10,000 beams, and R⁻¹ y's exact residual summed 2m + 1 terms a row (22 s for
    2000 beams).
    """

    __slots__ = ("d", "groups", "kappa", "m")

    def __init__(
        self,
        m: int,
        groups: list[tuple[IntArray, FloatArray, FloatArray, FloatArray, FloatArray]],
        d: FloatArray,
        kappa: float,
    ) -> None:
        self.m = m
        self.groups = groups
        self.d = d
        self.kappa = kappa

    def sandwich(self, a: FloatArray, part: int) -> FloatArray:
        """``aᵀ X a`` (``a`` (m, n)), X the inverse (0), its magnitude (1) or its bound (2).

        As ``(aᵀ X) a`` with X dense: ``aᵀ X`` block by block, then one product.
        """
        left = np.zeros((a.shape[1], self.m))
        for group in self.groups:
            index, blocks = group[0], group[2 if part == 2 else 1]
            if part == 1:
                blocks = np.abs(blocks)
            rows = a[index]  # (c, k, n)
            left[:, index] = np.matmul(rows.transpose(0, 2, 1), blocks).transpose(1, 0, 2)
        return left @ a

    def _apply(self, v: FloatArray, part: int) -> FloatArray:
        """``X v`` (``v`` (m, 1)), X the refined scaled inverse (3) or its magnitude (-3)."""
        out = np.zeros_like(v)
        for group in self.groups:
            index, blocks = group[0], group[4]
            if part < 0:
                blocks = np.abs(blocks)
            out[index] = np.matmul(blocks, v[index])
        return out

    def scaled_solve(self, v: FloatArray) -> FloatArray:
        """``(D R D)⁻¹ v``, refined once against its exact residual (``v`` (m, 1))."""
        w = self._apply(v, 3)
        residual = np.empty_like(v)
        for group in self.groups:
            index, scaled = group[0], group[3]
            c, k = index.shape
            flat = index.reshape(-1)
            own = np.repeat(w[index][:, :, 0], k, axis=0)  # each row's block of w
            residual[flat] = _exact_row_residual(scaled.reshape(c * k, k), own, v[flat])
        return w - self._apply(residual, 3)

    def scaled_magnitude(self, v: FloatArray) -> FloatArray:
        """``|(D R D)⁻¹| |v|`` (``v`` (m, 1)): the refined scaled inverse's magnitude applied."""
        return self._apply(np.abs(v), -3)

    def dense(self) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """The inverse, its bound, ``D R D`` and its refined inverse as m x m arrays (for tests)."""
        out = [np.zeros((self.m, self.m)) for _ in range(4)]
        for group in self.groups:
            index = group[0]
            for row, block in enumerate(index):
                at = np.ix_(block, block)
                for whole, part in zip(out, group[1:], strict=True):
                    whole[at] = part[row]
        return out[0], out[1], out[2], out[3]


def _exact_row_residual(a: FloatArray, b: FloatArray, c: FloatArray) -> FloatArray:
    """``Σⱼ aᵢⱼ bᵢⱼ - cᵢ`` for each row i (``a``, ``b`` (rows, k), ``c`` (rows, 1)), rounded once.

    :func:`_exact_residual`'s terms (Dekker's TwoProduct, then :func:`math.fsum`) for
    products taken entry by entry: a block-diagonal matrix's rows against their own
    block's part of a vector. All NaN where a product or a sum overflows. Returns
    (rows, 1).
    """
    rows, k = a.shape
    out = np.empty((rows, 1))
    step = max(1, _RESIDUAL_TERMS // (2 * k + 1))
    for first in range(0, rows, step):
        at = slice(first, min(rows, first + step))
        rounded = a[at] * b[at]
        ah, al = _halves(a[at])
        bh, bl = _halves(b[at])
        error = ((ah * bh - rounded) + ah * bl + al * bh) + al * bl
        terms = np.concatenate((rounded, error, -c[at]), axis=1)
        if not np.isfinite(terms).all():
            return np.full((rows, 1), math.nan)
        try:
            out[at, 0] = [math.fsum(row) for row in terms.tolist()]
        except OverflowError:
            return np.full((rows, 1), math.nan)
    return out


def _refined_block_inverse(
    r: FloatArray, blocks: list[list[int]] | None = None
) -> _BlockInverse | None:
    """:func:`_refined_inverse` of the symmetric ``r``, one diagonal block at a time.

    The blocks are :func:`_r_blocks`'s (``blocks`` where the caller has them; one
    per beam for a diagonal R), each inverted and refined on its own and kept as its
    own (:class:`_BlockInverse`: the inverse is zero, and exactly so, between
    blocks), κ the largest block's. A whole R of m components took m³ products at
    once (review 40: a 1000-beam scan's update ran the machine out of memory), and
    the blocks side by side four dense m x m arrays (review 44, EKFREV6: 3.2 GB for
    10,000 beams). None as :func:`_refined_inverse`.
    """
    if blocks is None:
        blocks = _r_blocks(r)
    m = r.shape[0]
    by_size: dict[int, list[tuple[list[int], tuple[FloatArray, ...]]]] = {}
    d = np.empty(m)
    kappa = 1.0
    for block in blocks:
        found = _refined_inverse(r if len(blocks) == 1 else r[np.ix_(block, block)])
        if found is None:
            return None
        scaled, refined, d[block], block_kappa = found[3]
        kappa = max(kappa, block_kappa)
        by_size.setdefault(len(block), []).append((block, (found[0], found[1], scaled, refined)))
    groups = [
        (
            np.array([block for block, _ in members], dtype=np.int64),
            *(np.stack([parts[i] for _, parts in members]) for i in range(4)),
        )
        for members in by_size.values()
    ]
    return _BlockInverse(m, groups, d, kappa)  # type: ignore[arg-type]


class _Information:
    """The information form's posterior, its state step and error, and the means to measure others.

    ``posterior`` is P⁺ = J⁻¹ (exactly symmetric), ``step`` P⁺ Hᵀ R⁻¹ y (and
    ``step_error`` a bound on its error, entry by entry),
    ``error`` P⁺'s estimated error in units of ε relative to
    ``sqrt(P⁺ᵢᵢ P⁺ⱼⱼ)``. ``scaled`` is J scaled to a unit diagonal
    (``d`` its scale) and ``reference`` P⁺ in the same units, ``floor`` (in
    relative units) the error common to every candidate measured against J:
    that of J itself.
    """

    __slots__ = ("d", "error", "floor", "posterior", "reference", "scaled", "step", "step_error")

    def __init__(
        self,
        posterior: FloatArray,
        step: FloatArray,
        error: float,
        scaled: FloatArray,
        reference: FloatArray,
        d: FloatArray,
        floor: float,
    ) -> None:
        self.posterior = posterior
        self.step = step
        self.error = error
        self.scaled = scaled
        self.reference = reference
        self.d = d
        self.floor = floor
        self.step_error = step

    def error_of(self, candidate: FloatArray) -> float:
        """The measured error of the covariance ``candidate``, in units of ε as ``error``.

        ``P⁺ (J X - I)`` is ``X - J⁻¹`` to first order (J X - I exact to one
        rounding), and J⁻¹ differs from the exact posterior by ``floor``. A
        non-finite ``candidate`` has an infinite error.
        """
        ref = self.reference
        scaled_candidate = candidate / (self.d * self.d[:, None])
        if not np.isfinite(scaled_candidate).all():
            return math.inf
        deviation = ref @ _product_minus_identity(self.scaled, scaled_candidate)
        unit = np.sqrt(ref.diagonal())
        measured = float(np.max(np.abs(deviation) / np.outer(unit, unit)))
        if not measured < math.inf:
            return math.inf
        return (measured + self.floor) / _EPS


def _refinement_work(p: FloatArray, blocks: list[list[int]]) -> float:
    """:func:`_information_update`'s work from sizes: its exact residuals' terms, b³ a block."""
    return float(sum(len(b) ** 3 for b in blocks) + 2 * p.shape[0] ** 3) * _RESIDUAL_TERM_WORK


def _information_update(
    p: FloatArray, jac: FloatArray, r: FloatArray, y: FloatArray
) -> _Information | None:
    """``P⁺ = (P⁻¹ + Hᵀ R⁻¹ H)⁻¹`` (exactly symmetric), the step ``P⁺ Hᵀ R⁻¹ y`` and P⁺'s error.

    P⁻¹ and R⁻¹ are refined once (:func:`_refined_inverse`), J = P⁻¹ + Hᵀ R⁻¹ H
    is scaled to a unit diagonal, inverted by Cholesky and the inverse refined
    once against J. Its error estimate, in units of ε relative to
    ``sqrt(P⁺ᵢᵢ P⁺ⱼⱼ)``: the residual that refinement leaves (``P⁺ (J P⁺ - I)``,
    measured) plus J's own error (the bounds of the refined inverses and J's
    roundings, entry by entry), carried through J⁻¹ to first order
    (|P⁺| δJ |P⁺|). P and R are positive definite (checked by the kernels and
    the public layer). None when a factorisation fails (a matrix singular to
    working precision) or P⁺ fails the kernels' test of a covariance
    (:func:`_positive_definite`: finite, the pivots of its LDLᵀ
    factorisation, those of D P⁺ D over dᵢ², normal floats); None too, with nothing
    computed, where its work (:func:`_refinement_work`) exceeds
    ``_EXACT_POSTERIOR_WORK_MAX`` (before review 43 unlimited: 140 s for a dense R
    of 800 components).
    """
    blocks = _r_blocks(r)
    if _refinement_work(p, blocks) > _EXACT_POSTERIOR_WORK_MAX:
        return None  # not made: past the cap, decided from sizes (review 43, EKFREV5)
    prior = _refined_inverse(p)
    noise = _refined_block_inverse(r, blocks)
    if prior is None or noise is None:
        return None
    p_inv = prior[0]
    abs_jac = np.abs(jac)
    gain_part = noise.sandwich(jac, 0)
    information = p_inv + gain_part
    found = _scaled_inverse_parts(information)
    if found is None:
        return None
    scaled, reference, d_j, kappa_j = found
    if not np.isfinite(reference).all():
        return None
    # One refinement step against J, then the residual it leaves (both exact sums).
    reference = reference - reference @ _product_minus_identity(scaled, reference)
    reference = 0.5 * (reference + reference.T)
    posterior = reference * d_j * d_j[:, None]
    posterior = 0.5 * (posterior + posterior.T)  # exactly symmetric, as a kernel's P
    if not _is_covariance(posterior):
        return None
    # J's own error, entry by entry: the refined inverses' bounds (H and its products
    # carry R⁻¹'s), and ε n for the roundings of Hᵀ R⁻¹ H and of the sum.
    n, m = jac.shape[1], jac.shape[0]
    perturbation = prior[1] + noise.sandwich(abs_jac, 2)
    perturbation += (n + 2) * _EPS * (np.abs(p_inv) + noise.sandwich(abs_jac, 1))
    scaled_perturbation = perturbation * d_j * d_j[:, None]
    abs_ref = np.abs(reference)
    unit = np.sqrt(reference.diagonal())
    floor = float(np.max((abs_ref @ scaled_perturbation @ abs_ref) / np.outer(unit, unit)))
    info = _Information(posterior, np.empty(0), 0.0, scaled, reference, d_j, floor)
    error = info.error_of(posterior)
    if not error < math.inf:
        return None
    info.error = error
    # The step s = P⁺ g, g = Hᵀ R⁻¹ y, each solve refined once against its exact
    # residual: w = R⁻¹ y with R scaled by powers of two (so that R⁻¹ y does not
    # overflow for a tiny R), then J s = g. P⁺ g can cancel far beyond P⁺'s error
    # (a residual of many posterior deviations, a correlated R): the bound on s's
    # error carries those of g (its roundings, w's refined error) and of J through
    # P⁺, entry by entry.
    d_r, kappa_r = noise.d, noise.kappa
    y_scaled = (y * d_r)[:, None]
    w = noise.scaled_solve(y_scaled)
    w_full = d_r[:, None] * w  # R⁻¹ y
    g_scaled = (jac.T @ w_full) * d_j[:, None]  # D_J g
    s = reference @ g_scaled  # D_J⁻¹ P⁺ g
    s = s - reference @ _exact_residual(scaled, s, g_scaled)
    info.step = s[:, 0] * d_j
    w_error = (4.0 * _EPS + 2.0 * (_EPS * kappa_r) ** 2) * noise.scaled_magnitude(y_scaled)
    g_error = (m + 2) * _EPS * (abs_jac.T @ np.abs(w_full)) + abs_jac.T @ (d_r[:, None] * w_error)
    abs_s = np.abs(s)
    s_error = abs_ref @ (g_error * d_j[:, None] + scaled_perturbation @ abs_s)
    s_error += (4.0 * _EPS + 2.0 * (_EPS * kappa_j) ** 2) * abs_s
    info.step_error = s_error[:, 0] * d_j
    return info


def _entry(kernel: Any, refused: float, *arrays: int) -> Any:
    """The compiled entry of ``kernel`` for its signature (see the module).

    ``arrays`` gives each argument's kind: the ndim of one of the filter's own
    arrays (a writeable C-contiguous float64 array, as numba types it), or
    minus the ndim of an :data:`OBJECT` (the user's). With numba's JIT
    disabled, the kernel itself (a plain function). Where NumPy's structs are
    not known to :mod:`navkit._shared.array_objects` (``LAYOUT_OK`` False:
    another NumPy major), the objects cannot be typed in C: the kernel is
    compiled for arrays in their place, and the entry is its dispatcher
    behind the public layer's former tests (:func:`_typed_by_dispatcher`),
    returning ``refused`` for what the C test refuses.
    """
    compile_for = getattr(kernel, "compile", None)
    if compile_for is None:  # NUMBA_DISABLE_JIT=1
        return kernel
    from numba.core import types  # here: importing this module must not import numba

    from navkit._shared.array_objects import LAYOUT_OK, OBJECT

    _DISPATCHERS.append(kernel)
    if not LAYOUT_OK:
        compile_for(tuple(types.Array(types.float64, abs(k), "C") for k in arrays))
        kernel.disable_compile()
        objects = tuple(i for i, k in enumerate(arrays) if k < 0)
        return _typed_by_dispatcher(kernel, objects, refused)
    sig = tuple(OBJECT if k < 0 else types.Array(types.float64, k, "C") for k in arrays)
    entry = compile_for(sig)
    kernel.disable_compile()  # nothing else ever reaches the dispatcher
    return entry


def _typed_by_dispatcher(kernel: Any, objects: tuple[int, ...], refused: float) -> Any:
    """``kernel`` (a dispatcher of one signature of arrays) as the entry of :func:`_entry`.

    The arguments at ``objects`` must be ndarrays exactly (numba's dispatcher
    would take a masked array's data, dropping its mask) of native byte order
    and of the compiled types (any other raises at dispatch): else
    ``refused``. numba's dispatcher itself does not tell byte orders apart
    once it has typed an unaligned array (its type cache keys an unaligned
    array by a fingerprint without the byte order): a big-endian array passed
    after an unaligned one was read as native float64, its bytes swapped.
    """

    def entry(*args: Any) -> Any:
        for i in objects:
            arg = args[i]
            if type(arg) is not np.ndarray or not arg.dtype.isnative:
                return refused
        try:
            return kernel(*args)
        except Exception:  # a dispatch failure: not of the compiled types
            return refused

    return entry


# The dispatchers of the kernels compiled so far (each for its one signature).
_DISPATCHERS: list[Any] = []
_PREDICT: dict[int, PredictKernel] = {}
_UPDATE: dict[tuple[int, int], UpdateKernel] = {}


def predict_kernel(n: int) -> PredictKernel:
    """The predict kernel of ``n``-state filters, compiled on first request.

    Compiled (or loaded from numba's cache) for its one signature: the
    filter's state array and three :data:`OBJECT` arguments. Returns the
    compiled entry (no dispatcher: the kernel types its arguments itself),
    which takes any objects.
    """
    kernel = _PREDICT.get(n)
    if kernel is None:
        kernel = _entry(_make_predict(n), BAD_TYPE, 2, -1, -2, -2)
        _PREDICT[n] = kernel
    return kernel


def update_kernel(n: int, m: int) -> UpdateKernel:
    """The update kernel of ``n``-state filters and ``m``-dimensional measurements.

    Compiled on first request, as :func:`predict_kernel`: the state, four
    :data:`OBJECT` arguments, the buffer and the residual (``y``, a new
    array of the caller's).
    """
    kernel = _UPDATE.get((n, m))
    if kernel is None:
        kernel = _entry(_make_update(n, m), _FAIL_TYPE, 2, -1, -1, -2, -2, 3, 1)
        _UPDATE[(n, m)] = kernel
    return kernel


def kernel_dispatchers() -> list[Any]:
    """The numba dispatchers of the kernels compiled so far (for tests: one signature each)."""
    return list(_DISPATCHERS)


def compile_kernels(n: int = 1, m: int = 1) -> None:
    """Compile (or load from numba's cache) the kernels of ``n`` states and ``m``-D measurements.

    Each kernel has one signature (its own arrays and :data:`OBJECT` arguments,
    see the module); afterwards they compile nothing more.
    """
    predict_kernel(n)
    update_kernel(n, m)
