"""A run's trials are bounded over all of a scenario's cases, not only per case (review 27).

Each count a ``Scenario.cases`` returns was bounded (at most 100000), but not
their number: a scenario of 10^5 cases asked for 10^5 trials each would build
10^10 trials (2 * 10^6 of them took 20 s and their memory before the first ran).
A run now has at most 1000000 trials over all its cases, refused with a
ValueError naming ``trials`` and the case where the total passed the limit,
before any trial runs. The built-in scenarios stay within it at their per-case
maximum (900001 at most).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import pytest

from navkit.sim import Scenario, ScenarioResult, Trial, TrialResult, sweep
from navkit.sim.scenarios import get_scenario

MAX_PER_CASE = 100_000
MAX_TOTAL = 1_000_000


class _Cases(Scenario):
    """``n_cases`` cases of ``trials`` each; a trial that runs is an error here."""

    name, title, paper, default_trials = "cases", "many cases", "none", 1

    def __init__(self, n_cases: int) -> None:
        self.n_cases = n_cases

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        return tuple((f"case {k}", trials) for k in range(self.n_cases))

    def run_trial(self, trial: Trial) -> TrialResult:
        raise AssertionError("no trial may run")

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        raise AssertionError("nothing to summarize")


@pytest.mark.parametrize(
    "start",
    [
        lambda s: s.trials(MAX_PER_CASE),
        lambda s: s.run(trials=MAX_PER_CASE),
        lambda s: sweep(s, trials=MAX_PER_CASE),
        lambda s: sweep(s, trials=MAX_PER_CASE, workers=2),
    ],
    ids=["trials", "run", "sweep", "sweep-pool"],
)
def test_more_trials_than_the_limit_over_the_cases_are_refused_before_any_runs(
    start: Callable[[Scenario], object],
) -> None:
    # 11 cases of the per-case maximum: 1100000 trials, each count allowed.
    with pytest.raises(ValueError, match="trials") as info:
        start(_Cases(11))
    message = str(info.value)
    assert "_Cases.cases(100000)" in message and "cases 0..10" in message
    assert "1100000" in message and "1000000" in message


def test_the_limit_is_said_at_the_first_case_past_it() -> None:
    # 10^5 cases of 20 trials: past the limit at case 50000 (1000020 trials).
    with pytest.raises(ValueError, match=r"cases 0\.\.50000 ask for 1000020 trials"):
        _Cases(MAX_PER_CASE).trials(20)


def test_exactly_the_limit_is_allowed_and_one_more_is_not() -> None:
    assert sum(n for _, n in _Cases(10)._checked_cases(MAX_PER_CASE)) == MAX_TOTAL
    with pytest.raises(ValueError, match="1000001"):

        class _OneMore(_Cases):
            def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
                return (*super().cases(trials), ("one more", 1))

        _OneMore(10).trials(MAX_PER_CASE)


def test_cases_without_trials_do_not_count() -> None:
    class _Sparse(_Cases):
        def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
            return tuple((f"case {k}", trials if k < 2 else 0) for k in range(MAX_PER_CASE))

    trials = _Sparse(0).trials(3)
    assert [(t.case_index, t.index) for t in trials] == [(0, 0), (0, 1), (0, 2), (1, 0),
                                                         (1, 1), (1, 2)]  # fmt: skip


@pytest.mark.parametrize("name", ["omni-apf", "indoor-nav", "soccer", "diff-astar", "greedy",
                                  "demo"])  # fmt: skip
def test_the_built_in_scenarios_are_within_the_limit_at_the_per_case_maximum(name: str) -> None:
    counts = [n for _, n in get_scenario(name)()._checked_cases(MAX_PER_CASE)]
    assert max(counts) == MAX_PER_CASE and sum(counts) <= MAX_TOTAL
