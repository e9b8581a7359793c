"""``sweep`` on the start methods that start workers afresh, on every Python.

Python 3.14 starts ``multiprocessing`` workers with ``forkserver`` on Linux
(``fork`` before), as ``spawn`` does on macOS and Windows: a worker imports
what it runs (the scenario's module, navkit) instead of inheriting it, and
everything sent to it must pickle. CI runs Python 3.11 on Linux (``fork``), so
these checks choose the start method themselves: a sweep's pool follows
``multiprocessing.set_start_method`` and its results equal a serial sweep's.
"""

from __future__ import annotations

import json
import multiprocessing
import os
import subprocess
import sys
from pathlib import Path

import pytest

# A user's scenario in a module of its own, which the workers import to unpickle
# it (the script's folder is on their path).
_QUICK = """
import os
from navkit.sim import Scenario, ScenarioResult, TrialResult

class Quick(Scenario):
    name, title, paper, default_trials = "quick", "test", "none", 4

    def cases(self, trials):
        return (("a", trials), ("b", trials))

    def run_trial(self, trial):
        return TrialResult(trial, {"seed": float(trial.seed % 1000), "pid": float(os.getpid())})

    def summarize(self, results, *, seed):
        return ScenarioResult(self.name, seed, tuple(results), ())
"""

# The guard is needed: starting the workers runs the script's top level again.
_SCRIPT = """
import json, multiprocessing, os, sys
from navkit.sim import sweep
from quick import Quick

if __name__ == "__main__":
    multiprocessing.set_start_method(sys.argv[1])
    pooled = sweep(Quick(), trials=3, seeds=11, workers=2)
    serial = sweep(Quick(), trials=3, seeds=11, workers=1)
    print(json.dumps({
        "method": multiprocessing.get_start_method(),
        "pooled": [[r.trial.case, r.trial.index, r.values["seed"]] for r in pooled.trials],
        "serial": [[r.trial.case, r.trial.index, r.values["seed"]] for r in serial.trials],
        "worker_pids": sorted({int(r.values["pid"]) for r in pooled.trials}),
        "parent": os.getpid(),
    }))
"""


@pytest.mark.parametrize(
    "method",
    [
        pytest.param(
            "forkserver",
            marks=pytest.mark.skipif(
                "forkserver" not in multiprocessing.get_all_start_methods(),
                reason="no forkserver here",
            ),
        ),
        pytest.param("spawn", marks=pytest.mark.slow),  # macOS and Windows; slower to start
    ],
)
def test_a_sweep_on_fresh_workers_equals_a_serial_one(tmp_path: Path, method: str) -> None:
    (tmp_path / "quick.py").write_text(_QUICK, encoding="utf-8")
    script = tmp_path / "run_sweep.py"
    script.write_text(_SCRIPT, encoding="utf-8")
    # The parent's environment (NUMBA_CACHE_DIR included) goes to the child and its workers.
    done = subprocess.run(
        [sys.executable, str(script), method],
        capture_output=True, text=True, timeout=300, cwd=tmp_path, env=dict(os.environ),
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    found = json.loads(done.stdout.strip().splitlines()[-1])
    assert found["method"] == method
    assert found["pooled"] == found["serial"]
    assert len(found["pooled"]) == 6
    assert found["parent"] not in found["worker_pids"]  # the trials did run in the pool

