"""A wait for numba's compiler lock that ends in an exception does not unbalance compile_gc.

numba reports the acquire of its compiler lock (``numba:compiler_lock`` start)
before it waits for the lock. ``compile_gc`` counted those events per thread,
so a wait that ended in an exception (Ctrl-C while another thread compiles, a
ROS 2 node shutting down during a first use elsewhere) counted an acquire that
never happened: the count never returned to 0 in that thread, and the next
navkit compile there ended its pause never. The collector stayed off for the
rest of the process and numba ran with :mod:`navkit._shared.compile_shortcuts`
switched on for good, the user's own compiles included (found in session 22:
``gc.isenabled()`` False and ``compile_shortcuts.active()`` True after the
compile). The listener now asks the lock whether this thread still holds it.

Each check runs in a fresh interpreter with an empty numba cache, so that the
kernel really compiles.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from subprocess_probe import LOCK_WAIT_SENDER

# A kernel whose first call compiles (an empty cache), cheap to compile.
_COMPILE = """
import gc
import numpy as np
from navkit._shared import compile_shortcuts
from navkit.mapping._grid_kernels import world_to_continuous_kernel
seen = []
from numba.core import event
class Watch(event.Listener):
    def on_start(self, ev):
        seen.append((gc.isenabled(), compile_shortcuts.active()))
    def on_end(self, ev):
        pass
event.register("numba:compile", Watch())
world_to_continuous_kernel(np.zeros((1, 2)), 0.0, 0.0, 0.0, 1.0, np.zeros((1, 2)))
print(seen[:1], gc.isenabled(), compile_shortcuts.active(), compile_shortcuts._COUNT)
"""


def _run(code: str, cache: Path) -> str:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    out = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code) + _COMPILE],
        check=True, capture_output=True, text=True, timeout=600, env=env,
    )  # fmt: skip
    return out.stdout.strip()


def test_a_lock_wait_that_raises_leaves_the_next_compile_balanced(tmp_path: Path) -> None:
    # The wait itself raises (as an interrupted RLock.acquire does), after numba
    # reported the acquire.
    out = _run(
        """
        from navkit._shared.jit import load_numba
        load_numba()
        from numba.core.compiler_lock import global_compiler_lock

        class Interrupted:
            def __init__(self, lock):
                self.lock = lock
                self.armed = True
            def acquire(self, *args):
                if self.armed:
                    self.armed = False
                    raise KeyboardInterrupt
                return self.lock.acquire(*args)
            def __getattr__(self, name):
                return getattr(self.lock, name)

        real = global_compiler_lock._lock
        global_compiler_lock._lock = Interrupted(real)
        try:
            with global_compiler_lock:
                raise AssertionError("not reached")
        except KeyboardInterrupt:
            pass
        global_compiler_lock._lock = real
        """,
        tmp_path,
    )
    # During the compile: collector off, shortcuts on; after it: both back.
    assert out == "[(False, True)] True False 0"


@pytest.mark.skipif(not hasattr(__import__("signal"), "pthread_kill"), reason="POSIX signals")
def test_ctrl_c_while_another_thread_compiles_leaves_the_next_compile_balanced(
    tmp_path: Path,
) -> None:
    # A real SIGINT interrupting the main thread's wait for the lock another thread holds
    # (sent once the main thread is seen waiting: a loaded machine can outlast any sleep).
    out = _run(
        LOCK_WAIT_SENDER
        + textwrap.dedent(
            """
        import signal, sys, threading, time, traceback
        from navkit._shared.jit import load_numba
        load_numba()
        from numba.core.compiler_lock import global_compiler_lock

        held, done = threading.Event(), threading.Event()
        def hold():
            with global_compiler_lock:
                held.set()
                done.wait()
        holder = threading.Thread(target=hold)
        holder.start()
        held.wait()
        threading.Thread(target=send_in_the_lock_wait, args=(signal.SIGINT,)).start()
        try:
            with global_compiler_lock:
                raise AssertionError("not reached")
        except KeyboardInterrupt:
            # (The last frame outside navkit's handler: since review 39 a Ctrl-C while
            # the main thread takes numba's compiler lock comes through it.)
            frames = traceback.extract_tb(sys.exc_info()[2])
            where = [f.name for f in frames if not f.filename.endswith("interrupts.py")][-1]
            assert where == "acquire", where  # interrupted while waiting
        done.set()
        holder.join()
        """
        ),
        tmp_path,
    )
    assert out == "[(False, True)] True False 0"
