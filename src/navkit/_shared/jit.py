"""Typed numba compilation decorators shared by every kernel module (private).

``numba.njit`` carries no type annotations before numba 0.62 (navkit supports
0.61.2), so under ``mypy --strict`` a function decorated with it directly
becomes untyped ("Untyped decorator makes function untyped"). These
decorators are ``njit`` with navkit's options, cast to keep the decorated
function's signature; kernel modules use them instead of ``numba.njit``:

* :data:`njit_cached`: ``njit(cache=True)``;
* :data:`njit_inline`: ``njit(cache=True, inline="always")``, inlined into its
  callers at numba IR level;
* :data:`njit_no_refcount` / :data:`njit_inline_no_refcount`: the same without
  numba's reference counting, for kernels that allocate nothing;
* :func:`typed_njit`: any other options (``typed_njit(cache=True, fastmath=...)``).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar, cast

from numba import njit

_F = TypeVar("_F", bound=Callable[..., Any])


def typed_njit(**options: Any) -> Callable[[_F], _F]:
    """``numba.njit(**options)`` typed as a decorator that keeps the function's signature."""
    return cast(Callable[[_F], _F], njit(**options))


njit_cached: Callable[[_F], _F] = typed_njit(cache=True)
"""``numba.njit(cache=True)``."""

njit_inline: Callable[[_F], _F] = typed_njit(cache=True, inline="always")
"""``numba.njit(cache=True, inline="always")``: inlined into the calling kernel."""

# Kernels that allocate nothing are compiled without numba's reference counting
# (the private jit option ``_nrt=False``). With it, every call that passes arrays
# increments and decrements their reference counts atomically, which perf showed
# to take about a third of an A* search's time. Such a function must not create
# arrays; numba refuses to compile it if it does.
NO_REFCOUNT: dict[str, Any] = {"cache": True, "_nrt": False}

njit_no_refcount: Callable[[_F], _F] = typed_njit(**NO_REFCOUNT)
"""``numba.njit(cache=True)`` without reference counting, for allocation-free kernels."""

njit_inline_no_refcount: Callable[[_F], _F] = typed_njit(inline="always", **NO_REFCOUNT)
"""As :data:`njit_no_refcount`, inlined into the caller at numba IR level."""
