"""Running a scenario's trials anywhere: this process, a process pool or a Dask cluster."""

from __future__ import annotations

import concurrent.futures
import dataclasses
import numbers
import pickle
import queue
import time
from collections.abc import Callable, Sequence
from typing import Any, cast

import numpy as np

from navkit._shared.cores import usable_cores
from navkit._shared.counts import counted
from navkit._shared.validation import as_bool, bounded_int, is_ndarray, shown
from navkit.sim._pool import process_pool
from navkit.sim._scenario import (
    DaskClient,
    Scenario,
    ScenarioResult,
    Trial,
    TrialExecutor,
    TrialResult,
    trial_seed,
)

__all__ = ["sweep"]

#: Most worker processes a local pool may be asked for.
MAX_WORKERS = 1024

# What it returns is ignored: a progress bar's ``update`` may return a value.
Progress = Callable[[int, int], object]


def _as_scenario(scenario: object) -> Scenario:
    if isinstance(scenario, Scenario):
        return scenario
    if isinstance(scenario, str):
        # Imported here: navkit.sim.scenarios imports navkit.sim, which imports this module.
        from navkit.sim.scenarios import get_scenario

        return get_scenario(scenario)()
    if isinstance(scenario, type) and issubclass(scenario, Scenario):
        raise TypeError(
            f"scenario must be a Scenario or a scenario name, got the class "
            f"{scenario.__name__}: pass an instance, {scenario.__name__}(...)"
        )
    kind = type(scenario).__name__
    raise TypeError(f"scenario must be a Scenario or a scenario name, got {kind}")


def _seed_int(value: object, name: str) -> int:
    return bounded_int(value, name, 0, 2**64, exclusive=True)  # trial_seed's base seeds


def _plan(scenario: Scenario, trials: int | None, seeds: object) -> tuple[tuple[Trial, ...], int]:
    """Every trial with its seed, and the base seed to record."""
    if is_ndarray(seeds) and seeds.ndim == 0:
        seeds = seeds[()]  # a NumPy scalar: one base seed (or refused as one, by name)
    if isinstance(seeds, (numbers.Integral, bool, np.bool_)):
        base = _seed_int(seeds, "seeds")
        return scenario.trials(trials, seed=base), base
    if isinstance(seeds, (str, bytes)) or not (isinstance(seeds, Sequence) or is_ndarray(seeds)):
        raise TypeError(f"seeds must be an integer or a sequence of integers, got {shown(seeds)}")
    bases = [_seed_int(s, f"seeds[{i}]") for i, s in enumerate(seeds)]
    if not bases:
        raise ValueError("seeds must hold at least one seed")
    if trials is not None and trials != len(bases):
        raise ValueError(
            f"seeds holds {counted(len(bases), 'seed')} for trials={trials}: give one per "
            "trial index"
        )
    out = []
    for t in scenario.trials(len(bases) if trials is None else trials, seed=0):
        if t.index >= len(bases):
            raise ValueError(
                f"seeds: case {t.case!r} runs {t.index + 1} or more trials, "
                f"seeds holds {len(bases)}"
            )
        out.append(dataclasses.replace(t, seed=trial_seed(bases[t.index], t.case_index, t.index)))
    return tuple(out), bases[0]


def run_one(scenario: Scenario, trial: Trial, keep_traces: bool) -> TrialResult:
    """Run one trial and time it (what every executor runs; module-level, so it pickles).

    Without ``keep_traces`` the trace is dropped here, in the worker: it is then
    neither pickled back to the sweep's process nor held there.
    """
    began = time.perf_counter()
    result = scenario.run_trial(trial)
    elapsed = time.perf_counter() - began
    if not isinstance(result, TrialResult):
        raise TypeError(
            f"{type(scenario).__name__}.run_trial returned a {type(result).__name__}, "
            "not a TrialResult"
        )
    if result.trial != trial:
        raise ValueError(f"{type(scenario).__name__}.run_trial returned another trial's result")
    changes: dict[str, Any] = {}
    if result.wall_time == 0.0:
        changes["wall_time"] = elapsed
    if not keep_traces and result.trace is not None:
        changes["trace"] = None
    return dataclasses.replace(result, **changes) if changes else result


def _name_trial(exc: BaseException, scenario: Scenario, trial: Trial, total: int) -> None:
    """Add a note naming the failed trial to ``exc`` (shown under its traceback)."""
    note = (
        f"in scenario {scenario.name!r}, case {trial.case!r}, trial {trial.index} "
        f"(seed {trial.seed}; {counted(total, 'trial')} in the sweep)"
    )
    exc.add_note(note)


def _check_pickles(scenario: Scenario) -> None:
    """Refuse, before any worker starts, a scenario the pool cannot send to its workers.

    pickle's own error (an ``AttributeError`` for a class defined in a function,
    a ``PicklingError`` or ``TypeError`` for an unpicklable option) would come
    from the first trial's submission, as another exception type.
    """
    try:
        pickle.dumps(scenario)
    except Exception as exc:  # whatever pickle raises for this object
        raise TypeError(
            f"scenario {type(scenario).__qualname__} must pickle to run in worker processes "
            f"({exc}): define its class at a module's top level and give it plain options, "
            "or run it in this process (workers=1)"
        ) from exc


def _is_dask_client(executor: object) -> bool:
    """A ``dask.distributed.Client`` (duck-typed: dask is not imported)."""
    return callable(getattr(executor, "submit", None)) and callable(
        getattr(executor, "gather", None)
    )


def _serial(
    scenario: Scenario, trials: Sequence[Trial], progress: Progress | None, keep_traces: bool
) -> list[TrialResult]:
    results = []
    for trial in trials:
        try:
            results.append(run_one(scenario, trial, keep_traces))
        except Exception as exc:
            _name_trial(exc, scenario, trial, len(trials))
            raise
        if progress is not None:
            progress(len(results), len(trials))
    return results


def _submitted(
    submit: Callable[[Trial], Any],
    cancel: Callable[[list[Any]], None],
    scenario: Scenario,
    trials: Sequence[Trial],
    progress: Progress | None,
) -> list[TrialResult]:
    """Submit every trial, collect results as they finish, in the trials' order.

    Works with ``concurrent.futures`` and Dask futures alike: both call
    ``add_done_callback`` hooks when a future finishes (Dask from another
    thread), which queue the trial's position for this thread to collect.
    """
    done: queue.SimpleQueue[int] = queue.SimpleQueue()
    futures: list[Any] = []
    try:
        for i, trial in enumerate(trials):
            future = submit(trial)
            futures.append(future)
            future.add_done_callback(lambda _f, i=i: done.put(i))
        results: list[TrialResult | None] = [None] * len(trials)
        for count in range(1, len(trials) + 1):
            i = done.get()
            try:
                results[i] = futures[i].result()
            except Exception as exc:
                _name_trial(exc, scenario, trials[i], len(trials))
                raise
            if progress is not None:
                progress(count, len(trials))
    except BaseException:
        cancel(futures)
        raise
    return [r for r in results if r is not None]


def _cancel_all(futures: list[Any]) -> None:
    for f in futures:
        f.cancel()


def sweep(
    scenario: Scenario | str,
    *,
    trials: int | None = None,
    seeds: int | Sequence[int] = 0,
    workers: int | None = None,
    executor: TrialExecutor | None = None,
    progress: Progress | None = None,
    keep_traces: bool = True,
) -> ScenarioResult:
    """Run every trial of a scenario in parallel and summarize them.

    The trials run in this process, in a local process pool (the default), on
    a ``concurrent.futures`` executor or on a Dask cluster. Each trial's seed
    depends only on the seeds given and the trial's place (see
    :func:`trial_seed`), and the results are put back into the scenario's
    order whatever order they finish in, so the same seeds give the same
    result on every executor: equal ``to_dict()`` up to wall-clock
    measurements (each trial's ``wall_time``, values and summary entries
    named ``*_wall_time``, and the table columns and rows whose heading or
    first cell holds the word ``wall``), on machines of one CPU type (the
    scan repulsion sums are vectorised to the CPU's SIMD width: see
    :func:`~navkit.planning.repulsive_force_from_scan`).

    Parameters
    ----------
    scenario : Scenario or str
        The scenario, or a registered name (``"omni-apf"``), constructed with
        its default options.
    trials : int, optional
        Trials per case (default the scenario's ``default_trials``, or the
        length of ``seeds`` when that is a sequence), in [1, 100000]; at most
        1000000 trials over all the cases.
    seeds : int or sequence of int, default 0
        An int is the base seed: trial ``k`` of case ``c`` gets
        ``trial_seed(seeds, c, k)`` (as :meth:`Scenario.trials`). A sequence
        gives one base seed per trial index: trial ``k`` of every case gets
        ``trial_seed(seeds[k], c, k)``, so ``[s] * n`` is the same as ``s``
        with ``trials=n``, and extending the sequence adds trials without
        changing the earlier ones. It must hold one seed per trial index (as
        many as ``trials`` when both are given). Seeds are integers >= 0; the
        result records ``seeds[0]`` as its seed.
    workers : int or None, default None
        Without an ``executor``: 1 runs the trials in this process; otherwise
        a ``concurrent.futures.ProcessPoolExecutor`` of
        ``min(workers, number of trials)`` processes (None: every core this
        process may use; at most 61 on Windows), or this process when that
        is 1. Not used with an ``executor`` (still checked). The pool starts
        its workers by :mod:`multiprocessing`'s start method
        (``multiprocessing.set_start_method`` chooses it): they start afresh
        with ``spawn`` (the default on macOS and Windows) and ``forkserver``
        (the default on Linux from Python 3.14; ``fork`` before): there a
        script must call ``sweep`` under
        ``if __name__ == "__main__":`` (starting the workers runs the script's
        top level again), and the scenario must pickle, its class importable by
        the workers (defined in a module or the script, not in a notebook).
    executor : concurrent.futures.Executor or dask.distributed.Client, optional
        Where to run the trials: an executor's ``submit``, or a Dask client's
        ``submit(..., pure=False)`` (any object with ``submit`` and
        ``gather`` is taken for a Dask client; dask itself is not imported).
        The scenario object is sent with each trial, so it must pickle.
    progress : callable, optional
        Called as ``progress(done, total)`` in this process after each trial
        finishes.
    keep_traces : bool, default True
        Keep each trial's :class:`~navkit.sim.Trace` in the result. False
        drops it where the trial ran, as soon as the trial's values are
        computed (a worker process or Dask worker sends no trace back): every
        ``TrialResult.trace`` is None and ``result.traces`` empty, and the
        scene draws no driven runs (the built-in scenarios compute every
        figure inside the trial, so ``to_dict()`` is the same either way, up
        to wall-clock measurements as above). For long sweeps: see Notes.

    Returns
    -------
    ScenarioResult
        ``scenario.summarize`` of every trial, in the scenario's order, with
        the traces or without them (``keep_traces``).

    Raises
    ------
    TypeError, ValueError
        Bad arguments (named in the message); a scenario whose ``cases``,
        ``run_trial`` or ``summarize`` returns what its contract does not
        allow (named); with a local pool of more than one worker, a scenario
        that does not pickle (``TypeError``, before any worker starts).
    Exception
        The first exception a trial raises, re-raised here with a note naming
        the scenario, case, trial and seed; the trials not yet started are
        cancelled, and the results of those done are not returned. An
        exception from ``progress`` (a ``KeyboardInterrupt`` too) ends the
        sweep the same way, without the note. In the local pool, the trials
        running are let finish after an exception, but a ``KeyboardInterrupt``
        (Ctrl-C, which its workers leave to this process) kills the workers at
        once; the workers also end when this process dies.

    Notes
    -----
    By default the result keeps every trial's :class:`~navkit.sim.Trace`
    (``result.traces``), so memory grows with the number of trials: 80 bytes
    a recorded step (times, poses, estimates and commands: 8 kB a simulated
    second at :class:`~navkit.sim.Simulation`'s default 100 Hz) and the scans
    when they are recorded; about 127 kB a trial for ``Greedy`` with its
    default options (its 40 trials of ``trials=10`` peak 5.1 MB higher with
    their traces than without: 121 kB of arrays a trial, the rest their
    objects; review 50), so 127 GB for a million trials. With
    ``keep_traces=False`` a trial keeps only its values (a few hundred bytes)
    and each trace lives only while its trial runs: those 40 ``Greedy``
    trials peaked at 0.2 MB in this process, against 5.3 MB with their traces
    (a pool of 2 workers; 0.6 and 5.3 MB with ``workers=1``; tracemalloc).

    Examples
    --------
    >>> from navkit.sim.scenarios import Demo
    >>> demo = Demo(map="office", duration=0.2)
    >>> a = sweep(demo, trials=1, seeds=7, workers=1)
    >>> b = sweep(demo, seeds=[7], workers=1)
    >>> [r.trial.seed for r in a.trials] == [r.trial.seed for r in b.trials]
    True
    >>> a.summary["collisions"]
    0.0
    >>> lean = sweep(demo, trials=1, seeds=7, workers=1, keep_traces=False)
    >>> lean.traces, lean.summary["travel_time"] == a.summary["travel_time"], len(a.traces)
    ((), True, 3)
    """
    scenario = _as_scenario(scenario)
    if trials is not None:  # its range is the scenario's (Scenario.trials checks it)
        trials = bounded_int(trials, "trials", or_none=True)
    if workers is not None:
        workers = bounded_int(workers, "workers", 1, MAX_WORKERS, or_none=True)
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be callable or None, got {type(progress).__name__}")
    keep = as_bool(keep_traces, "keep_traces")
    is_executor = isinstance(executor, concurrent.futures.Executor)
    if executor is not None and not is_executor and not _is_dask_client(executor):
        raise TypeError(
            "executor must be a concurrent.futures.Executor or a dask.distributed.Client, "
            f"got {type(executor).__name__}"
        )
    plan, base = _plan(scenario, trials, seeds)

    if is_executor:
        runner = cast(concurrent.futures.Executor, executor)  # is_executor said so
        results = _submitted(
            lambda t: runner.submit(run_one, scenario, t, keep),
            _cancel_all,
            scenario,
            plan,
            progress,
        )
    elif executor is not None:
        client = cast(DaskClient, executor)  # not an Executor: duck-typed above
        results = _submitted(
            lambda t: client.submit(run_one, scenario, t, keep, pure=False),
            client.cancel,
            scenario,
            plan,
            progress,
        )
    else:
        n = min(int(workers) if workers is not None else usable_cores(), len(plan))
        if n <= 1:
            results = _serial(scenario, plan, progress, keep)
        else:
            _check_pickles(scenario)
            with process_pool(n) as pool:
                results = _submitted(
                    lambda t: pool.submit(run_one, scenario, t, keep),
                    _cancel_all,
                    scenario,
                    plan,
                    progress,
                )
    summary = scenario.summarize(results, seed=base)
    if not isinstance(summary, ScenarioResult):
        raise TypeError(
            f"{type(scenario).__name__}.summarize returned a {type(summary).__name__}, "
            "not a ScenarioResult"
        )
    return summary
