"""navkit.sim's process pool on Windows and macOS, simulated on Linux (portability review).

``ProcessPoolExecutor`` refuses more than 61 workers on Windows, where
``sweep(workers=None)`` on a machine of 64 or more cores, or ``workers=100``,
asked for more. macOS and Windows start workers with ``spawn``: the workers'
set-up must work in a fresh interpreter.
"""

from __future__ import annotations

import signal
import sys
import textwrap

import pytest

from navkit.sim._pool import process_pool
from subprocess_probe import probe_outcome


@pytest.mark.parametrize("workers", [61, 62, 64, 1024])
def test_windows_pools_have_at_most_61_workers(
    monkeypatch: pytest.MonkeyPatch, workers: int
) -> None:
    monkeypatch.setattr(sys, "platform", "win32")
    with process_pool(workers) as pool:  # no work: no process starts
        assert pool._max_workers == min(workers, 61)


def test_linux_pools_have_the_workers_asked_for() -> None:
    with process_pool(64) as pool:
        assert pool._max_workers == 64


@pytest.mark.slow
def test_spawned_workers_ignore_ctrl_c_and_watch_their_parent() -> None:
    # (The probe inherits this environment, NUMBA_CACHE_DIR included.)
    script = textwrap.dedent(
        """
        import json, multiprocessing, os, signal
        if __name__ == "__main__":
            multiprocessing.set_start_method("spawn", force=True)
            from navkit.sim._pool import process_pool
            with process_pool(2) as pool:
                handlers = [pool.submit(signal.getsignal, signal.SIGINT).result()
                            for _ in range(4)]
                pids = {pool.submit(os.getppid).result() for _ in range(4)}
            print(json.dumps([[int(h) for h in handlers], sorted(pids), os.getpid()]))
        """
    )
    handlers, parents, me = probe_outcome(script, timeout=120)
    assert handlers == [int(signal.SIG_IGN)] * 4
    assert parents == [me]
