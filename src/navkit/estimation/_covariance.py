"""Validation helpers specific to estimation: covariance matrices and index lists (private)."""

from __future__ import annotations

import numbers
from collections.abc import Iterable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array

__all__ = ["covariance", "index_tuple"]

# Relative tolerance for symmetry and semi-definiteness checks of user matrices.
_REL_TOL = 1e-9


def covariance(value: ArrayLike, name: str, n: int, *, semidefinite: bool = False) -> FloatArray:
    """Return ``value`` as a symmetric (n, n) float64 covariance or raise naming ``name``.

    Positive definiteness is required unless ``semidefinite`` (process noise may
    be zero on some states). Tiny asymmetry from rounding is averaged out.
    """
    arr = as_float_array(value, name, shape=(n, n))
    scale = max(float(np.max(np.abs(arr))), 1e-300)
    if np.max(np.abs(arr - arr.T)) > _REL_TOL * scale:
        raise ValueError(f"{name} must be symmetric")
    arr = np.asarray(0.5 * (arr + arr.T), dtype=np.float64)
    if semidefinite:
        if n and float(np.linalg.eigvalsh(arr)[0]) < -_REL_TOL * scale:
            raise ValueError(f"{name} must be positive semi-definite")
    else:
        try:
            np.linalg.cholesky(arr)
        except np.linalg.LinAlgError:
            raise ValueError(f"{name} must be positive definite") from None
    return arr


def index_tuple(indices: Iterable[Any], name: str, n: int) -> tuple[int, ...]:
    """Validate distinct integer indices into a length-``n`` vector."""
    try:
        items = tuple(indices)
    except TypeError:
        raise TypeError(f"{name} must be a sequence of integer indices") from None
    out: list[int] = []
    for item in items:
        if isinstance(item, bool) or not isinstance(item, numbers.Integral):
            raise TypeError(f"{name} must hold integers, got {item!r}")
        if not 0 <= int(item) < n:
            raise ValueError(f"{name} index {int(item)} is out of range for length {n}")
        out.append(int(item))
    if len(set(out)) != len(out):
        raise ValueError(f"{name} holds duplicate indices: {out}")
    return tuple(out)
