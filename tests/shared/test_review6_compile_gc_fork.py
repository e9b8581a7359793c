"""A process forked while a thread pauses the collector gets the collector back.

The pauses are counted for the whole process; a child of ``os.fork`` has only
the forking thread, so the other threads' pauses never end there.
"""

from __future__ import annotations

import gc
import multiprocessing
import os
import sys
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager

import pytest

from navkit._shared import compile_gc

pytestmark = pytest.mark.skipif(
    not hasattr(os, "fork") or sys.platform != "linux", reason="needs os.fork"
)


@contextmanager
def _collector(enabled: bool) -> Iterator[None]:
    was = gc.isenabled()
    (gc.enable if enabled else gc.disable)()
    try:
        yield
    finally:
        (gc.enable if was else gc.disable)()


@contextmanager
def _paused_in_another_thread() -> Iterator[None]:
    """A pause under way in another thread (as during its first compile)."""
    inside, leave = threading.Event(), threading.Event()

    def other() -> None:
        with compile_gc.paused():
            inside.set()
            leave.wait(30)

    worker = threading.Thread(target=other)
    worker.start()
    assert inside.wait(30)
    try:
        yield
    finally:
        leave.set()
        worker.join(30)


def _in_child(report: Callable[[], str]) -> str:
    """``report()`` as computed in a forked child."""
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: report, then leave at once (no pytest teardown here)
        try:
            os.write(write, report().encode())
        finally:
            os._exit(0)
    os.close(write)
    with os.fdopen(read) as pipe:
        out = pipe.read()
    os.waitpid(pid, 0)
    return out


def _state_after_a_pause() -> str:
    before = gc.isenabled()
    with compile_gc.paused():
        during = gc.isenabled()
    return f"{before} {during} {gc.isenabled()}"


@pytest.mark.parametrize("enabled", [True, False])
def test_a_child_forked_during_another_threads_pause_has_the_collector_as_before(
    enabled: bool,
) -> None:
    with _collector(enabled), _paused_in_another_thread():
        assert not gc.isenabled()
        out = _in_child(_state_after_a_pause)
        parent_during = gc.isenabled()
    # The child starts with the state from before the pause and pauses normally
    # again; the parent's pause goes on until its thread ends it.
    assert out == f"{enabled} False {enabled}"
    assert parent_during is False


def test_a_child_forked_inside_the_forking_threads_own_pause_ends_it_normally() -> None:
    def report() -> str:
        inside = gc.isenabled()
        pause.__exit__(None, None, None)  # the pause the child inherited
        return f"{inside} {gc.isenabled()}"

    with _collector(True), _paused_in_another_thread():
        pause = compile_gc.paused()
        pause.__enter__()
        try:
            out = _in_child(report)
        finally:
            pause.__exit__(None, None, None)
        assert not gc.isenabled()  # the other thread's pause still runs here
    assert gc.isenabled()
    assert out == "False True"


def test_a_fork_outside_any_pause_leaves_the_users_choice_alone() -> None:
    with _collector(True):
        with compile_gc.paused():
            pass
        gc.disable()  # the user's, after a pause that recorded "enabled"
        assert _in_child(lambda: str(gc.isenabled())) == "False"


def _child_reports(queue: multiprocessing.Queue[bool]) -> None:
    queue.put(gc.isenabled())


def test_a_multiprocessing_fork_worker_has_the_collector_running() -> None:
    context = multiprocessing.get_context("fork")
    queue: multiprocessing.Queue[bool] = context.Queue()
    with _collector(True), _paused_in_another_thread():
        worker = context.Process(target=_child_reports, args=(queue,))
        worker.start()
        enabled = queue.get(timeout=60)
        worker.join(60)
    assert enabled is True
    assert worker.exitcode == 0
