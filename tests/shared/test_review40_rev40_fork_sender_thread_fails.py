"""An early signal's exception when the held signals' sender thread cannot start (review 40, REV40).

navkit's fork hooks hold every signal with a Python handler across a fork and
send those that came again once ``os.fork`` returns, from a short-lived thread
(``interrupts.release_in_parent``); a signal that landed before its hold was in
place has its handler's exception kept and raised as ``os.fork`` returns.
Review 39 (REV39) starts the sender thread before arranging that raise, so that
an exception raised in the hook (a profiler in use) no longer takes the held
signals with it. But a thread that cannot start (``RuntimeError: can't start
new thread``, as when the fork took the last process of ``RLIMIT_NPROC``, which
threads count against on Linux) now takes the early exception with it: the
program's ``SIGTERM`` handler raised ``SystemExit`` and the caller never saw it
(before review 39 it did). Now the raise is arranged whatever became of the
sender.

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

# As test_review39_rev39_fork_profiler_signals.py: a thread holds numba's compiler
# lock, so the main thread's fork waits in its before hook; a SIGTERM whose handler
# raises lands as the hook starts (before the hold), a SIGUSR1 from the thread
# once the hook waits (held). Here no thread can start once the fork is made.
_EARLY_AND_NO_THREAD = textwrap.dedent(
    """
    import faulthandler, json, os, signal, sys, threading, time
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
            # Not on a timer: once the fork's hook waits for the compiler lock.
            main, frame = threading.main_thread().ident, None
            end = time.monotonic() + 50
            while time.monotonic() < end and (
                frame is None or frame.f_code.co_name != "_take_for_fork"
            ):
                time.sleep(0.002)
                frame = sys._current_frames().get(main)
            os.kill(os.getpid(), signal.SIGUSR1)
            time.sleep(0.05)

    forked = []
    start = threading.Thread.start

    def no_thread_after_the_fork(self):
        if forked:  # the process limit reached by the fork
            raise RuntimeError("can't start new thread")
        start(self)

    threading.Thread.start = no_thread_after_the_fork
    os.register_at_fork(before=lambda: forked.append(1))  # runs first, before navkit's

    def tracer(frame, event, arg):
        if event == "call" and frame.f_code.co_name == "_forks":
            sys.settrace(None)
            signal.raise_signal(signal.SIGTERM)
        return None

    thread = threading.Thread(target=compile_elsewhere, daemon=True)
    thread.start()
    holding.wait(10)
    sys.settrace(tracer)
    pid = None
    early = False
    try:
        pid = os.fork()
        if pid == 0:
            os._exit(0)
        time.sleep(0.001)
    except SystemExit:
        early = True
    sys.settrace(None)
    os.waitpid(pid or -1, 0)
    thread.join(10)
    print(json.dumps([early, usr1 == []]))
    """
)


def test_an_early_signal_s_exception_reaches_the_caller_when_no_thread_can_start() -> None:
    # The SIGUSR1 was held during the fork (its sender could not start: lost, as
    # before review 39), and the SIGTERM's SystemExit reached the caller.
    assert probe_outcome(_EARLY_AND_NO_THREAD, timeout=120) == [True, True]
