"""First uses of navkit from several threads at once (a ROS 2 node's executor).

The checks that compile run in a fresh interpreter with an empty numba cache,
so that numba is loaded and the kernels really compile.
"""

from __future__ import annotations

import gc
import os
import subprocess
import sys
import textwrap
import threading
from pathlib import Path

import pytest

from navkit._shared import compile_gc


def _run(code: str, cache: Path) -> str:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    out = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        check=True, capture_output=True, text=True, timeout=300, env=env,
    )  # fmt: skip
    return out.stdout.strip()


@pytest.mark.parametrize("enabled", [True, False])
def test_overlapping_pauses_in_two_threads_restore_the_state_once_both_end(
    enabled: bool,
) -> None:
    inside = threading.Event()
    leave = threading.Event()
    seen: list[bool] = []

    def other() -> None:
        with compile_gc.paused():
            inside.set()
            leave.wait(10)
            seen.append(gc.isenabled())

    was = gc.isenabled()
    if not enabled:
        gc.disable()
    try:
        worker = threading.Thread(target=other)
        with compile_gc.paused():
            worker.start()
            inside.wait(10)
        # This thread's pause is over but the other's is not: still paused.
        seen.append(gc.isenabled())
        leave.set()
        worker.join(10)
        seen.append(gc.isenabled())
    finally:
        if was:
            gc.enable()
    assert seen == [False, False, enabled]


def test_a_compile_that_takes_the_lock_from_an_ending_one_stays_paused(tmp_path: Path) -> None:
    """Thread X releases numba's compiler lock, thread Y takes it and starts compiling,
    and only then does X's pause end (listeners around navkit's hold X there).

    Each thread recorded whether the collector ran when its pause began: Y
    recorded "off" (X's pause), X switched it back on, so Y compiled with the
    collector running.
    """
    out = _run(
        """
        import gc, threading
        import numpy as np
        from numba.core import event
        state = threading.local()
        compiling, second_started, first_resumed = [], threading.Event(), threading.Event()
        class Before(event.Listener):  # registered before navkit's listeners
            def on_start(self, ev):
                state.depth = getattr(state, "depth", 0) + 1
            def on_end(self, ev):
                state.depth = max(getattr(state, "depth", 0) - 1, 0)
                if state.depth == 0 and getattr(state, "compiled", False):
                    state.compiled, state.ended = False, True
                    second_started.wait(10)  # the lock is free, navkit's pause not yet over
        class After(event.Listener):  # registered after navkit's listeners
            def on_start(self, ev):
                pass
            def on_end(self, ev):
                if getattr(state, "ended", False):
                    state.ended = False
                    first_resumed.set()
        event.register("numba:compiler_lock", Before())
        from navkit._shared.jit import load_numba
        load_numba()
        event.register("numba:compiler_lock", After())
        on_at_end = []
        class Record(event.Listener):
            def on_start(self, ev):
                state.compiled = True
                if threading.current_thread() not in compiling:
                    compiling.append(threading.current_thread())
                if len(compiling) == 2:
                    second_started.set()
            def on_end(self, ev):
                if compiling.index(threading.current_thread()) == 1:
                    first_resumed.wait(10)
                on_at_end.append(gc.isenabled())
        event.register("numba:compile", Record())
        from navkit.mapping._grid_kernels import world_to_cell_kernel, world_to_continuous_kernel
        points = np.array([[0.7, 0.2]])
        cells, spots = np.empty((1, 2), dtype=np.int64), np.empty((1, 2))
        threads = [
            threading.Thread(target=world_to_cell_kernel, args=(points, 0.0, 0.0, 0.0, 0.5, cells)),
            threading.Thread(
                target=world_to_continuous_kernel, args=(points, 0.0, 0.0, 0.0, 0.5, spots)
            ),
        ]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        # Row from y, column from x, in cells of 0.5 m (centres at integers).
        expected = [[0.2 / 0.5 - 0.5, 0.7 / 0.5 - 0.5]]
        right = (cells.tolist() == [[0, 1]], np.allclose(spots, expected))
        print(len(compiling), first_resumed.is_set(), any(on_at_end), gc.isenabled(), right)
        """,
        tmp_path,
    )
    # Every navkit compile ended with the collector still paused; it runs again after.
    assert out == "2 True False True (True, True)"


def test_loading_numba_while_a_users_kernel_types_a_navkit_one_does_not_deadlock(
    tmp_path: Path,
) -> None:
    """Thread A loads numba; thread B compiles a user's kernel calling a navkit one.

    A held navkit's lock and waited for numba's compiler lock (initialising the
    compiler); B held the compiler lock and, typing the stand-in, waited for
    navkit's lock. A listener delays A just before it takes the compiler lock.
    """
    out = _run(
        """
        import os, threading, time
        from numba import njit
        from numba.core import event
        delayed = []
        class Delay(event.Listener):
            def on_start(self, ev):
                if threading.current_thread().name == "A" and not delayed:
                    delayed.append(True)
                    time.sleep(0.5)
            def on_end(self, ev):
                pass
        event.register("numba:compiler_lock", Delay())
        from navkit._shared import jit, se2

        @njit
        def users(x):
            return se2.sinc(x) + 1.0

        results = []
        a = threading.Thread(target=jit.load_numba, name="A", daemon=True)
        b = threading.Thread(target=lambda: results.append(users(0.0)), name="B", daemon=True)
        a.start()
        time.sleep(0.1)
        b.start()
        a.join(30)
        b.join(30)
        print(a.is_alive() or b.is_alive(), results, jit.numba_loaded(), flush=True)
        os._exit(0)  # a deadlocked thread would hang the interpreter's exit
        """,
        tmp_path,
    )
    assert out == "False [2.0] True"


@pytest.mark.slow
def test_two_processes_filling_one_empty_cache_leave_one_a_third_loads(tmp_path: Path) -> None:
    """As ``navkit warmup --workers 2`` or a sweep's process pool on first use."""
    code = """
        import numpy as np
        from navkit._shared.jit import load_numba
        load_numba()
        from numba.core import event
        compiled = []
        class Record(event.Listener):
            def on_start(self, ev):
                compiled.append(ev.data["dispatcher"].py_func.__module__)
            def on_end(self, ev):
                pass
        event.register("numba:compile", Record())
        from navkit.planning import astar
        from navkit.geometry._integrate_kernels import integrate_kernel
        cells = astar(np.ones((6, 6)), (0, 0), (5, 5)).cells
        pose = integrate_kernel(0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 2.0)
        navkit_compiles = sum(module.startswith("navkit") for module in compiled)
        print(len(cells), pose, navkit_compiles > 0)
        """
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    command = [sys.executable, "-c", textwrap.dedent(code)]
    both = [
        subprocess.Popen(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True)
        for _ in range(2)
    ]
    outs = [process.communicate(timeout=600) for process in both]
    assert [process.returncode for process in both] == [0, 0], [err for _, err in outs]
    # Six cells on the diagonal of a 6 x 6 grid; 2 m straight ahead at 1 m/s.
    assert [out.strip() for out, _ in outs] == ["6 (2.0, 0.0, 0.0) True"] * 2
    third = _run(code, tmp_path)
    assert third == "6 (2.0, 0.0, 0.0) False"  # every kernel loaded from the cache
