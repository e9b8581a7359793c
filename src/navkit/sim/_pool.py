"""The local process pool of :func:`~navkit.sim.sweep` and :func:`~navkit.sim.warmup`.

Left to itself, a ``concurrent.futures.ProcessPoolExecutor`` serves an
interrupted program badly: leaving its ``with`` block waits for every queued
task (a cold :func:`~navkit.sim.warmup` ignored Ctrl-C for a minute), and a
worker whose parent died hard (``SIGKILL``, the OOM killer) waits forever for
work on its queue. :func:`process_pool` owns the pool instead: an interrupt
stops it at once, and its workers end with their parent.
"""

from __future__ import annotations

import concurrent.futures
import contextlib
import ctypes
import multiprocessing
import multiprocessing.connection
import os
import signal
import sys
import threading
import warnings
from collections.abc import Iterator

from navkit._shared import jit
from navkit.errors import KernelCacheWarning

__all__ = ["process_pool"]

#: ``PR_SET_PDEATHSIG`` from ``<linux/prctl.h>``.
_PR_SET_PDEATHSIG = 1

#: Most workers a ``ProcessPoolExecutor`` takes on Windows (it waits on every
#: worker's handle at once, ``WaitForMultipleObjects``' 64 less its own three).
_MAX_WINDOWS_WORKERS = 61


@contextlib.contextmanager
def process_pool(workers: int) -> Iterator[concurrent.futures.ProcessPoolExecutor]:
    """A process pool of ``workers`` processes, shut down when the block ends.

    On leaving the block normally, waits for the work submitted. On an
    exception (a failed task), cancels the work not yet started and waits for
    the tasks running. On an interrupt (``KeyboardInterrupt``, ``SystemExit``
    or any other exception that is not an ``Exception``, also while waiting),
    cancels the work not started and kills the workers at once: their results
    would be thrown away, and a task may run for minutes.

    The workers ignore ``SIGINT`` (a Ctrl-C reaches the whole process group:
    the owner alone handles it, by stopping the pool) and end when their parent
    process ends, however it ends. Submit from the thread that entered the
    block (as ``sweep`` and ``warmup`` do): on Linux a worker is also killed
    when the thread that started it ends (``PR_SET_PDEATHSIG`` follows the
    thread), and workers start at a ``submit``. On Windows at most 61 workers
    start (more would make ``ProcessPoolExecutor`` refuse the pool). When this
    process has already warned that numba cannot cache the kernels
    (:class:`~navkit.errors.KernelCacheWarning`), the workers do not say it
    again (a spawned or forkserver worker would, once each: it does not inherit
    this process's "said").
    """
    if sys.platform == "win32":
        workers = min(workers, _MAX_WINDOWS_WORKERS)
    # Not cache_problem(): that would load numba here (over a second of CPU).
    warned = jit.cache_warned()
    pool = concurrent.futures.ProcessPoolExecutor(
        max_workers=workers, initializer=_start_worker, initargs=(warned,)
    )
    try:
        try:
            yield pool
        except Exception:
            pool.shutdown(wait=True, cancel_futures=True)
            raise
        pool.shutdown(wait=True)
    except BaseException as exc:
        if not isinstance(exc, Exception):
            _kill(pool)
        raise


def _kill(pool: concurrent.futures.ProcessPoolExecutor) -> None:
    """Cancel the pool's queued work and kill its workers (as ``kill_workers`` in Python 3.14)."""
    processes = list(pool._processes.values()) if pool._processes else []
    # Taken first: shutdown(wait=False) forgets the pool's thread, so that a second
    # shutdown(wait=True) would return at once, without waiting for it.
    manager: threading.Thread | None = getattr(pool, "_executor_manager_thread", None)
    results = getattr(pool, "_result_queue", None)  # shutdown forgets it too
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        with contextlib.suppress(ProcessLookupError, ValueError):  # gone, or closed
            process.kill()
    for process in processes:
        process.join()
    # A worker killed while sending a result leaves half a message in the result
    # pipe, and the pool's thread would wait for the rest forever (also at exit,
    # which joins it): with every writer gone, closing ours ends its read.
    writer = getattr(results, "_writer", None)
    if writer is not None:
        with contextlib.suppress(OSError):
            writer.close()
    # The pool's thread sees the workers die, fails the futures left and joins them.
    if manager is not None:
        manager.join()


def _start_worker(warned: bool = False) -> None:
    """Initializer of every worker; ``warned``: the parent said numba cannot cache the kernels."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if warned:
        warnings.filterwarnings("ignore", category=KernelCacheWarning)
    parent = multiprocessing.parent_process()
    if parent is None:  # pragma: no cover - not started by multiprocessing
        return
    # Only where the pool's process is this one's parent: a forkserver worker's
    # parent is the fork server (Python 3.14's default on Linux), which outlives a
    # killed pool's process as long as its workers hold its "alive" pipe.
    if parent.pid == os.getppid() and _kill_on_parent_death():
        if not parent.is_alive():  # died before the request took effect
            os._exit(1)
        return
    # Elsewhere a thread waits for the parent's end (its sentinel becomes ready).
    watch = threading.Thread(
        target=_exit_after, args=(parent.sentinel,), name="navkit-parent-watch", daemon=True
    )
    watch.start()


def _kill_on_parent_death() -> bool:
    """Ask Linux to ``SIGKILL`` this process when its parent ends; False where unsupported."""
    done = False
    # A platform test the type checker reads (as "linux", not startswith: Python 3.3+
    # says "linux" on every Linux), around the call, not an early return before it.
    if sys.platform == "linux":
        try:
            prctl = ctypes.CDLL(None, use_errno=True).prctl
            # prctl is variadic and reads its arguments as unsigned long: pass them so.
            args = (ctypes.c_ulong(int(signal.SIGKILL)), ctypes.c_ulong(0), ctypes.c_ulong(0))
            done = int(prctl(_PR_SET_PDEATHSIG, *args, ctypes.c_ulong(0))) == 0
        except (OSError, AttributeError):  # no libc, or no prctl in it
            pass
    return done


def _exit_after(sentinel: int) -> None:
    """Wait, without holding the GIL, for ``sentinel`` to become ready; then end this process."""
    multiprocessing.connection.wait([sentinel])
    # Not sys.exit: the main thread is blocked on the pool's queue, or in a task.
    os._exit(1)
