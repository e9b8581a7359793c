"""Signals during a run with worker processes: one line, no traceback, no orphans."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(not hasattr(os, "killpg"), reason="POSIX signals")

# `navkit run demo --workers 2`, signalled from its progress callback (in the
# command's process) once the second-to-last trial is done: one worker then
# waits for work that will not come, the other runs the last trial.
_SCRIPT = """
import multiprocessing, os, signal, sys
from navkit.cli import _progress
from navkit.cli import main

pids_file, how = sys.argv[1], sys.argv[2]
original = _progress.ProgressBar.__call__

def call(self, done, total):
    original(self, done, total)
    if done == total - 1:
        with open(pids_file, "w") as f:
            f.write(" ".join(str(p.pid) for p in multiprocessing.active_children()))
        if how == "ctrl-c":
            os.killpg(0, signal.SIGINT)  # a terminal's Ctrl-C: the whole process group
        else:
            os.kill(os.getpid(), signal.SIGTERM)  # `kill PID`, a job's time limit
        signal.pause()  # the signal's exception, or the end, comes first

_progress.ProgressBar.__call__ = call
sys.exit(main(["run", "demo", "--trials", "1", "--workers", "2", "--quiet"]))
"""


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    with contextlib.suppress(OSError):  # a zombie not yet reaped by init counts as gone
        status = Path(f"/proc/{pid}/stat").read_text().split(") ")[-1][:1]
        return status != "Z"
    return True


def _run(tmp_path: Path, how: str) -> tuple[int, str, str, list[int]]:
    pids_file = tmp_path / "pids"
    out, err = tmp_path / "out.txt", tmp_path / "err.txt"
    # Files, not pipes: orphaned workers would hold pipes open and hang the test.
    with out.open("w") as o, err.open("w") as e:
        process = subprocess.Popen(
            [sys.executable, "-c", _SCRIPT, str(pids_file), how],
            stdout=o, stderr=e, cwd=tmp_path, start_new_session=True,
        )  # fmt: skip
        try:
            code = process.wait(timeout=300)
        finally:
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGKILL)
    pids = [int(p) for p in pids_file.read_text().split()] if pids_file.exists() else []
    return code, out.read_text(), err.read_text(), pids


def _kill_leftovers(pids: list[int]) -> None:
    for pid in pids:
        with contextlib.suppress(OSError):
            os.kill(pid, signal.SIGKILL)


def test_ctrl_c_with_an_idle_worker_is_one_line(tmp_path: Path) -> None:
    # The idle worker died of KeyboardInterrupt in the pool's queue and printed
    # "Process ForkProcess-1: Traceback ..." under the command's own line.
    code, out, err, pids = _run(tmp_path, "ctrl-c")
    try:
        assert len(pids) == 2
        assert code == 130
        assert err == "navkit: interrupted\n"
        assert out == ""
        deadline = time.monotonic() + 10
        while any(map(_alive, pids)) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not any(map(_alive, pids))
    finally:
        _kill_leftovers(pids)


def test_sigterm_ends_the_run_and_its_workers(tmp_path: Path) -> None:
    # SIGTERM killed the command outright (exit -15) and left its workers
    # blocked forever on the pool's queue, orphaned; the same cleanup as for
    # Ctrl-C now runs: one line, exit code 128 + 15, workers gone.
    code, out, err, pids = _run(tmp_path, "term")
    try:
        assert len(pids) == 2
        deadline = time.monotonic() + 10
        while any(map(_alive, pids)) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not any(map(_alive, pids))
        assert code == 128 + signal.SIGTERM
        assert err == "navkit: terminated (SIGTERM)\n"
        assert out == ""
        assert sorted(p.name for p in tmp_path.iterdir()) == ["err.txt", "out.txt", "pids"]
    finally:
        _kill_leftovers(pids)


def test_handlers_are_restored_after_the_command() -> None:
    from navkit.cli import main

    before = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    assert main(["--version"]) == 0
    assert {s: signal.getsignal(s) for s in before} == before
