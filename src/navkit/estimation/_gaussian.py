"""Base class of filters that hold a Gaussian state estimate (private)."""

from __future__ import annotations

from typing import Any

import numpy as np

from navkit._shared.types import FloatArray

__all__ = ["GaussianEstimate", "subclass_state"]


class GaussianEstimate:
    """Mean ``_x`` (n,) and covariance ``_p`` (n, n), published as copies.

    Subclasses own and update the two arrays; callers only ever see copies, so
    they cannot corrupt the filter by writing into what they read.
    """

    __slots__ = ("_p", "_x")

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


def subclass_state(obj: Any, base: type) -> tuple[dict[str, Any] | None, dict[str, Any]] | None:
    """What a subclass of ``base`` adds to ``obj``, in Python's default pickle state layout.

    The filters pickle and copy themselves through ``__reduce__`` (their estimate
    lives in one array with views into it), which rebuilds an instance of the
    class from that array alone. For an instance of a subclass this returns
    ``(instance __dict__ or None, {slot: value})`` of the slots the subclasses
    declare (private names mangled), which :mod:`pickle` and :mod:`copy` restore
    after the rebuild, so that subclasses copy whole; None for ``base`` itself or
    when there is nothing to add.
    """
    slots: dict[str, Any] = {}
    for klass in type(obj).__mro__:
        if klass is base:
            break
        declared = klass.__dict__.get("__slots__", ())
        for name in (declared,) if isinstance(declared, str) else declared:
            if name in ("__dict__", "__weakref__"):
                continue
            if name.startswith("__") and not name.endswith("__"):
                name = f"_{klass.__name__.lstrip('_')}{name}"
            if hasattr(obj, name):
                slots[name] = getattr(obj, name)
    instance = getattr(obj, "__dict__", None) or None
    if instance is None and not slots:
        return None
    return instance, slots
