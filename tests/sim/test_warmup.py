"""navkit.sim.warmup (issue 17): compiles every kernel ahead, so first calls are fast."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from navkit.sim import WARMUP_STEPS, WarmupReport, WarmupStep, warmup

# The first astar call of a fresh process, CPU seconds (import excluded).
FIRST_ASTAR = textwrap.dedent(
    """
    import time
    import numpy as np
    from navkit.planning import astar
    t = time.process_time()
    astar(np.ones((8, 8)), (0, 0), (7, 7))
    print(time.process_time() - t)
    """
)


def _first_astar(cache: Path) -> float:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    done = subprocess.run(
        [sys.executable, "-c", FIRST_ASTAR], env=env, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return float(done.stdout.split()[-1])


@pytest.mark.slow
def test_after_warmup_a_fresh_process_plans_without_compiling(tmp_path: Path) -> None:
    cache = tmp_path / "numba"
    cache.mkdir()
    cold = _first_astar(cache / "cold")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache / "warm"))
    script = "from navkit.sim import warmup; warmup(workers=1, only=['astar'])"
    subprocess.run([sys.executable, "-c", script], env=env, check=True)
    warm = _first_astar(cache / "warm")
    # Relative, not absolute: loading the cached code is many times cheaper than compiling.
    assert warm < 0.5 * cold, (warm, cold)


def test_a_step_reports_what_it_compiled_in_a_fresh_cache(tmp_path: Path) -> None:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    script = textwrap.dedent(
        """
        from navkit.sim import warmup
        first = warmup(workers=1, only=["geometry"])
        print(",".join(first.compiled))
        print(",".join(first.loaded))
        """
    )
    done = subprocess.run(
        [sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True
    )
    compiled, loaded = done.stdout.splitlines()[:2]
    assert "navkit.geometry._integrate_kernels" in compiled
    assert loaded == ""
    # A second process finds the same kernels in the cache and compiles nothing.
    done = subprocess.run(
        [sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True
    )
    again_compiled, again_loaded = done.stdout.splitlines()[:2]
    assert again_compiled == ""
    # The step's own kernels are loaded; helpers they call (navkit._shared.se2's,
    # compiled once and inlined by LLVM since review 51) are in their callers'
    # cached code and are not loaded on their own.
    loaded_again = set(again_loaded.split(","))
    assert loaded_again <= set(compiled.split(","))
    geometry = {name for name in compiled.split(",") if name.startswith("navkit.geometry.")}
    assert geometry
    assert {name for name in loaded_again if name.startswith("navkit.geometry.")} == geometry


def test_in_process_report_and_progress() -> None:
    calls: list[tuple[int, int]] = []
    report = warmup(
        workers=1, only=["reactive", "geometry"], progress=lambda d, t: calls.append((d, t))
    )
    assert isinstance(report, WarmupReport)
    assert [s.name for s in report.steps] == ["reactive", "geometry"]  # WARMUP_STEPS order
    assert calls == [(0, 2), (1, 2), (2, 2)]
    assert report.workers == 1
    assert report.seconds >= max(s.seconds for s in report.steps)
    assert report.cpu_seconds == pytest.approx(sum(s.cpu_seconds for s in report.steps))
    for step in report.steps:
        assert not set(step.compiled) & set(step.loaded)
        assert all(k.startswith("navkit.") for k in step.compiled + step.loaded)


def test_parallel_steps_run_in_worker_processes() -> None:
    report = warmup(workers=2, only=["geometry", "reactive"])
    assert report.workers == 2
    assert [s.name for s in report.steps] == ["reactive", "geometry"]
    # Never more processes than steps.
    assert warmup(workers=8, only=["geometry"]).workers == 1


def test_every_step_is_named_and_costed() -> None:
    assert len(WARMUP_STEPS) == len(set(WARMUP_STEPS)) >= 8
    assert {"astar", "field_dstar", "estimation", "simulation", "mapping"} <= set(WARMUP_STEPS)


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"workers": 0}, ValueError, "workers"),
        ({"workers": 2.0}, TypeError, "workers"),
        ({"workers": True}, TypeError, "workers"),
        ({"only": ["nope"]}, ValueError, "only"),
        ({"only": "astar"}, TypeError, "only"),
        ({"only": [1]}, TypeError, "only"),
        ({"progress": 3}, TypeError, "progress"),
    ],
)
def test_bad_arguments_are_refused(kwargs: dict[str, object], error: type, match: str) -> None:
    with pytest.raises(error, match=match):
        warmup(**kwargs)  # type: ignore[arg-type]


def test_records_validate() -> None:
    step = WarmupStep("astar", ["a"], (), 1.0, 0.5)
    assert step.compiled == ("a",)
    with pytest.raises(ValueError, match="seconds"):
        WarmupStep("astar", (), (), -1.0, 0.5)
    with pytest.raises(TypeError, match="compiled"):
        WarmupStep("astar", "abc", (), 1.0, 0.5)
    report = WarmupReport([step, WarmupStep("mapping", ("a", "b"), ("c",), 1.0, 1.0)], 2.0, 1)
    assert report.compiled == ("a", "b") and report.loaded == ("c",)
    with pytest.raises(TypeError, match="steps"):
        WarmupReport((1,), 1.0, 1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="workers"):
        WarmupReport((), 1.0, 0)
