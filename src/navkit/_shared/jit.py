"""Compilation options shared by the planning kernels (private)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar, cast

from numba import njit

_F = TypeVar("_F", bound=Callable[..., Any])

# Kernels that allocate nothing are compiled without numba's reference counting
# (the private jit option ``_nrt=False``). With it, every call that passes arrays
# increments and decrements their reference counts atomically, which perf showed
# to take about a third of an A* search's time. Such a function must not create
# arrays; numba refuses to compile it if it does.
NO_REFCOUNT: dict[str, Any] = {"cache": True, "_nrt": False}

njit_no_refcount = cast(Callable[[_F], _F], njit(**NO_REFCOUNT))
"""``numba.njit(cache=True)`` without reference counting, for allocation-free kernels."""

njit_inline_no_refcount = cast(
    Callable[[_F], _F], njit(inline="always", **NO_REFCOUNT)
)
"""As :data:`njit_no_refcount`, inlined into the caller at numba IR level."""
