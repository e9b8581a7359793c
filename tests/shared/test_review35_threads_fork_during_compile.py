"""A process forked while another thread holds numba's compiler lock can use navkit.

numba takes its compiler lock (a re-entrant lock of the process) for every
compile and every load of a kernel from its cache, and navkit for loading
numba. A child forked while another thread held it (``navkit.sim.sweep``'s
process pool with Python's ``fork`` start method, the default on Linux before
Python 3.14, started while a ROS 2 callback makes a first call) inherited the
lock held by a thread that does not exist in the child: its first kernel call
waited for ever (a two-worker sweep of the demo never ended). A fork now waits
for the compile under way to end, and the child starts with the lock free.

The interleaving is forced: a thread holds the lock until the fork is done, or
for a few seconds where the fork waits for it (after the fix). Each case runs
in a fresh interpreter, so that no test's threads or locks leak into another.
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
import textwrap

import pytest

pytestmark = pytest.mark.skipif(
    not hasattr(os, "fork") or sys.platform != "linux", reason="needs os.fork"
)

_SCRIPT = textwrap.dedent(
    """
    import multiprocessing, sys, threading, time
    import numpy as np
    from navkit._shared.jit import load_numba
    from numba.core.compiler_lock import global_compiler_lock

    load_numba()
    holding, forked, letting_go = threading.Event(), threading.Event(), threading.Event()

    def compile_elsewhere():
        # A compile in another thread, as long as the fork takes (at most HOLD s).
        with global_compiler_lock:
            holding.set()
            forked.wait(HOLD)
            letting_go.set()  # still held: a fork that waited for it returns after this

    def child(queue):
        # The lock as numba takes it for a kernel's first call, then such a call.
        got = global_compiler_lock._lock.acquire(timeout=WAIT)
        if not got:
            queue.put("the compiler lock is held by a thread of the parent")
            return
        global_compiler_lock._lock.release()
        from navkit.planning import astar  # its kernels: loaded in the child
        costs = np.ones((4, 5))
        queue.put(astar(costs, (0, 0), (3, 4)).points.tolist())

    context = multiprocessing.get_context("fork")
    queue = context.Queue()
    thread = threading.Thread(target=compile_elsewhere)
    thread.start()
    assert holding.wait(60)
    worker = context.Process(target=child, args=(queue,))
    worker.start()  # forks (waits for the other thread's compile to end)
    # Whether the fork waited, by the order of events, not a clock: the main
    # thread's own pause on a loaded machine (before or after it forks) is not
    # the fork's wait.
    waited = letting_go.is_set()
    forked.set()
    thread.join()
    out = queue.get(timeout=120)
    worker.join(60)
    from navkit.planning import astar
    same = out == astar(np.ones((4, 5)), (0, 0), (3, 4)).points.tolist()
    print(repr((out if not same else "the parent's path", worker.exitcode, waited)))
    """
)


def _run(hold: float, wait: float) -> tuple[object, int, bool]:
    script = f"HOLD = {hold!r}\nWAIT = {wait!r}\n" + _SCRIPT
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=300, check=False
    )
    assert done.returncode == 0, done.stderr
    out: tuple[object, int, bool] = ast.literal_eval(done.stdout.strip().splitlines()[-1])
    return out


def test_a_child_forked_while_another_thread_compiles_plans() -> None:
    out, exitcode, waited = _run(hold=2.0, wait=10.0)
    # The parent's fork waited for the compile (the lock held for HOLD s), and the
    # child found the lock free and planned the path the parent plans.
    assert out == "the parent's path"
    assert exitcode == 0
    assert waited


# A Ctrl-C while a fork waits: tests/shared/test_review36_concur_fork_waits.py (it is
# held until the fork is done, then raised in the parent; it was lost here before).
