"""A sweep may keep its trials' values without their traces (review 45, SCENMEM).

``Scenario.run`` and ``sweep`` kept every trial's ``Trace`` in the result: about
120 kB a trial for ``Greedy``, 120 GB at the documented limit of 10**6 trials.
``keep_traces=False`` drops each trace in ``run_one``, where the trial ran (a
worker process or Dask worker sends none back), and changes nothing else: the
same ``to_dict()`` for every registered scenario, wall-clock figures aside.
Measured with ``peak_bytes``: 201 trials of the office demo (0.5 s legs) peak at
4.75 MB with their traces, 0.31 MB without; 400 ``omni-apf`` trials (one target,
6 s) at 19.2 MB and 0.53 MB.
"""

from __future__ import annotations

import concurrent.futures
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from shapely.geometry import box

from memory_peak import peak_bytes
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import (
    Robot,
    Scenario,
    ScenarioResult,
    Simulation,
    Table,
    Trial,
    TrialResult,
    World,
    sweep,
)
from navkit.sim.scenarios import SCENARIOS, Demo
from scenario_results import SMALL, comparable

#: Needs no data folder: the office map is built in code.
TINY = Demo(map="office", duration=0.5)


def test_every_registered_scenario_has_a_small_version() -> None:
    assert set(SMALL) == set(SCENARIOS)


@pytest.mark.parametrize("name", sorted(SMALL))
def test_without_traces_every_scenario_gives_the_same_result(name: str, shared_data: Path) -> None:
    scenario = SMALL[name]()
    full = scenario.run(1, seed=4)
    lean = scenario.run(1, seed=4, keep_traces=False)
    assert any(r.trace is not None for r in full.trials)  # the option has something to drop
    assert all(r.trace is None for r in lean.trials) and lean.traces == ()
    assert comparable(lean) == comparable(full)
    # The scene keeps its map, plans and markers; only the driven runs are missing.
    assert full.scene is not None and lean.scene is not None
    assert full.scene.traces and not lean.scene.traces
    assert [label for label, _ in lean.scene.paths] == [label for label, _ in full.scene.paths]
    assert [label for label, _ in lean.scene.points] == [label for label, _ in full.scene.points]


class Recording(concurrent.futures.Executor):
    """Runs each task at once in this thread and remembers what the task returned."""

    def __init__(self) -> None:
        self.returned: list[Any] = []

    def submit(
        self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any
    ) -> concurrent.futures.Future[Any]:
        future: concurrent.futures.Future[Any] = concurrent.futures.Future()
        result = fn(*args, **kwargs)
        self.returned.append(result)
        future.set_result(result)
        return future


@pytest.mark.parametrize("keep", [True, False])
def test_the_trace_is_dropped_by_the_task_itself(keep: bool) -> None:
    """What an executor's task returns (what a pool or Dask would pickle) has no trace."""
    executor = Recording()
    result = sweep(TINY, trials=1, seeds=2, executor=executor, keep_traces=keep)
    assert len(executor.returned) == 3
    assert all((r.trace is not None) is keep for r in executor.returned)
    assert all((r.trace is not None) is keep for r in result.trials)


def test_a_process_pool_without_traces_equals_this_process() -> None:
    serial = sweep(TINY, trials=2, seeds=5, workers=1)
    pooled = sweep(TINY, trials=2, seeds=5, workers=2, keep_traces=False)
    assert all(r.trace is None for r in pooled.trials)
    assert comparable(pooled) == comparable(serial)


def test_dropping_the_traces_bounds_a_sweeps_memory() -> None:
    """30 trials: the traces (scans included) are most of what a sweep keeps."""
    full_peak, full = peak_bytes(lambda: sweep(TINY, trials=10, seeds=1, workers=1))
    lean_peak, lean = peak_bytes(
        lambda: sweep(TINY, trials=10, seeds=1, workers=1, keep_traces=False)
    )
    assert len(lean.trials) == len(full.trials) == 30
    # Measured 0.76 MB against 0.11 MB (what one trial needs while it runs).
    assert lean_peak < full_peak / 3, (lean_peak, full_peak)


# ------------------------------------------------------------- a scenario of the user's


def _short_trace() -> Any:
    world = World(box(-1.0, -1.0, 3.0, 1.0).exterior)
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.1)
    forward = Simulation(
        world, robot, lambda obs: Twist2D(0.2, 0.0, 0.0), start=(0.0, 0.0, 0.0), duration=0.1
    )
    return forward.run()


class Timed(Scenario):
    """Trials that time themselves (as the built-in ones do) and return a trace or none."""

    name, title, paper, default_trials = "timed", "test", "none", 2

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        return (("with a trace", trials), ("without", trials))

    def run_trial(self, trial: Trial) -> TrialResult:
        trace = _short_trace() if trial.case_index == 0 else None
        return TrialResult(trial, {"k": float(trial.index)}, trace, wall_time=1.5)

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        rows = tuple((r.trial.case, r.values["k"]) for r in results)
        return ScenarioResult(self.name, seed, tuple(results), (Table("t", ("case", "k"), rows),))


def test_a_trials_own_wall_time_and_values_survive_the_drop() -> None:
    full = Timed().run(seed=1)
    lean = Timed().run(seed=1, keep_traces=False)
    assert [r.trace is None for r in full.trials] == [False, False, True, True]
    assert all(r.trace is None for r in lean.trials)
    assert [r.wall_time for r in lean.trials] == [1.5] * 4  # not replaced by run_one's clock
    assert lean.to_dict() == full.to_dict()


# ---------------------------------------------------------------------------- checks


@pytest.mark.parametrize("value", [1, 0, "False", None, 1.0, np.array([True]), [], np.float64(0)])
@pytest.mark.parametrize("where", ["sweep", "run"])
def test_keep_traces_takes_bools_only(value: object, where: str) -> None:
    calls: list[tuple[int, int]] = []

    def progress(done: int, total: int) -> None:
        calls.append((done, total))

    with pytest.raises(TypeError, match=r"^keep_traces must be a bool, got "):
        if where == "sweep":
            sweep(TINY, trials=1, workers=1, progress=progress, keep_traces=value)  # type: ignore[arg-type]
        else:
            TINY.run(1, progress=progress, keep_traces=value)  # type: ignore[arg-type]
    assert calls == []  # refused before any trial ran


def test_a_numpy_bool_is_a_bool() -> None:
    result = sweep(TINY, trials=1, workers=1, keep_traces=np.bool_(False))  # type: ignore[arg-type]
    assert result.traces == ()
    assert len(Timed().run(keep_traces=np.bool_(True)).traces) == 2  # type: ignore[arg-type]
