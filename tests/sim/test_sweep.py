"""navkit.sim.sweep: the same seeds give the same result in this process, a process
pool, a thread pool and a real Dask cluster (issue 14, "Sweeps beyond one machine")."""

from __future__ import annotations

import concurrent.futures
import time
from collections.abc import Iterator, Sequence
from typing import Any

import numpy as np
import pytest

from dask_cluster import local_cluster
from navkit.sim import (
    Scenario,
    ScenarioResult,
    Table,
    Trial,
    TrialResult,
    sweep,
    trial_seed,
)
from navkit.sim.scenarios import Demo
from scenario_results import comparable

distributed = pytest.importorskip("distributed")

#: A cheap demo: each trial plans a leg and simulates 0.5 s of it (~10-30 ms).
TINY = Demo(duration=0.5)


class Recorder:
    """A progress callback that remembers its calls."""

    def __init__(self) -> None:
        self.calls: list[tuple[int, int]] = []

    def __call__(self, done: int, total: int) -> None:
        self.calls.append((done, total))


@pytest.fixture(scope="module")
def client() -> Iterator[Any]:
    """A real Dask cluster of two worker processes, one thread each (started once)."""
    cluster = local_cluster(distributed)
    dask_client = distributed.Client(cluster)
    try:
        yield dask_client
    finally:
        dask_client.close()
        cluster.close()


# --------------------------------------------------------------------------- scenarios for tests


class Sleepy(Scenario):
    """Trials that finish in the reverse of their order (later ones sleep less)."""

    name = "sleepy"
    title = "test"
    paper = "none"
    default_trials = 4

    def __init__(self, *, fail: int | None = None) -> None:
        self.fail = fail

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        return (("a", trials), ("b", 1))

    def run_trial(self, trial: Trial) -> TrialResult:
        position = trial.case_index * 100 + trial.index
        if position == self.fail:
            raise ValueError(f"trial {position} fails")
        time.sleep(0.01 * max(0, 5 - position) if position < 100 else 0.0)
        return TrialResult(trial, {"position": float(position), "seed": float(trial.seed % 1000)})

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        rows = tuple((r.trial.case, r.values["position"]) for r in results)
        return ScenarioResult(self.name, seed, tuple(results), (Table("t", ("case", "k"), rows),))


# --------------------------------------------------------------------- equality across executors


def test_process_pool_equals_this_process() -> None:
    serial = sweep(TINY, trials=2, seeds=5, workers=1)
    pooled = sweep(TINY, trials=2, seeds=5, workers=2)
    assert len(serial.trials) == 6
    assert comparable(pooled) == comparable(serial)
    with concurrent.futures.ProcessPoolExecutor(max_workers=2) as pool:
        assert comparable(sweep(TINY, trials=2, seeds=5, executor=pool)) == comparable(serial)
    assert all(r.wall_time > 0.0 for r in pooled.trials)


def test_dask_cluster_equals_this_process(client: Any) -> None:
    serial = sweep(TINY, trials=2, seeds=5, workers=1)
    assert comparable(sweep(TINY, trials=2, seeds=5, executor=client)) == comparable(serial)


def test_a_100_trial_sweep_on_the_cluster_equals_the_local_run(client: Any) -> None:
    local = sweep(TINY, trials=34, seeds=11, workers=1)
    assert len(local.trials) == 102
    progress = Recorder()
    remote = sweep(TINY, trials=34, seeds=11, executor=client, progress=progress)
    assert comparable(remote) == comparable(local)
    assert progress.calls == [(k, 102) for k in range(1, 103)]
    # The trials really differ from each other (noise), so equality means something.
    errors = {r.values["estimate_error"] for r in remote.trials}
    assert len(errors) > 90


# --------------------------------------------------------------------------- order and progress


@pytest.mark.parametrize("kind", ["serial", "threads"])
def test_results_come_back_in_trial_order(kind: str) -> None:
    progress = Recorder()
    scenario = Sleepy()
    if kind == "serial":
        result = sweep(scenario, trials=5, workers=1, progress=progress)
    else:
        with concurrent.futures.ThreadPoolExecutor(max_workers=6) as pool:
            result = sweep(scenario, trials=5, executor=pool, progress=progress)
    positions = [r.values["position"] for r in result.trials]
    assert positions == [0.0, 1.0, 2.0, 3.0, 4.0, 100.0]
    assert [r.trial for r in result.trials] == list(scenario.trials(5, seed=0))
    assert progress.calls == [(k, 6) for k in range(1, 7)]


# --------------------------------------------------------------------------- seeds


def test_an_int_seed_is_the_scenarios_base_seed() -> None:
    result = sweep(Sleepy(), trials=3, seeds=9, workers=1)
    assert [r.trial for r in result.trials] == list(Sleepy().trials(3, seed=9))
    assert result.seed == 9


def test_a_seed_sequence_gives_one_base_seed_per_trial_index() -> None:
    scenario = Sleepy()
    listed = sweep(scenario, seeds=[4, 8, 15], workers=1)
    assert [(r.trial.case_index, r.trial.index) for r in listed.trials] == [
        (0, 0), (0, 1), (0, 2), (1, 0),
    ]  # fmt: skip
    expected = [trial_seed(s, c, k) for s, c, k in ((4, 0, 0), (8, 0, 1), (15, 0, 2), (4, 1, 0))]
    assert [r.trial.seed for r in listed.trials] == expected
    assert listed.seed == 4
    # [s] * n is the int seed s; extending the sequence keeps the earlier trials.
    same = sweep(scenario, trials=3, seeds=[6, 6, 6], workers=1)
    assert [r.trial for r in same.trials] == [r.trial for r in sweep(scenario, trials=3, seeds=6,
                                                                    workers=1).trials]  # fmt: skip
    longer = sweep(scenario, seeds=[4, 8, 15, 16], workers=1)
    assert [r.trial.seed for r in longer.trials][:3] == expected[:3]


def test_a_zero_dimensional_seed_array_is_one_base_seed() -> None:
    # np.array(9) is neither an int nor a sequence: it raised NumPy's unnamed
    # "iteration over a 0-d array".
    seeds: Any = np.array(9, dtype=np.uint64)
    result = sweep(Sleepy(), trials=3, seeds=seeds, workers=1)
    assert [r.trial for r in result.trials] == list(Sleepy().trials(3, seed=9))
    assert result.seed == 9
    with pytest.raises(TypeError, match=r"^seeds must be an integer or a sequence"):
        sweep(Sleepy(), trials=3, seeds=seeds.astype(float), workers=1)
    negative: Any = np.array(-1)
    with pytest.raises(ValueError, match=r"^seeds must be in \[0, 2\*\*64\)"):
        sweep(Sleepy(), trials=3, seeds=negative, workers=1)


# --------------------------------------------------------------------------- failures


@pytest.mark.parametrize("kind", ["serial", "threads"])
def test_a_failing_trial_propagates_named(kind: str) -> None:
    scenario = Sleepy(fail=2)
    with pytest.raises(ValueError, match="trial 2 fails") as info:
        if kind == "serial":
            sweep(scenario, trials=4, workers=1)
        else:
            with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
                sweep(scenario, trials=4, executor=pool)
    notes = getattr(info.value, "__notes__", [])
    assert any("'sleepy'" in n and "case 'a', trial 2" in n for n in notes), notes


def test_a_failing_trial_on_the_cluster_propagates_named(client: Any) -> None:
    broken = Demo(map="office", duration=0.5)
    broken.map_path = "/nonexistent/navkit/map.yaml"  # every worker fails to load it
    with pytest.raises(OSError, match="nonexistent") as info:
        sweep(broken, trials=1, executor=client)
    assert any("'demo'" in n and "trial 0" in n for n in getattr(info.value, "__notes__", []))


def test_a_scenario_by_name() -> None:
    result = sweep("demo", workers=1)
    assert result.scenario == "demo" and len(result.trials) == 3


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"scenario": 3}, TypeError, "scenario"),
        ({"scenario": "nosuch"}, ValueError, "unknown scenario"),
        ({"trials": 0}, ValueError, "trials"),
        ({"trials": 2.0}, TypeError, "trials"),
        ({"seeds": -1}, ValueError, "seeds"),
        ({"seeds": True}, TypeError, "seeds"),
        ({"seeds": "1"}, TypeError, "seeds"),
        ({"seeds": []}, ValueError, "seeds"),
        ({"seeds": [1, -2]}, ValueError, r"seeds\[1\]"),
        ({"seeds": 2**64}, ValueError, r"^seeds must be in \[0, 2\*\*64\)"),
        ({"seeds": [1, 2**64]}, ValueError, r"^seeds\[1\] must be in \[0, 2\*\*64\)"),
        ({"seeds": [1, 2], "trials": 3}, ValueError, "seeds"),
        ({"workers": 0}, ValueError, "workers"),
        ({"workers": True}, TypeError, "workers"),
        ({"executor": object()}, TypeError, "executor"),
        ({"progress": 5}, TypeError, "progress"),
    ],
)
def test_bad_arguments(kwargs: dict[str, Any], error: type[Exception], match: str) -> None:
    scenario = kwargs.pop("scenario", Sleepy())
    with pytest.raises(error, match=match):
        sweep(scenario, workers=1, **kwargs) if "workers" not in kwargs else sweep(
            scenario, **kwargs
        )
