"""A user's own Scenario: a broken contract is named, not run silently or as a raw error.

Found by a user's-eye review of ``Scenario`` subclasses: ``cases()`` giving a
negative count ran no trial of that case without a word, a float count failed
inside ``range`` ("'float' object cannot be interpreted as an integer"),
items that are not pairs failed to unpack; ``summarize`` returning None made
``run()`` return None; a scenario that cannot be pickled (a class defined in
a function) failed in the process pool with pickle's ``AttributeError``.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import pytest

from navkit.sim import Scenario, ScenarioResult, Table, Trial, TrialResult, sweep


class Flip(Scenario):
    """One case of ``n`` trials; ``cases_of`` and ``summary_of`` replace the contract's parts."""

    name, title, paper, default_trials = "flip", "a test scenario", "none", 2
    cases_of: Callable[[int], Any] | None = None
    summary_of: Callable[[Sequence[TrialResult], int], Any] | None = None

    def cases(self, trials: int) -> Any:
        return (("one", trials),) if self.cases_of is None else type(self).cases_of(trials)  # type: ignore[misc]

    def run_trial(self, trial: Trial) -> TrialResult:
        return TrialResult(trial, {"seed_parity": float(trial.seed % 2)})

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> Any:
        if self.summary_of is not None:
            return type(self).summary_of(results, seed)  # type: ignore[misc]
        table = Table("flip", ("trials",), ((len(results),),))
        return ScenarioResult(self.name, seed, tuple(results), (table,), {"n": len(results)})


def _with(**parts: Any) -> Flip:
    return type("Custom", (Flip,), {k: staticmethod(v) for k, v in parts.items()})()


def test_the_well_formed_scenario_runs() -> None:
    assert Flip().run(3).summary == {"n": 3.0}
    assert _with(cases_of=lambda n: (("a", n), ("b", 0))).run(2).summary == {"n": 2.0}


@pytest.mark.parametrize(
    ("cases", "error", "words"),
    [
        pytest.param(lambda n: (("a", -1),), ValueError,
                     r"Custom\.cases\(2\)\[0\]: the count must be in \[0, 100000\], got -1",
                     id="negative"),
        pytest.param(lambda n: (("a", 10**9),), ValueError,
                     r"the count must be in \[0, 100000\], got 1000000000", id="huge"),
        pytest.param(lambda n: (("a", 1.5),), TypeError,
                     r"Custom\.cases\(2\)\[0\]: the count must be an integer, got float",
                     id="float"),
        pytest.param(lambda n: (("a", True),), TypeError,
                     r"the count must be an integer, got bool", id="bool"),
        pytest.param(lambda n: ("a",), TypeError,
                     r"Custom\.cases\(2\)\[0\] must be a \(description, count\) pair, got str",
                     id="not-a-pair"),
        pytest.param(lambda n: (("a", 1, 2),), TypeError,
                     r"must be a \(description, count\) pair, got a tuple of 3", id="triple"),
        pytest.param(lambda n: ((1, 1),), TypeError,
                     r"Custom\.cases\(2\)\[0\]: the description must be a str, got int",
                     id="description"),
        pytest.param(lambda n: None, TypeError,
                     r"Custom\.cases\(2\) must return a sequence of \(description, count\) "
                     r"pairs, got NoneType", id="none"),
        pytest.param(lambda n: {"a": 1}, TypeError, r"must return a sequence .*got dict",
                     id="mapping"),
    ],
)
def test_cases_out_of_contract_are_named(cases: Any, error: type, words: str) -> None:
    scenario = _with(cases_of=cases)
    with pytest.raises(error, match=words):
        scenario.trials(2)
    with pytest.raises(error, match=words):
        scenario.run(2)


@pytest.mark.parametrize(
    "summary",
    [pytest.param(lambda r, s: None, id="none"), pytest.param(lambda r, s: {"n": 1.0}, id="dict")],
)
def test_a_summarize_that_returns_no_result_is_named(summary: Any) -> None:
    with pytest.raises(TypeError, match=r"Custom\.summarize returned a \w+, not a ScenarioResult"):
        _with(summary_of=summary).run(2)


def test_a_scenario_that_cannot_pickle_is_refused_before_the_pool_starts() -> None:
    class Local(Flip):  # defined in a function: pickle cannot find it by name
        pass

    with pytest.raises(TypeError, match=r"scenario .*Local.* must pickle to run in worker "
                                         r"processes.*workers=1"):  # fmt: skip
        sweep(Local(), trials=2, workers=2)
    assert sweep(Local(), trials=2, workers=1).summary == {"n": 2.0}  # in this process: fine


def test_the_case_count_is_checked_too() -> None:
    # _case_of (the built-in scenarios' run_trial) and _results_by_case count the
    # cases; a broken cases() is named there as in trials() and run().
    scenario = _with(cases_of=lambda n: (("a", -1),))
    with pytest.raises(ValueError, match=r"Custom\.cases\(1\)\[0\]: the count must be in"):
        scenario._case_of(Trial("a", 0, 0, 1))
    assert Flip()._case_of(Trial("one", 0, 0, 1)) == 0
