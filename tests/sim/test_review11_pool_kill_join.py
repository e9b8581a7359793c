"""process_pool's interrupt waits for the pool's thread to fail the futures left.

``_kill`` shut the pool down without waiting, then called
``shutdown(wait=True)`` to wait for the pool's thread: but the first shutdown
forgets that thread, so the second returned at once. Leaving the block on
Ctrl-C then left the futures pending and the killed workers unreaped.
"""

from __future__ import annotations

import concurrent.futures
import multiprocessing
import threading
import time

import pytest

from navkit.sim._pool import process_pool


def test_interrupt_leaves_every_future_done_and_the_pool_thread_ended() -> None:
    with pytest.raises(KeyboardInterrupt), process_pool(2) as pool:
        running = [pool.submit(time.sleep, 120) for _ in range(3)]
        while not all(f.running() for f in running[:2]):
            time.sleep(0.01)
        workers = list(pool._processes.values())
        manager: threading.Thread | None = getattr(pool, "_executor_manager_thread", None)
        raise KeyboardInterrupt
    # Checked at once, with no waiting: process_pool has already waited.
    assert manager is not None and not manager.is_alive()
    assert all(f.done() for f in running)
    for future in running[:2]:  # killed while running
        with pytest.raises(concurrent.futures.process.BrokenProcessPool):
            future.result(timeout=0)
    # A forkserver worker's status comes through a pipe from the server (Python 3.14's
    # default on Linux): the pool's thread and _kill both wait for it, and the one that
    # reads second finds the pipe closed and can record 255 (multiprocessing.popen_forkserver).
    killed = {-9, 255} if multiprocessing.get_start_method() == "forkserver" else {-9}
    assert [w.exitcode in killed for w in workers] == [True, True]  # reaped, by SIGKILL
