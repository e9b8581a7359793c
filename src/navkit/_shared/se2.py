"""SE(2) scalar kernels shared by every layer that moves poses (private).

Plain numba functions on scalars (and one on float64 arrays) compiled with
``cache=True``: angle wrapping, ``sinc``, the SE(2) exponential of a body twist
and pose composition. The geometry, kinematics and estimation kernels call them
so that wrapping and the exponential exist once.

The angle wrap, the exponential and the pose integration are compiled once
and inlined by LLVM into their callers (:data:`_ONCE`), not copied by numba at
each call site (``inline="always"``, which types and lowers the copy again
there: issue 17, review 51). ``sinc`` and ``compose_scalar``, called only
inside those, stay numba-inlined: they are copied once, into the one body
that is compiled.
"""

from __future__ import annotations

import math

from navkit._shared.jit import NO_REFCOUNT, njit_cached, njit_force_inline, njit_inline, typed_njit
from navkit._shared.types import FloatArray

_TWO_PI = 2.0 * math.pi

# Typed and lowered once, inlined by LLVM (alwaysinline) into every kernel calling it,
# where numba's IR-level copies were typed and lowered again at each call site (navkit
# warmup made 8 copies of wrap_scalar and 4 of exp_body, each with two of sinc). Unlike
# njit_force_inline it keeps a Python wrapper: the kinematics and the odometry call
# exp_body from Python, and tests call both.
_ONCE = typed_njit(**NO_REFCOUNT, forceinline=True)


@_ONCE
def wrap_scalar(a: float) -> float:
    """Wrap one finite angle to (-pi, pi]; angles already in range are returned unchanged."""
    if -math.pi < a <= math.pi:
        return a
    # fmod(a, 2pi) exactly (numba has no math.fmod; % of a non-negative float is fmod),
    # then one exact fold: bit for bit navkit._shared.angles.wrap_float.
    r = math.copysign(abs(a) % _TWO_PI, a)
    if r > math.pi:
        return r - _TWO_PI
    if r <= -math.pi:
        return r + _TWO_PI
    return r


#: Below this ``|x|`` (2**-10) :func:`sinc` takes its series, correctly rounded there.
SINC_SERIES_LIMIT = 0.0009765625


@njit_inline
def sinc(x: float) -> float:
    """sin(x)/x: its Taylor series for ``|x| < 2**-10``, else ``sin(x) / x``.

    The series ``1 - x²/6 + x⁴/120`` in Horner form ends with one rounding, of
    ``1 - x²(1/6 - x²/120)``: the truncation (x⁶/5040 < 1e-5 ulp of the
    result below 2**-10) and the inner roundings (x²/6 times a few 2**-53)
    leave it correctly rounded but for values within ~1e-5 ulp of a halfway
    point (none of 8·10^4 sampled against mpmath). ``sin(x) / x`` rounds twice,
    within 1 ulp but 1 ulp off for about a third of arguments, so the series
    is kept up to where its truncation still vanishes. Before review 49 the
    series (summed left to right, two roundings) ended at 1e-4, where
    ``sin(x) / x`` was 1 ulp off.
    """
    if abs(x) < SINC_SERIES_LIMIT:
        x2 = x * x
        return 1.0 - x2 * (1.0 / 6.0 - x2 / 120.0)
    return math.sin(x) / x


@_ONCE
def exp_body(vx: float, vy: float, omega: float, dt: float) -> tuple[float, float, float]:
    """Body-frame displacement (dx, dy, dtheta) of a constant twist held for ``dt``.

    This is the SE(2) exponential: with h = omega*dt/2,
    A = sin(2h)/(2h), B = (1 - cos 2h)/(2h) = sin(h)*sinc(h) and
    dx = dt*(A*vx - B*vy), dy = dt*(B*vx + A*vy). Written with ``sinc`` so that
    it is exact for straight lines and numerically stable as omega -> 0.
    """
    dth = omega * dt
    h = 0.5 * dth
    a = sinc(dth)
    b = math.sin(h) * sinc(h)
    return dt * (a * vx - b * vy), dt * (b * vx + a * vy), dth


@njit_inline
def compose_scalar(
    x: float, y: float, th: float, dx: float, dy: float, dth: float
) -> tuple[float, float, float]:
    """Pose (x, y, th) composed with a relative motion (dx, dy, dth) in its own frame."""
    c = math.cos(th)
    s = math.sin(th)
    return x + c * dx - s * dy, y + s * dx + c * dy, wrap_scalar(th + dth)


@njit_force_inline
def integrate_scalar(
    x: float, y: float, th: float, vx: float, vy: float, omega: float, dt: float
) -> tuple[float, float, float]:
    """Pose after holding the body twist (vx, vy, omega) for ``dt`` seconds."""
    dx, dy, dth = exp_body(vx, vy, omega, dt)
    return compose_scalar(x, y, th, dx, dy, dth)


@njit_cached
def exp_forward_array(vx: FloatArray, omega: FloatArray, out: FloatArray) -> None:
    """:func:`exp_body` of each row's forward distance and turn (``vy`` 0, ``dt`` 1) into ``out``.

    ``vx``, ``omega``: 1-D arrays of equal length; ``out``: (N, 3). One odometry
    step a row, without the two constant arrays of the input's size (``vy``,
    ``dt``) that a general vectorised form would need.
    """
    for i in range(vx.shape[0]):
        dx, dy, dth = exp_body(vx[i], 0.0, omega[i], 1.0)
        out[i, 0] = dx
        out[i, 1] = dy
        out[i, 2] = dth
