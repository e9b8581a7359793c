"""A fork waits for navkit's import of numba in another thread; a Ctrl-C meanwhile is kept.

Review 35 made a fork wait for numba's compiler lock (a compile or a cache load
under way in another thread). Two cases were left:

* A fork while another thread was inside navkit's first import of numba (the
  first half second of a process's first kernel call): the child inherited
  Python's locks of the modules being imported, held by a thread it does not
  have, and hung at its first kernel call. The fork now waits for the import
  too (``compile_gc.NUMBA_IMPORT``), in an order no thread can deadlock with:
  numba's compiler lock, then the import lock. ``logging`` is imported before
  navkit registers its fork hooks: registered later (numba imports it), its
  hook took logging's lock before navkit's waited for an import that needs it.
* A Ctrl-C while the fork waited: Python ignores an exception raised in a fork
  hook ("Exception ignored in ...") and forks anyway, so the interrupt was
  lost and the fork made without the lock (the child's first kernel call hung).
  It is now held until the fork is done and sent again in the parent once
  ``os.fork`` has returned.

The interleavings are forced (an import held at one of numba's modules, a
thread holding the compiler lock) for a few seconds at most, so the old code
fails, and nothing waits for ever: every process has a timeout, a hang is a
failure that says so. Each case runs in a fresh interpreter.
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
import textwrap

import pytest

from subprocess_probe import FORK_WAIT_SENDER

pytestmark = pytest.mark.skipif(
    not hasattr(os, "fork") or sys.platform != "linux", reason="needs os.fork"
)

#: How long the forced interleaving holds the other thread (s).
HOLD = 2.0
#: How long the parent waits for the child's answer before calling it hung (s).
WAIT = 20.0


def _run(script: str) -> tuple[object, str]:
    """The value the script prints last and its stderr; a hang fails with a message."""
    script = f"HOLD = {HOLD!r}\nWAIT = {WAIT!r}\n" + script
    try:
        done = subprocess.run(
            [sys.executable, "-c", script],
            capture_output=True,
            text=True,
            timeout=240,
            check=False,
        )
    except subprocess.TimeoutExpired as exc:
        pytest.fail(f"the probe process hung (a fork deadlock?): {exc.stderr!r}")
    assert done.returncode == 0, done.stderr
    return ast.literal_eval(done.stdout.strip().splitlines()[-1]), done.stderr


# A thread makes navkit's first kernel call, its import of numba held at one
# module (Python's locks of the modules under way held) for at most HOLD s; the
# main thread forks meanwhile and the child plans.
_IMPORTING = textwrap.dedent(
    """
    import faulthandler, os, select, sys, threading, time
    faulthandler.dump_traceback_later(200, exit=True)
    import numpy as np
    from navkit._shared.jit import load_numba
    assert "numba" not in sys.modules

    importing, forked, letting_go = threading.Event(), threading.Event(), threading.Event()

    class HoldImport:
        # Holds the loading thread at MODULE's import, once.
        def find_spec(self, name, path=None, target=None):
            if name == MODULE and threading.current_thread().name == "loader":
                sys.meta_path.remove(self)
                importing.set()
                forked.wait(HOLD)
                letting_go.set()  # the import goes on: a fork that waits returns after it
            return None

    sys.meta_path.insert(0, HoldImport())
    loader = threading.Thread(target=load_numba, name="loader")
    loader.start()
    assert importing.wait(120)
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read)
        from navkit.planning import astar
        path = astar(np.ones((4, 5)), (0, 0), (3, 4)).points.tolist()
        os.write(write, repr(path).encode())
        os._exit(0)
    waited = letting_go.is_set()  # by the order of events: no clock (a loaded machine)
    forked.set()
    os.close(write)
    ready, _, _ = select.select([read], [], [], WAIT)
    answer = os.read(read, 10000).decode() if ready else ""
    if not answer:
        os.kill(pid, 9)
    os.waitpid(pid, 0)
    loader.join()
    from navkit.planning import astar
    parents = repr(astar(np.ones((4, 5)), (0, 0), (3, 4)).points.tolist())
    out = "the parent's path" if answer == parents else answer or "the child hung"
    print(repr((out, waited)))
    """
)


@pytest.mark.parametrize(
    "module",
    [
        # Early: numba's compiler lock does not exist yet when the fork starts.
        "numba.core.config",
        # Late: numba has imported logging, and its next module calls getLogger.
        "numba.core.typeinfer",
    ],
)
def test_a_child_forked_during_another_threads_numba_import_plans(module: str) -> None:
    (out, waited), stderr = _run(f"MODULE = {module!r}\n" + _IMPORTING)
    # The fork waited for the import (held HOLD s), and the child planned.
    assert out == "the parent's path"
    assert waited
    assert "Exception ignored" not in stderr


# Ctrl-C twice while the fork waits for another thread's compile (the compiler
# lock held HOLD s): the fork still waits, the child finds the lock free, and
# the parent gets one KeyboardInterrupt after os.fork has returned.
_INTERRUPTED = FORK_WAIT_SENDER + textwrap.dedent(
    """
    import faulthandler, os, select, signal, threading, time
    faulthandler.dump_traceback_later(200, exit=True)
    from navkit._shared import compile_gc
    from navkit._shared.jit import load_numba
    from numba.core.compiler_lock import global_compiler_lock

    load_numba()
    holding, all_sent = threading.Event(), threading.Event()
    waited = []

    def compile_elsewhere():
        with global_compiler_lock:
            holding.set()
            time.sleep(HOLD)
            assert all_sent.wait(50)  # (a loaded machine: both sent inside the wait)
            time.sleep(0.05)
            waited.append(in_the_forks_wait())  # as the lock is let go: no clock

    thread = threading.Thread(target=compile_elsewhere)
    thread.start()
    assert holding.wait(60)
    threading.Thread(target=send_during_the_wait, args=([signal.SIGINT] * 2, all_sent)).start()
    read, write = os.pipe()
    interrupts, returned = 0, False
    try:
        pid = os.fork()
        if pid == 0:
            os.close(read)
            free = global_compiler_lock._lock.acquire(timeout=WAIT)
            os.write(write, b"free" if free else b"held")
            os._exit(0)
        returned = True
        time.sleep(HOLD)  # the held Ctrl-C arrives within milliseconds
    except KeyboardInterrupt:
        interrupts += 1
    try:
        time.sleep(HOLD / 2)  # no second one
    except KeyboardInterrupt:
        interrupts += 1
    os.close(write)
    ready, _, _ = select.select([read], [], [], WAIT + 10)
    child = os.read(read, 100).decode() if ready else "no answer"
    thread.join()
    importing = getattr(compile_gc, "NUMBA_IMPORT", threading.Lock())  # (before review 36)
    free = compile_gc._PAUSE_LOCK.acquire(blocking=False) and importing.acquire(blocking=False)
    handler = signal.getsignal(signal.SIGINT) is signal.default_int_handler
    held = compile_gc._held_for_fork()
    print(repr((returned and waited == [True], child, interrupts, free, held, handler)))
    """
)


def test_ctrl_c_while_a_fork_waits_is_raised_after_the_fork_with_the_lock_taken() -> None:
    out, stderr = _run(_INTERRUPTED)
    assert out == (True, "free", 1, True, [], True)
    assert "Exception ignored" not in stderr


# The compiler lock, then the import lock, as the fork takes them: a thread
# compiling a user's kernel that calls a navkit stand-in before numba is loaded
# takes the import lock inside the compiler lock (load_numba). The fork starts
# while that thread holds the compiler lock and waits to take the import lock.
_LOCK_ORDER = textwrap.dedent(
    """
    import faulthandler, os, threading, time
    faulthandler.dump_traceback_later(200, exit=True)
    from navkit._shared import compile_gc
    from navkit._shared.jit import load_numba
    from numba.core.compiler_lock import global_compiler_lock

    load_numba()
    holding, forking = threading.Event(), threading.Event()

    def compile_elsewhere():
        with global_compiler_lock:
            holding.set()
            forking.wait(60)
            time.sleep(HOLD / 4)  # the fork is waiting by now
            with compile_gc.NUMBA_IMPORT:
                pass

    thread = threading.Thread(target=compile_elsewhere)
    thread.start()
    assert holding.wait(60)
    forking.set()
    pid = os.fork()
    if pid == 0:
        os._exit(0)
    _, status = os.waitpid(pid, 0)
    thread.join(60)
    print(repr((status, thread.is_alive())))
    """
)


def test_a_fork_takes_the_locks_in_the_order_a_compiling_thread_does() -> None:
    out, _ = _run(_LOCK_ORDER)
    assert out == (0, False)


# Threads forking at once while another compiles: one fork waits in its hook for
# the locks the other's fork holds. Each after-fork hook let go of the locks and
# the Ctrl-C hold of whichever thread had recorded them last (one list for the
# process): a thread's hook put back the main thread's SIGINT handler
# ("ValueError: signal only works in main thread", ignored in the hook), or
# released a lock another thread had just taken.
_FORKING_THREADS = textwrap.dedent(
    """
    import faulthandler, os, signal, sys, threading, time
    faulthandler.dump_traceback_later(200, exit=True)
    from navkit._shared import compile_gc
    from navkit._shared.jit import load_numba
    from numba.core.compiler_lock import global_compiler_lock

    load_numba()
    sys.setswitchinterval(1e-6)

    def fork():
        pid = os.fork()
        if pid == 0:
            os._exit(0)
        os.waitpid(pid, 0)

    for _ in range(60):
        holding = threading.Event()

        def compile_elsewhere():
            with global_compiler_lock:
                holding.set()
                time.sleep(0.002)

        compiling = threading.Thread(target=compile_elsewhere)
        compiling.start()
        assert holding.wait(60)
        forking = [threading.Thread(target=fork) for _ in range(2)]
        for thread in forking:
            thread.start()
        fork()
        for thread in forking:
            thread.join(60)
        compiling.join(60)
    free = global_compiler_lock._lock.acquire(timeout=WAIT)
    importing = getattr(compile_gc, "NUMBA_IMPORT", threading.Lock())  # (before review 36)
    free = free and importing.acquire(blocking=False)
    handler = signal.getsignal(signal.SIGINT) is signal.default_int_handler
    print(repr((free, handler)))
    """
)


def test_threads_forking_at_once_each_let_go_of_their_own_locks() -> None:
    out, stderr = _run(_FORKING_THREADS)
    assert out == (True, True)
    assert "Exception ignored" not in stderr, stderr[-2000:]
