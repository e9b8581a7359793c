"""navkit's compile counts in a forked child (review 39, REV39).

Review 38 made each navkit dispatcher count its compiles under way in a C
re-entrant lock (``navkit._shared.jit._CompileDepth``), which a Ctrl-C cannot
leave up. numba changes the count only under its compiler lock, which a fork
waits for, except a fork from a signal handler run inside navkit's locking
code: that one goes without it (``compile_gc._take_for_fork``, review 38). A
thread compiling a kernel then held the kernel's count lock, and the child's
first call of that kernel waited for it for ever (numba's own counter, an
int, let the child compile). The counts of the threads the fork left behind
are freed in the child now; the forking thread's own are kept.

Every case runs in a fresh interpreter with a timeout; the parent kills a
child that hangs and reports it.
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

# A thread counts a compile of ``kernel`` (as numba's Dispatcher.compile does,
# under the compiler lock) and, as a helper's compile starts, waits for the
# collector's pause lock, which the main thread holds; a SIGUSR1 handler forks
# there (the fork goes without the compiler lock). The child calls the kernel
# and a kernel of its own calling it, both compiled there.
_LOST_THREAD = textwrap.dedent(
    """
    import faulthandler, json, os, signal, sys, threading, time
    faulthandler.dump_traceback_later(60, exit=True)
    import numba
    from navkit._shared import compile_gc, jit
    from numba.core.compiler_lock import global_compiler_lock

    jit.load_numba()

    def add_one(x):
        return x + 1

    add_one.__qualname__ = "add_one"
    kernel = jit.typed_njit(cache=False)(add_one)
    main_in, forked = threading.Event(), []

    def on_usr1(signum, frame):
        pid = os.fork()
        if pid == 0:
            ok = kernel(1) == 2
            ok = ok and numba.njit(lambda x: kernel(x) * 10)(1) == 20
            os._exit(0 if ok else 3)
        end = time.monotonic() + 20
        while time.monotonic() < end:
            got, status = os.waitpid(pid, os.WNOHANG)
            if got:
                forked.append(status)
                return
            time.sleep(0.01)
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        forked.append("hung")

    signal.signal(signal.SIGUSR1, on_usr1)

    def compile_elsewhere():
        with global_compiler_lock, kernel._compiling_counter:
            main_in.wait(10)
            with compile_gc.paused():
                pass

    source = {}

    def tracer(frame, event, arg):
        def local(frame, event, arg):
            name = frame.f_code.co_filename
            lines = source.setdefault(name, open(name).read().splitlines())
            if event == "line" and "_PAUSES == 0" in lines[frame.f_lineno - 1]:
                sys.settrace(None)
                main_in.set()
                time.sleep(0.3)  # the other thread now waits for the pause lock
                signal.raise_signal(signal.SIGUSR1)
            return local
        return local if frame.f_code.co_name == "_begin_pause" else None

    thread = threading.Thread(target=compile_elsewhere, daemon=True)
    thread.start()
    time.sleep(0.1)
    sys.settrace(tracer)
    with compile_gc.paused():
        pass
    sys.settrace(None)
    thread.join(10)
    print(json.dumps({"forked": forked, "other_thread_done": not thread.is_alive()}))
    """
)


def test_a_child_forked_while_another_thread_compiled_a_kernel_compiles_it() -> None:
    out = probe_outcome(_LOST_THREAD, timeout=120)
    # Before review 39 the child waited for ever in its first call of the kernel.
    assert out == {"forked": [0], "other_thread_done": True}


# The forking thread's own count, taken before the fork, is the child's still:
# its compile goes on there and lets the count go as it ends.
_OWN_COUNT = textwrap.dedent(
    """
    import json, os
    from navkit._shared import jit

    jit.load_numba()

    def add_two(x):
        return x + 2

    add_two.__qualname__ = "add_two"
    kernel = jit.typed_njit(cache=False)(add_two)
    counter = kernel._compiling_counter
    with counter:
        pid = os.fork()
        if pid == 0:
            inside = bool(counter) and counter.counter == 1
    if pid == 0:
        os._exit(0 if inside and not counter and kernel(1) == 3 else 3)
    print(json.dumps(os.waitpid(pid, 0)[1]))
    """
)


def test_the_forking_threads_own_compile_count_is_kept_in_the_child() -> None:
    assert probe_outcome(_OWN_COUNT, timeout=120) == 0
