"""Checks of the arguments every scenario method takes (shared by omni-apf and greedy).

Candidates for ``navkit.sim._scenario`` (the framework), where every scenario
could use them.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from typing import Any

import numpy as np

from navkit.sim import TrialResult

__all__ = ["MAX_TRIALS", "check_trials", "group_results"]

#: Most trials per case, as ``Scenario.trials``.
MAX_TRIALS = 100_000
#: Largest base seed.
MAX_SEED = 2**64 - 1


def check_trials(trials: Any) -> int:
    """``trials`` per case as an int in [1, MAX_TRIALS] (TypeError, ValueError)."""
    if isinstance(trials, bool) or not isinstance(trials, (int, np.integer)):
        raise TypeError(f"trials must be an integer, got {type(trials).__name__}")
    if not 1 <= trials <= MAX_TRIALS:
        raise ValueError(f"trials must be in [1, {MAX_TRIALS}], got {trials}")
    return int(trials)


def group_results(
    results: Any, seed: Any, check_case: Callable[[int], object]
) -> tuple[tuple[TrialResult, ...], dict[int, list[TrialResult]], int]:
    """Checked ``results`` and ``seed`` of ``summarize``, and the results by case index.

    ``check_case(case_index)`` raises for an index the scenario does not have.
    """
    if isinstance(results, (Mapping, str, bytes, set, frozenset)) or not isinstance(
        results, Iterable
    ):
        raise TypeError(f"results must be a sequence of TrialResult, got {type(results).__name__}")
    out = tuple(results)
    for k, r in enumerate(out):
        if not isinstance(r, TrialResult):
            raise TypeError(f"results[{k}] must be a TrialResult, got {type(r).__name__}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)):
        raise TypeError(f"seed must be an integer, got {type(seed).__name__}")
    if not 0 <= seed <= MAX_SEED:
        raise ValueError("seed must be an integer in [0, 2**64 - 1]")
    by_case: dict[int, list[TrialResult]] = {}
    for r in out:
        check_case(r.trial.case_index)  # a foreign trial fails here, naming the range
        by_case.setdefault(r.trial.case_index, []).append(r)
    return out, by_case, int(seed)
