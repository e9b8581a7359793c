"""A Ctrl-C at any point of navkit's fork hooks leaves no lock held; nested forks (review 37).

navkit's fork hooks (``navkit._shared.compile_gc``) take numba's compiler lock,
navkit's import lock and the collector's pause lock before a fork and let go
of them after it. A Ctrl-C waiting for another thread's lock was held and raised
after the fork (review 36), but one landing elsewhere in the hooks (the locks
were free, so nothing was held) raised there; Python reports an exception in a
fork hook as ignored and goes on. Landing between a lock's acquire and its
record, or in the after hook before its releases, it left the lock held by the
forking thread for good: numba's compiler lock held by the main thread, and
every other thread's first kernel call (and its next fork) waited for ever; or
it left the after hook failing ("cannot release un-acquired lock") before its
releases. 15 of the hooks' 28 delivery points did. A Ctrl-C is now held from
the hook's start to ``os.fork``'s return, and the points left (before the hold,
after the handler is back) have nothing taken.

The hooks are called as ``os.fork`` calls them (each exception reported and
ignored), with a ``KeyboardInterrupt`` injected at each point CPython delivers
one (``interrupt_points.DELIVERY``) where Python's own SIGINT handler is in
place: a real Ctrl-C reaches a handler installed meanwhile instead. Each case
then checks from another thread that every lock is free, the SIGINT handler is
Python's again, and the hooks' records are empty; and a real fork after it.
In a fresh interpreter, with a timeout.

A fork made by a signal handler while the thread's own fork waits lets go of
its own hold only (see the second test).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

import pytest

from subprocess_probe import FORK_WAIT_SENDER, probe_outcome

pytestmark = pytest.mark.skipif(
    not hasattr(os, "fork") or sys.platform != "linux", reason="needs os.fork"
)

_SCRIPT = textwrap.dedent(
    """
    import faulthandler, json, os, signal, sys, threading
    faulthandler.dump_traceback_later(240, exit=True)
    from navkit._shared import compile_gc
    from navkit._shared.jit import load_numba
    from numba.core.compiler_lock import global_compiler_lock

    load_numba()
    EVENTS = ("call", "c_return")  # interrupt_points.DELIVERY
    ERRORS = []

    def hooks(profile):
        # As os.fork runs them: an exception in a hook is reported and ignored.
        for hook in (compile_gc._before_fork, compile_gc._after_fork_in_parent):
            try:
                sys.setprofile(profile)
                try:
                    hook()
                finally:
                    sys.setprofile(None)
            except KeyboardInterrupt:
                pass
            except Exception as error:  # reported as ignored: a fault of the hooks
                ERRORS.append(f"{hook.__name__}: {error!r}")

    def run(stop_at):
        # The hooks with a KeyboardInterrupt at the stop_at-th delivery point
        # where Python's SIGINT handler is in place; how many such points passed.
        seen = 0

        def profile(frame, event, arg):
            nonlocal seen
            if event in EVENTS and signal.getsignal(signal.SIGINT) is signal.default_int_handler:
                seen += 1
                if seen == stop_at:
                    sys.setprofile(None)
                    raise KeyboardInterrupt

        hooks(profile)
        return seen

    def free_elsewhere(lock):
        out = []

        def take():
            got = lock.acquire(timeout=0.5)
            if got:
                lock.release()
            out.append(got)

        thread = threading.Thread(target=take)
        thread.start()
        thread.join()
        return out[0]

    LOCKS = {
        "compiler": global_compiler_lock._lock,
        "import": compile_gc.NUMBA_IMPORT,
        "pause": compile_gc._PAUSE_LOCK,
    }

    def left():
        # What the interrupted hooks left behind (and cleans it up for the next case).
        bad = [name for name, lock in LOCKS.items() if not free_elsewhere(lock)]
        if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
            bad.append("handler")
            signal.signal(signal.SIGINT, signal.default_int_handler)
        if compile_gc._held_for_fork():
            bad.append("record")
        bad.extend(ERRORS)
        ERRORS.clear()
        for lock in LOCKS.values():
            while True:
                try:
                    lock.release()
                except RuntimeError:
                    break
        for name in ("held_for_fork", "fork_hold", "forks"):  # this and earlier versions'
            value = getattr(compile_gc._THREAD, name, None)
            if isinstance(value, list):
                value.clear()
        return bad

    points = run(0)
    assert not left()
    leaks = {}
    for k in range(1, points + 1):
        run(k)
        bad = left()
        if bad:
            leaks[k] = bad
    # A real fork afterwards: the child finds the compiler lock free.
    pid = os.fork()
    if pid == 0:
        os._exit(0 if global_compiler_lock._lock.acquire(timeout=5) else 1)
    _, status = os.waitpid(pid, 0)
    print(json.dumps({"points": points, "leaks": leaks, "child": status}))
    """
)


def test_a_ctrl_c_anywhere_in_the_fork_hooks_leaves_every_lock_free() -> None:
    out = probe_outcome(_SCRIPT, timeout=240)
    assert out["points"] >= 1  # the interrupt is injected somewhere
    assert out["leaks"] == {}, out
    assert out["child"] == 0


# A signal handler forks while the main thread's fork waits for another
# thread's compile (the compiler lock held HOLD s), and a Ctrl-C comes during
# the inner fork's wait. The inner fork's after hook let go of every Ctrl-C hold
# of the thread, the outer fork's too: the Ctrl-C, sent again once the inner
# os.fork had returned, reached Python's handler inside the outer fork's before
# hook, and was reported as ignored there and lost.
_NESTED = FORK_WAIT_SENDER + textwrap.dedent(
    """
    import faulthandler, json, os, signal, sys, threading, time
    faulthandler.dump_traceback_later(200, exit=True)
    from navkit._shared import compile_gc
    from navkit._shared.jit import load_numba
    from numba.core.compiler_lock import global_compiler_lock

    HOLD = 2.0
    load_numba()
    holding, all_sent = threading.Event(), threading.Event()
    inner = []

    def compile_elsewhere():
        with global_compiler_lock:
            holding.set()
            time.sleep(HOLD)
            assert all_sent.wait(50)  # (a loaded machine: all sent inside the wait)
            time.sleep(0.05)


    def fork_in_handler(signum, frame):
        pid = os.fork()
        if pid == 0:
            os._exit(0)
        inner.append(os.waitpid(pid, 0)[1])

    signal.signal(signal.SIGUSR1, fork_in_handler)
    thread = threading.Thread(target=compile_elsewhere)
    thread.start()
    assert holding.wait(60)
    threading.Thread(
        target=send_during_the_wait, args=([signal.SIGUSR1, signal.SIGINT], all_sent)
    ).start()
    interrupts, returned = 0, False
    try:
        pid = os.fork()
        if pid == 0:
            os._exit(0 if global_compiler_lock._lock.acquire(timeout=5) else 1)
        returned = True
        time.sleep(HOLD)  # the held Ctrl-C arrives within milliseconds
    except KeyboardInterrupt:
        interrupts += 1
    try:
        time.sleep(HOLD / 2)  # no second one
    except KeyboardInterrupt:
        interrupts += 1
    _, child = os.waitpid(pid, 0)
    thread.join(60)
    handler = signal.getsignal(signal.SIGINT) is signal.default_int_handler
    print(json.dumps([returned, interrupts, inner, child, handler]))
    """
)


def test_a_fork_in_a_signal_handler_during_a_forks_wait_keeps_the_outer_forks_hold() -> None:
    done = subprocess.run(
        [sys.executable, "-c", _NESTED], capture_output=True, text=True, timeout=200, check=False
    )
    assert done.returncode == 0, done.stderr
    returned, interrupts, inner, child, handler = json.loads(done.stdout.splitlines()[-1])
    # The inner fork was made; the outer one too, and its child found the lock
    # free; the Ctrl-C was raised once, after the outer os.fork had returned.
    assert (returned, interrupts, inner, child, handler) == (True, 1, [0], 0, True)
    assert "Exception ignored" not in done.stderr, done.stderr[-2000:]


# A thread compiling (numba's compiler lock held) forks while the main thread's
# own fork waits in its hook for that lock, its Ctrl-C hold in place. The child
# copied the hold's handler, which nothing there ends: every Ctrl-C in the child
# was kept for good (a worker that Ctrl-C could not stop).
_OTHER_THREADS_CHILD = textwrap.dedent(
    """
    import faulthandler, json, os, signal, threading, time
    faulthandler.dump_traceback_later(200, exit=True)
    from navkit._shared.jit import load_numba
    from numba.core.compiler_lock import global_compiler_lock

    load_numba()
    holding = threading.Event()
    out = {}

    def compile_and_fork():
        with global_compiler_lock:
            holding.set()
            time.sleep(0.5)  # the main thread's fork waits in its hook meanwhile
            read, write = os.pipe()
            pid = os.fork()
            if pid == 0:
                default = signal.getsignal(signal.SIGINT) is signal.default_int_handler
                try:
                    signal.raise_signal(signal.SIGINT)
                    time.sleep(0.1)
                    stopped = False
                except KeyboardInterrupt:
                    stopped = True
                os.write(write, json.dumps([default, stopped]).encode())
                os._exit(0)
            os.close(write)
            out["child"] = json.loads(os.read(read, 100).decode() or "null")
            os.waitpid(pid, 0)

    thread = threading.Thread(target=compile_and_fork)
    thread.start()
    assert holding.wait(60)
    pid = os.fork()
    if pid == 0:
        os._exit(0)
    os.waitpid(pid, 0)
    thread.join(60)
    handler = signal.getsignal(signal.SIGINT) is signal.default_int_handler
    print(json.dumps([out.get("child"), handler]))
    """
)


def test_a_child_of_another_thread_forking_meanwhile_stops_on_ctrl_c() -> None:
    # The child has Python's SIGINT handler and a Ctrl-C stops it; the parent's is back.
    assert probe_outcome(_OTHER_THREADS_CHILD, timeout=200) == [[True, True], True]
