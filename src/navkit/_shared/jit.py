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
* :data:`njit_helper`: :data:`njit_no_refcount` without a Python wrapper, for
  helpers called only from other kernels;
* :data:`njit_force_inline` / :data:`njit_not_inlined`: compiled once and
  inlined by LLVM, and the callee of such a function that must stay a call;
* :func:`typed_njit`: any other options (``typed_njit(cache=True, fastmath=...)``).

None of them builds a cfunc wrapper (``no_cfunc_wrapper=True``): navkit never
passes a kernel as a first-class function value, and every wrapper is compiled
and optimised with its kernel on first use.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar, cast

from numba import njit

_F = TypeVar("_F", bound=Callable[..., Any])


def typed_njit(**options: Any) -> Callable[[_F], _F]:
    """``numba.njit(**options)`` typed as a decorator that keeps the function's signature."""
    return cast(Callable[[_F], _F], njit(**options))


#: Options every navkit kernel is compiled with.
CACHED: dict[str, Any] = {"cache": True, "no_cfunc_wrapper": True}

njit_cached: Callable[[_F], _F] = typed_njit(**CACHED)
"""``numba.njit(cache=True)``."""

njit_inline: Callable[[_F], _F] = typed_njit(**CACHED, inline="always")
"""``numba.njit(cache=True, inline="always")``: inlined into the calling kernel."""

# Kernels that allocate nothing are compiled without numba's reference counting
# (the private jit option ``_nrt=False``). With it, every call that passes arrays
# increments and decrements their reference counts atomically, which perf showed
# to take about a third of an A* search's time. Such a function must not create
# arrays; numba refuses to compile it if it does.
NO_REFCOUNT: dict[str, Any] = {**CACHED, "_nrt": False}

njit_no_refcount: Callable[[_F], _F] = typed_njit(**NO_REFCOUNT)
"""``numba.njit(cache=True)`` without reference counting, for allocation-free kernels."""

njit_inline_no_refcount: Callable[[_F], _F] = typed_njit(inline="always", **NO_REFCOUNT)
"""As :data:`njit_no_refcount`, inlined into the caller at numba IR level."""

njit_helper: Callable[[_F], _F] = typed_njit(**NO_REFCOUNT, no_cpython_wrapper=True)
"""As :data:`njit_no_refcount`, for a helper called only from other kernels: no
Python wrapper is compiled (a wrapper of many arguments alone costs tenths of a
second), so Python cannot call it."""

njit_force_inline: Callable[[_F], _F] = typed_njit(**NO_REFCOUNT, forceinline=True)
"""``njit_no_refcount`` compiled once and inlined by LLVM (``alwaysinline``) into
its callers: as fast as numba's IR-level ``inline="always"``, which copies and
re-types the body at every call site (seconds of first-use compilation for a
body inlined eight times), but typed once. Its arguments must not be literals
at any call site: each literal value compiles it once more."""

njit_not_inlined: Callable[[_F], _F] = typed_njit(**NO_REFCOUNT, forceinline=False)
"""``njit_no_refcount`` for a kernel called from an LLVM-inlined one (numba's
``forceinline``): numba passes that flag on to callees that leave it unset,
which would inline this one into every call site too."""
