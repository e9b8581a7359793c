"""numba kernels behind :func:`navkit.geometry.integrate` and ``rollout`` (private).

Plain functions on scalars and float64 arrays, compiled with ``cache=True``; the
public layer validates input before calling them. The SE(2) scalar helpers
themselves live in :mod:`navkit._shared.se2`, inlined here: numba's cache keys
these kernels on this file alone, so a change of those helpers comes with a note
here (review 49: ``sinc``'s series, now in Horner form below 2**-10, was below 1e-4;
review 51: ``integrate_scalar`` is compiled once and inlined by LLVM, the same arithmetic).
"""

from __future__ import annotations

import numpy as np

from navkit._shared.jit import njit_cached
from navkit._shared.se2 import integrate_scalar


@njit_cached
def integrate_kernel(
    x: float, y: float, th: float, vx: float, vy: float, omega: float, dt: float
) -> tuple[float, float, float]:
    """Callable-from-Python entry to :func:`integrate_scalar`."""
    return integrate_scalar(x, y, th, vx, vy, omega, dt)


@njit_cached
def rollout_kernel(
    x: float, y: float, th: float, twists: np.ndarray, dts: np.ndarray, out: np.ndarray
) -> None:
    """Fill ``out`` (N+1, 3) with the poses of a twist sequence (N, 3) held for ``dts`` (N,)."""
    out[0, 0] = x
    out[0, 1] = y
    out[0, 2] = th
    for i in range(twists.shape[0]):
        x, y, th = integrate_scalar(x, y, th, twists[i, 0], twists[i, 1], twists[i, 2], dts[i])
        out[i + 1, 0] = x
        out[i + 1, 1] = y
        out[i + 1, 2] = th
