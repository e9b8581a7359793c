"""The local process pools of sweep and warmup: Ctrl-C stops them at once, no orphans."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from navkit.sim._pool import process_pool

pytestmark = pytest.mark.skipif(
    not Path("/proc/self/stat").exists() or not hasattr(os, "killpg"),
    reason="finds worker processes in /proc; POSIX signals",
)


def _alive(pid: int) -> bool:
    """``pid`` runs (a zombie not yet reaped by init counts as gone)."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return False
    return fields[0] != "Z"


def _children(pid: int) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        with contextlib.suppress(OSError, IndexError):
            fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            if int(fields[1]) == pid:
                found.append(int(entry.name))
    return found


def _wait_gone(pids: list[int], seconds: float) -> list[int]:
    deadline = time.monotonic() + seconds
    while any(map(_alive, pids)) and time.monotonic() < deadline:
        time.sleep(0.05)
    return [p for p in pids if _alive(p)]


def _kill_all(pids: list[int]) -> None:
    for pid in pids:
        with contextlib.suppress(OSError):
            os.kill(pid, signal.SIGKILL)


@pytest.mark.parametrize("target", ["process", "group"])
def test_ctrl_c_stops_a_cold_warmup_at_once(tmp_path: Path, target: str) -> None:
    # With an empty numba cache, warmup(workers=2) ignored Ctrl-C for over a
    # minute: leaving its pool's `with` block waited for every queued step.
    # Sent to the whole group (a terminal's Ctrl-C), the signal also made each
    # idle worker print a traceback of the pool's internals.
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    err = tmp_path / "err.txt"
    with err.open("w") as e:  # a file, not a pipe: orphans would hold a pipe open
        process = subprocess.Popen(
            [sys.executable, "-c", "import navkit.sim; navkit.sim.warmup(workers=2)"],
            stderr=e, env=env, cwd=tmp_path, start_new_session=True,
        )  # fmt: skip
        workers: list[int] = []
        try:
            deadline = time.monotonic() + 120
            while len(workers) < 2 and process.poll() is None and time.monotonic() < deadline:
                time.sleep(0.05)
                workers = _children(process.pid)
            assert len(workers) == 2, "warmup started no pool of two workers"
            time.sleep(1.0)  # compiling now
            assert process.poll() is None
            if target == "group":
                os.killpg(process.pid, signal.SIGINT)
            else:
                os.kill(process.pid, signal.SIGINT)
            # Seconds, not the minute or more of a cold compilation.
            code = process.wait(timeout=30)
            assert _wait_gone(workers, 10) == []
        finally:
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()
            _kill_all(workers)
    assert code == -signal.SIGINT
    lines = err.read_text().splitlines()
    assert lines[-1] == "KeyboardInterrupt"
    assert lines.count("Traceback (most recent call last):") == 1
    assert not any(line.startswith("Process ") for line in lines)


# A sweep with two workers whose process then blocks in its progress callback
# until it is killed: the workers run out of queued trials and wait for more.
_SWEEP = """
import multiprocessing, os, signal, sys
import navkit.sim._pool
from navkit.sim import sweep
from quick import Quick

pids_file, how = sys.argv[1], sys.argv[2]
if how == "thread":  # the portable way, used where prctl is not available
    navkit.sim._pool._kill_on_parent_death = lambda: False

def progress(done, total):
    with open(pids_file + ".part", "w") as f:
        f.write(" ".join(str(p.pid) for p in multiprocessing.active_children()))
    os.replace(pids_file + ".part", pids_file)
    signal.pause()

sweep(Quick(), trials=4, workers=2, progress=progress)
"""

# In a module of its own, so that workers started by spawn import it too.
_QUICK = """
from navkit.sim import Scenario, ScenarioResult, TrialResult

class Quick(Scenario):
    name, title, paper, default_trials = "quick", "test", "none", 4

    def cases(self, trials):
        return (("a", trials),)

    def run_trial(self, trial):
        return TrialResult(trial, {"seed": float(trial.seed % 1000)})

    def summarize(self, results, *, seed):
        return ScenarioResult(self.name, seed, tuple(results), ())
"""


@pytest.mark.parametrize("how", ["prctl", "thread"])
def test_sweep_workers_end_with_a_killed_parent(tmp_path: Path, how: str) -> None:
    # SIGKILL (or the OOM killer) ended the sweep's process and left its
    # workers blocked forever on the pool's queue, orphans.
    pids_file = tmp_path / "pids"
    (tmp_path / "quick.py").write_text(_QUICK)
    with (tmp_path / "err.txt").open("w") as e:
        process = subprocess.Popen(
            [sys.executable, "-c", _SWEEP, str(pids_file), how],
            stderr=e, cwd=tmp_path, start_new_session=True,
        )  # fmt: skip
        workers: list[int] = []
        try:
            deadline = time.monotonic() + 120
            while not pids_file.exists() and process.poll() is None:
                assert time.monotonic() < deadline, "the sweep never reported progress"
                time.sleep(0.05)
            workers = [int(p) for p in pids_file.read_text().split()]
            assert len(workers) == 2
            assert all(map(_alive, workers))
            os.kill(process.pid, signal.SIGKILL)
            assert process.wait(timeout=30) == -signal.SIGKILL
            assert _wait_gone(workers, 10) == []
        finally:
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()
            _kill_all(workers)


def test_interrupt_in_the_block_kills_the_running_workers() -> None:
    with pytest.raises(KeyboardInterrupt), process_pool(2) as pool:
        running = [pool.submit(time.sleep, 120) for _ in range(3)]
        while not all(f.running() for f in running[:2]):
            time.sleep(0.01)
        pids = list(pool._processes)
        raise KeyboardInterrupt
    assert len(pids) == 2
    assert _wait_gone(pids, 10) == []
    assert all(f.done() for f in running)  # none left to wait for


def test_an_exception_lets_the_running_task_finish(tmp_path: Path) -> None:
    # A failed task is not an interrupt: the tasks running end normally.
    mark = tmp_path / "mark"
    with pytest.raises(ValueError, match="a trial failed"), process_pool(2) as pool:
        task = pool.submit(_sleep_then_touch, 0.5, str(mark))
        while not task.running():
            time.sleep(0.01)
        raise ValueError("a trial failed")
    assert task.result() is None
    assert mark.exists()


def _sleep_then_touch(seconds: float, path: str) -> None:
    time.sleep(seconds)
    Path(path).touch()
