"""A ``KeyboardInterrupt`` injected where CPython can deliver one, through ``sys.setprofile``.

CPython runs a pending signal handler on entering a Python function and after a C
call returns: the profiler's ``call`` and ``c_return`` events. Exception-safety tests
interrupt a call at its k-th such point, for every k, and check what it leaves.
"""

from __future__ import annotations

import gc
import sys
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

#: Profiler events at which CPython delivers a pending interrupt.
DELIVERY: tuple[str, ...] = ("call", "c_return")


def interrupted_at(
    k: int, call: Callable[[], object], *, events: Sequence[str] = DELIVERY
) -> bool:
    """Run ``call`` with a KeyboardInterrupt at its ``k``-th of ``events``; True if raised."""
    try:
        _profiled(call, events, stop_at=k)
    except KeyboardInterrupt:
        return True
    return False


def delivery_points(call: Callable[[], object], *, events: Sequence[str] = DELIVERY) -> int:
    """How many of ``events`` ``call`` passes (run it on a copy of what it changes)."""
    return _profiled(call, events, stop_at=0)


def _profiled(call: Callable[[], object], events: Sequence[str], *, stop_at: int) -> int:
    """Run ``call`` counting ``events``; a KeyboardInterrupt at the ``stop_at``-th (0: none)."""
    seen = 0
    armed = True

    def profile(frame: Any, event: str, arg: Any) -> None:
        nonlocal seen
        if armed and event in events:
            seen += 1
            if seen == stop_at:
                sys.setprofile(None)
                raise KeyboardInterrupt

    # An interrupt landing inside ``np.errstate.__enter__`` (Python code,
    # after it set its context variable) leaves that error state set: the outer
    # errstate's reset puts the caller's back whatever the call left.
    # No garbage collection inside the call: a collection there runs other objects'
    # finalizers and weak-reference callbacks (Python calls, so more delivery points),
    # which made the count differ from run to run (session 37: a weak-valued table's
    # callback, as the records' copies left garbage behind).
    enabled = gc.isenabled()
    gc.disable()
    try:
        with np.errstate():
            sys.setprofile(profile)
            try:
                call()
                armed = False  # not the finally's own call
            finally:
                sys.setprofile(None)
    finally:
        if enabled:
            gc.enable()
    return seen


def interleaved(
    k: int, main: Callable[[], Any], handler: Callable[[], Any], *, catch_main: bool = True
) -> dict[str, Any]:
    """Run ``main``, running ``handler`` at its ``k``-th delivery point, as a signal would.

    Returns what each returned or the RuntimeError it raised (``"h"`` missing: the
    call had fewer points; ``catch_main=False`` lets ``main``'s propagate), and
    ``"points"``, how many ``main`` passed. No garbage collection meanwhile (no
    finalizers' calls among the points, see :func:`_profiled`).
    """
    seen = 0
    out: dict[str, Any] = {}

    def profile(frame: Any, event: str, arg: Any) -> None:
        nonlocal seen
        if event in DELIVERY:
            seen += 1
            if seen == k:
                sys.setprofile(None)
                try:
                    out["h"] = handler()
                except RuntimeError as error:
                    out["h"] = error

    enabled = gc.isenabled()
    gc.disable()
    sys.setprofile(profile)
    try:
        out["m"] = main()
    except RuntimeError as error:
        if not catch_main:
            raise
        out["m"] = error
    finally:
        sys.setprofile(None)
        if enabled:
            gc.enable()
    out["points"] = seen
    return out


#: Probe-script source (needs ``signal`` imported): an import hook, ``Interrupt``,
#: raising SIGINT once as numba imports its typing package, as a user's Ctrl-C
#: would land; ``Interrupt.fired`` tells whether it did. Install it with
#: ``sys.meta_path.insert(0, Interrupt())`` before numba is imported.
CTRL_C_IN_NUMBA_IMPORT = """
class Interrupt:
    # Ctrl-C while numba imports its typing package, as a user's would land.
    fired = False
    def find_spec(self, name, path=None, target=None):
        if name == "numba.core.typing" and not Interrupt.fired:
            Interrupt.fired = True
            signal.raise_signal(signal.SIGINT)
        return None
"""
