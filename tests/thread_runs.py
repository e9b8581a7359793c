"""Threads running navkit calls at once, and whether a call lets other threads run.

Since navkit's long kernels release the GIL (``navkit._shared.jit.RELEASES_GIL``),
two threads calling them really run them at the same time, on two cores:

* :func:`concurrent_results` starts one thread per call, lines them up at a
  barrier and lets them go together, a few rounds, and returns every round's
  results, to compare bit for bit with the same calls made one after another;
* :func:`run_switching_often` runs ``target(k)`` in one thread per ``k``
  with a switch interval of 1 µs, so that the threads' calls interleave
  (tests of the one-call guard);
* :func:`lines_beside_python` tells where another thread ran Python while
  ``call`` ran, without timing anything: with a switch interval of 100 s a
  thread holding the GIL is never asked to give it up, so the main thread
  can only run where ``call`` releases the GIL.
"""

from __future__ import annotations

import linecache
import math
import sys
import threading
import time
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from navkit.mapping import LaserScan


def concurrent_results(
    calls: Sequence[Callable[[], Any]], *, rounds: int = 3
) -> list[list[Any]]:
    """Each call in a thread of its own, all released together; ``rounds`` times.

    Returns one list per round, the calls' results in the order of ``calls``.
    An exception in any thread is raised here (the first one).
    """
    out: list[list[Any]] = []
    for _ in range(rounds):
        out.append(_one_round(calls))
    return out


def _one_round(calls: Sequence[Callable[[], Any]]) -> list[Any]:
    """One round of :func:`concurrent_results`."""
    barrier = threading.Barrier(len(calls))
    results: list[Any] = [None] * len(calls)
    errors: list[BaseException] = []

    def run(i: int) -> None:
        try:
            barrier.wait()
            results[i] = calls[i]()
        except BaseException as exc:  # reported by the main thread
            errors.append(exc)

    threads = [threading.Thread(target=run, args=(i,)) for i in range(len(calls))]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    if errors:
        raise errors[0]
    return results


def run_switching_often(target: Callable[[int], object], *, threads: int = 2) -> None:
    """``target(k)`` for ``k`` in ``range(threads)``, each in a thread, switching every 1 µs.

    The interpreter's switch interval is lowered for the run (and put back), so
    the threads' Python code interleaves finely; waits up to 300 s for each.
    """
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)
    try:
        workers = [threading.Thread(target=target, args=(k,)) for k in range(threads)]
        for worker in workers:
            worker.start()
        for worker in workers:
            worker.join(300)
    finally:
        sys.setswitchinterval(interval)


def free_elsewhere(lock: Any) -> bool:
    """Whether another thread can take ``lock`` now (a lock or an ``RLock``).

    ``RLock`` has no ``locked()`` before Python 3.14, and the thread holding
    one takes it again: asked from a thread of its own, which lets it go.
    """
    took: list[bool] = []

    def attempt() -> None:
        got = lock.acquire(blocking=False)
        if got:
            lock.release()
        took.append(got)

    th = threading.Thread(target=attempt)
    th.start()
    th.join()
    return took[0]


def lines_beside_python(call: Callable[[], object], *, tries: int = 3) -> set[str]:
    """The source lines at which ``call``, run in another thread, let the main thread run.

    A worker thread calls ``call`` once (its first call: per-thread scratch is
    allocated then), then ``tries`` times, each time setting an event just
    before the call while the main thread waits for it. With a switch interval
    of 100 s no thread is ever asked to give the GIL up, so the main thread
    runs only where the worker releases it: in a kernel compiled with
    ``nogil=True``, in numpy's loops over large arrays (copies, ufuncs), in a
    blocking wait. Each time it runs, the main thread notes the line the
    worker's innermost Python frame is at (a kernel call's line, as a numba
    kernel has no frame of its own), ``"function: source line"``, and
    releases the GIL again at once, until the call returns.

    A line that holds the GIL throughout is never noted, whatever the timing.
    A line that releases it for milliseconds is noted unless the worker takes
    the GIL back before the woken main thread does, every time. ``call`` must
    be compiled already (a compile waits on locks).
    """
    go, started, finished = threading.Event(), threading.Event(), threading.Event()
    done: list[bool] = []
    errors: list[BaseException] = []
    stop: list[bool] = []

    def work() -> None:
        try:
            call()
        except BaseException as exc:  # reported by the main thread
            errors.append(exc)
        finished.set()
        while True:
            go.wait()
            go.clear()
            if stop:
                return
            started.set()
            try:
                call()
            except BaseException as exc:
                errors.append(exc)
            done.append(True)
            finished.set()

    lines: set[str] = set()
    old = sys.getswitchinterval()
    worker = threading.Thread(target=work)
    worker.start()
    try:
        finished.wait()
        sys.setswitchinterval(100.0)
        for _ in range(tries):
            done.clear()
            started.clear()
            finished.clear()
            go.set()
            started.wait()  # woken as the worker starts the call
            while not done:
                frame = sys._current_frames().get(worker.ident or -1)
                if frame is not None and not done:
                    code = frame.f_code
                    text = linecache.getline(code.co_filename, frame.f_lineno).strip()
                    lines.add(f"{code.co_name}: {text}")
                del frame
                time.sleep(0)  # the GIL back to the worker, if it waits for it
            finished.wait()
            if errors:
                raise errors[0]
        return lines
    finally:
        sys.setswitchinterval(old)
        stop.append(True)
        go.set()
        worker.join()


def room_scan(seed: int, *, beams: int, lowest: float) -> LaserScan:
    """A scan in a 6 m x 4 m room from near its centre, clutter shortening each range.

    Each beam's range is the wall's times a uniform draw in ``[lowest, 1)``
    (seeded by ``seed``): scans of different seeds write different cells, so
    an update lost between threads shows.
    """
    rng = np.random.default_rng(seed)
    a = -math.pi + 2 * math.pi / beams * np.arange(beams)
    c, s = np.cos(a), np.sin(a)
    with np.errstate(divide="ignore"):
        tx = np.where(c > 0, 2.93 / c, np.where(c < 0, -2.97 / c, np.inf))
        ty = np.where(s > 0, 1.91 / s, np.where(s < 0, -1.95 / s, np.inf))
    ranges = np.minimum(tx, ty) * rng.uniform(lowest, 1.0, beams)
    return LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / beams,
                     range_min=0.1, range_max=8.0)  # fmt: skip
