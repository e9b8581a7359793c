"""Products computed the same way on every CPU, or where partial sums overflow (private).

:func:`ordered_dot` is ``np.dot`` of two short vectors with the products added
in order, one rounded product at a time: what OpenBLAS's x86-64 kernels of the
AVX2 era (Haswell, Zen, Sandy Bridge, Nehalem) compute for up to 15 terms, and
what its AVX-512 kernels (SkylakeX, Cooper Lake, Sapphire Rapids) do not: they
fuse multiplies and adds and add in another order, so a result that depends on
the last bit of a dot product (a norm, a speed limit) differed on those CPUs.

``rows @ matrix_t`` adds terms that can each exceed the float range (or whose
running sum does) while the sum fits: large terms of opposite signs cancel, a
large input meets a large entry before a small one. :func:`scaled_product`
computes such rows again with their largest input scaled to [0.5, 1) by an exact
power of two, where no term overflows, and scales them back; a result beyond
the float range stays infinite for the caller to refuse.
"""

from __future__ import annotations

import numpy as np

from navkit._shared.types import FloatArray

__all__ = ["ORDERED_MAX", "ordered_dot", "scaled_product"]

#: Most terms :func:`ordered_dot` adds in order; longer vectors go to ``np.dot``
#: (whose older kernels add 16 or more terms in blocks, not in order).
ORDERED_MAX = 15


def ordered_dot(a: FloatArray, b: FloatArray) -> float:
    """``float(np.dot(a, b))`` of 1-D float64 arrays, added in order up to 15 terms.

    ``0.0 + a[0]*b[0] + a[1]*b[1] + ...``, each product rounded, then each sum:
    the same bits on every CPU, equal to those of OpenBLAS's Haswell kernel
    (which computed navkit's documented figures). Vectors of more than
    :data:`ORDERED_MAX` terms use ``np.dot``. Products beyond the float range
    give ``inf`` (no warning, no error under any ``np.seterr``).

    Examples
    --------
    >>> ordered_dot(np.array([3.0, 4.0]), np.array([3.0, 4.0]))
    25.0
    """
    if a.shape[0] > ORDERED_MAX:
        return float(np.dot(a, b))
    total = 0.0
    for x, y in zip(a.tolist(), b.tolist(), strict=True):
        total += x * y
    return total


def scaled_product(rows: FloatArray, matrix_t: FloatArray) -> FloatArray:
    """``rows @ matrix_t`` for finite ``rows`` (..., K) and ``matrix_t`` (K, M), as a new array.

    Rows whose plain product is finite are returned bit for bit as ``rows @
    matrix_t`` gives them; the others are computed at a scale where no partial
    sum overflows (entries of ``matrix_t`` up to about 1e300 in magnitude).
    Entries beyond the float range come back infinite (no warning).

    Examples
    --------
    >>> scaled_product(np.array([1.5e308, 1.5e308]), np.array([[1.0], [-0.5]]))
    array([7.5e+307])
    """
    # Tiny terms underflow to 0 as under NumPy's defaults, whatever the caller's np.seterr.
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        out: FloatArray = rows @ matrix_t
    bad = ~np.isfinite(out).all(axis=-1)
    if bad.any():
        big = rows[bad]
        # frexp: peak = mantissa * 2**exponent with mantissa in [0.5, 1); the scaling by
        # 2**-exponent is exact except for inputs below 2**-1022 of the row's largest,
        # which round by at most 2**-1075 of it: far below the rounding of the terms.
        _, exponent = np.frexp(np.max(np.abs(big), axis=-1, keepdims=True))
        with np.errstate(over="ignore", invalid="ignore", under="ignore"):
            out[bad] = np.ldexp(np.ldexp(big, -exponent) @ matrix_t, exponent)
    return out
