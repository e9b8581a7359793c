"""Signals held during a fork when another came before the hold (review 39, REV39).

navkit's fork hooks hold every signal with a Python handler from the before
hook's start to ``os.fork``'s return, and send those that came meanwhile again
after it, in the parent (``navkit._shared.interrupts.release_in_parent``). A
signal landing before its hold is in place runs its handler there; an
exception it raises is kept and raised as ``os.fork`` returns, through a
profile function (review 38). With a profiler of the program's in use
(``cProfile``), that exception is raised in the after hook instead, where
Python reports it as ignored (documented in ``docs/compilation.md``), and it
took the signals held during the fork with it: they were never sent again.
They are sent now whatever becomes of the early exception.

Every case runs in a fresh interpreter with a timeout.
"""

from __future__ import annotations

import os
import sys
import textwrap

import pytest

from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(
    not hasattr(os, "fork") or sys.platform != "linux", reason="needs os.fork"
)

# A thread holds numba's compiler lock (as a compile does), so the main
# thread's fork waits in its before hook; a SIGTERM whose handler raises lands
# as the hook starts (before the hold), a SIGUSR1 from the thread during the wait
# (held). The SIGUSR1 handler only notes it.
_EARLY_AND_HELD = textwrap.dedent(
    """
    import cProfile, faulthandler, json, os, signal, sys, threading, time
    faulthandler.dump_traceback_later(60, exit=True)
    from navkit._shared.jit import load_numba
    from numba.core.compiler_lock import global_compiler_lock

    load_numba()
    usr1 = []

    def on_term(signum, frame):
        raise SystemExit("terminated")

    signal.signal(signal.SIGTERM, on_term)
    signal.signal(signal.SIGUSR1, lambda signum, frame: usr1.append(os.getpid()))
    holding = threading.Event()

    def compile_elsewhere():
        with global_compiler_lock:
            holding.set()
            time.sleep(0.3)
            os.kill(os.getpid(), signal.SIGUSR1)
            time.sleep(0.3)

    def tracer(frame, event, arg):
        if event == "call" and frame.f_code.co_name == "_forks":
            sys.settrace(None)
            signal.raise_signal(signal.SIGTERM)
        return None

    thread = threading.Thread(target=compile_elsewhere, daemon=True)
    thread.start()
    holding.wait(10)
    if sys.argv[1] == "profiled":
        profiler = cProfile.Profile()
        profiler.enable()
    sys.settrace(tracer)
    pid = None
    try:
        pid = os.fork()
        if pid == 0:
            os._exit(0)
        time.sleep(0.001)
    except SystemExit:
        pass
    sys.settrace(None)
    end = time.monotonic() + 2.0
    while time.monotonic() < end and not usr1:
        time.sleep(0.002)
    if sys.argv[1] == "profiled":
        profiler.disable()
    os.waitpid(pid or -1, 0)
    thread.join(10)
    print(json.dumps(usr1.count(os.getpid())))
    """
)


@pytest.mark.parametrize(
    "mode",
    [
        "plain",
        "profiled",
    ],
)
def test_a_signal_held_during_a_fork_reaches_the_parent_after_an_early_one(mode: str) -> None:
    # The held SIGUSR1 reaches its handler once in the parent, whatever became of the
    # early SIGTERM's exception.
    assert probe_outcome(_EARLY_AND_HELD, mode, timeout=120) == 1
