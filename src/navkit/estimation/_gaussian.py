"""Base class of filters that hold a Gaussian state estimate (private)."""

from __future__ import annotations

import numpy as np

from navkit._shared.types import FloatArray

__all__ = ["GaussianEstimate"]


class GaussianEstimate:
    """Mean ``_x`` (n,) and covariance ``_p`` (n, n), published as copies.

    Subclasses own and update the two arrays; callers only ever see copies, so
    they cannot corrupt the filter by writing into what they read.
    """

    __slots__ = ("__weakref__", "_p", "_x")

    _x: FloatArray
    _p: FloatArray

    @property
    def x(self) -> FloatArray:
        """Current state estimate (n,), a copy."""
        return np.array(self._x, dtype=np.float64, copy=True)

    @property
    def P(self) -> FloatArray:
        """Current covariance (n, n), a copy."""
        return np.array(self._p, dtype=np.float64, copy=True)
