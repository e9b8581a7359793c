"""compile_gc's listeners interrupted at every point CPython delivers a Ctrl-C.

The listeners begin a pause of the collector (and navkit's compile shortcuts)
when a navkit kernel's compile starts and end it when the compiling thread
releases numba's compiler lock. A ``KeyboardInterrupt`` landing between their
steps (on entering ``_end_pause``, after ``gc.enable``'s neighbours return...)
left the collector off, the pause count wrong or the shortcuts on for the rest
of the process (a fresh-eyes review, session 22). Now the steps run with a
Ctrl-C held back; one landing before them leaves the pause to the thread's
next release of the lock.

The interrupts are injected through ``sys.setprofile`` at every ``call`` and
``c_return`` event of the start and of the release, in turn, as CPython would
deliver a ``SIGINT``: to the handler in place at that moment (Python's default
raises ``KeyboardInterrupt``; navkit's hold keeps it for later).
"""

from __future__ import annotations

import sys

import pytest

from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

_PROBE = r"""
import gc, json, signal, sys, types
from navkit._shared import compile_gc, compile_shortcuts, jit
jit.load_numba()
from numba.core.compiler_lock import global_compiler_lock
from navkit.planning.grid import _astar_kernels

on_compile, _ = compile_gc._INSTALLED
navkit_compile = types.SimpleNamespace(data={"dispatcher": _astar_kernels.grid_search})
where = sys.argv[1]

def state():
    return [gc.isenabled(), compile_gc._PAUSES, compile_shortcuts.active()]

def interrupted_at(k):
    # The lock taken and a navkit compile started, as numba does; then the start
    # ("start") or the release ("release") interrupted at its k-th delivery point.
    seen = 0
    hits = []
    def profile(frame, event, arg):
        nonlocal seen
        if event in ("call", "c_return"):
            seen += 1
            if seen == k:
                sys.setprofile(None)
                hits.append(frame.f_code.co_name)
                handler = signal.getsignal(signal.SIGINT)
                if handler is signal.default_int_handler:
                    raise KeyboardInterrupt
                handler(signal.SIGINT, frame)
    global_compiler_lock.acquire()
    if where == "release":
        on_compile.on_start(navkit_compile)
    sys.setprofile(profile)
    try:
        if where == "start":
            on_compile.on_start(navkit_compile)
            sys.setprofile(None)
        global_compiler_lock.release()
        # A Ctrl-C held in the lock's release arrives as it is done (review 39).
        sys.setprofile(None)
    except KeyboardInterrupt:
        pass
    finally:
        sys.setprofile(None)
    if not hits:
        return None
    if global_compiler_lock.is_locked():  # numba's own release interrupted: let go
        global_compiler_lock._lock.release()
    with global_compiler_lock:  # the thread's next use of the lock (a cache load)
        pass
    after_next_release = state()
    global_compiler_lock.acquire()  # its next navkit compile
    on_compile.on_start(navkit_compile)
    during = state()
    global_compiler_lock.release()
    return {"at": hits[0], "next": after_next_release, "during": during, "after": state()}

outcomes = []
k = 1
while k < 500:
    outcome = interrupted_at(k)
    if outcome is None:
        break
    outcomes.append(outcome)
    k += 1
print(json.dumps(outcomes))
"""


@pytest.mark.parametrize("where", ["start", "release"])
def test_an_interrupt_anywhere_in_the_listeners_leaves_no_pause(where: str) -> None:
    outcomes = probe_outcome(_PROBE, where)
    points = {o["at"] for o in outcomes}
    # Every step was reached (the pause's and the shortcuts' own functions).
    assert ({"_begin_pause", "begin"} if where == "start" else {"_end_pause", "end"}) <= points
    for outcome in outcomes:
        assert outcome["next"] == [True, 0, False], outcome
        assert outcome["during"] == [False, 1, True], outcome
        assert outcome["after"] == [True, 0, False], outcome
