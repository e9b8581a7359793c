"""A sweep's forkserver workers end when the sweep's process is killed (Python 3.14 on Linux).

Python 3.14 starts pool workers with ``forkserver`` on Linux. Such a worker's
parent process is the fork server, not the sweep's process, so the
``PR_SET_PDEATHSIG`` that ``process_pool`` asks for fires only when the server
ends; and the server ends only when every process holding its "alive" pipe
has, the workers included. A ``SIGKILL``ed sweep (the OOM killer) left its
workers and the server waiting for work forever. Checked here on every Python
by choosing the start method.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = [
    pytest.mark.skipif(
        not Path("/proc/self/stat").exists()
        or "forkserver" not in multiprocessing.get_all_start_methods(),
        reason="finds worker processes in /proc; needs forkserver",
    ),
]

_SWEEP = """
import multiprocessing, os, signal, sys
from navkit.sim import sweep
from quick import Quick

pids_file = sys.argv[1]
multiprocessing.set_start_method("forkserver")

def progress(done, total):
    with open(pids_file + ".part", "w") as f:
        f.write(" ".join(str(p.pid) for p in multiprocessing.active_children()))
    os.replace(pids_file + ".part", pids_file)
    signal.pause()

sweep(Quick(), trials=4, workers=2, progress=progress)
"""

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


def _alive(pid: int) -> bool:
    """``pid`` runs (a zombie counts as gone)."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return False
    return fields[0] != "Z"


def _parent(pid: int) -> int:
    return int(Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[1])


def test_forkserver_workers_end_with_a_killed_sweep(tmp_path: Path) -> None:
    pids_file = tmp_path / "pids"
    (tmp_path / "quick.py").write_text(_QUICK, encoding="utf-8")
    survivors: list[int] = []
    with (tmp_path / "err.txt").open("w") as err:
        process = subprocess.Popen(
            [sys.executable, "-c", _SWEEP, str(pids_file)],
            stderr=err, cwd=tmp_path, start_new_session=True, env=dict(os.environ),
        )  # fmt: skip
        try:
            deadline = time.monotonic() + 240
            while not pids_file.exists() and process.poll() is None:
                assert time.monotonic() < deadline, "the sweep never reported progress"
                time.sleep(0.05)
            workers = [int(p) for p in pids_file.read_text().split()]
            assert len(workers) == 2
            server = _parent(workers[0])
            assert server != process.pid  # the fork server's child, not the sweep's
            os.kill(process.pid, signal.SIGKILL)
            assert process.wait(timeout=30) == -signal.SIGKILL
            deadline = time.monotonic() + 10
            while any(map(_alive, [*workers, server])) and time.monotonic() < deadline:
                time.sleep(0.05)
            survivors = [p for p in [*workers, server] if _alive(p)]
            assert survivors == []
        finally:
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGKILL)
                process.wait()
            for pid in survivors:  # the workers and the server are in the sweep's session
                with contextlib.suppress(OSError):
                    os.kill(pid, signal.SIGKILL)
