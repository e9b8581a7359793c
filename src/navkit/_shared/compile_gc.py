"""Pause Python's cyclic garbage collector while numba compiles navkit's kernels (private).

numba's compiler allocates many objects (IR nodes, types, LLVM wrappers) that
live until the compile ends, so during a first use the cyclic collector runs
hundreds of times, each oldest-generation pass scanning everything the process
holds, and frees nothing useful: on Field D*'s first use (plan, update, replan)
about 600 collections and 0.3 s of 3.9 s of CPU (issue 17; 0.08 s of the
0.48 s of a use that loads the kernels from numba's cache, most of it numba's
own initialisation).

* :func:`paused` disables the collector for a block and restores its previous
  state; :func:`navkit._shared.jit.load_numba` imports numba and initialises
  its compiler inside it.
* :func:`install` registers two listeners with numba's event API
  (``numba.core.event``): at the start of the compile of a navkit kernel the
  collector is disabled, and it is restored to its previous state when the
  compiling thread releases numba's compiler lock (after the kernel, its
  callees and its cache file are done, or the compile failed). Compiles of
  other code (the user's own kernels) are left alone, and loading a kernel
  from numba's cache changes nothing.

Garbage made meanwhile is collected as usual afterwards; the peak memory of a
compile rises by a few tens of MB (25 MB measured on Field D*'s).
"""

from __future__ import annotations

import gc
import importlib
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

__all__ = ["install", "paused"]

_INSTALLED: list[Any] = []


def _is_navkit(dispatcher: Any) -> bool:
    module = getattr(getattr(dispatcher, "py_func", None), "__module__", None) or ""
    return module == "navkit" or module.startswith("navkit.")


def _make_listeners() -> tuple[Any, Any]:
    """The listeners of numba's compile events and of its compiler lock."""
    # Any: numba's event module is not typed in every supported numba version.
    event: Any = importlib.import_module("numba.core.event")
    state = threading.local()

    def lock_depth() -> int:
        depth: int = getattr(state, "depth", 0)
        return depth

    class CompileStart(event.Listener):  # type: ignore[misc]  # (a class of Any)
        """Pause the collector when a navkit kernel's compile starts."""

        def on_start(self, ev: Any) -> None:
            data = ev.data if isinstance(ev.data, dict) else {}
            if getattr(state, "paused", False) or not _is_navkit(data.get("dispatcher")):
                return
            state.paused = True
            state.resume = gc.isenabled()
            gc.disable()

        def on_end(self, ev: Any) -> None:
            """Nothing here: the collector resumes when the compiler lock is released."""

    class LockRelease(event.Listener):  # type: ignore[misc]
        """Resume it when the compiling thread releases numba's compiler lock."""

        def on_start(self, ev: Any) -> None:
            state.depth = lock_depth() + 1

        def on_end(self, ev: Any) -> None:
            # Not below 0: a release whose acquire came before install() (numba
            # loaded from inside a compile, e.g. a user's kernel typing a navkit
            # one) would otherwise leave the count one low for good, and later
            # pauses would end at an inner release, mid-compile.
            state.depth = max(lock_depth() - 1, 0)
            if state.depth == 0 and getattr(state, "paused", False):
                state.paused = False
                if state.resume:
                    gc.enable()

    return CompileStart(), LockRelease()


@contextmanager
def paused() -> Iterator[None]:
    """Disable the collector for the block, then restore its previous state.

    For navkit's own one-off work in the library's many allocations: importing
    numba and initialising its compiler (:func:`navkit._shared.jit.load_numba`).

    Examples
    --------
    >>> import gc
    >>> with paused():
    ...     gc.isenabled()
    False
    >>> gc.isenabled()
    True
    """
    resume = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if resume:
            gc.enable()


def install() -> None:
    """Register the listener once (call after numba is imported).

    Examples
    --------
    >>> from navkit._shared import compile_gc
    >>> compile_gc.install()
    >>> compile_gc.install()  # idempotent
    >>> len(compile_gc._INSTALLED)
    2
    """
    if _INSTALLED:
        return
    event: Any = importlib.import_module("numba.core.event")
    on_compile, on_lock = _make_listeners()
    event.register("numba:compile", on_compile)
    event.register("numba:compiler_lock", on_lock)
    _INSTALLED.extend((on_compile, on_lock))
