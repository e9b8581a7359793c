"""Scenarios a user adds to (or removes from) ``SCENARIOS`` are what ``get_scenario`` finds."""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Sequence

import numpy as np
import pytest

from navkit.sim import Scenario, ScenarioResult, Trial, TrialResult, sweep
from navkit.sim.scenarios import SCENARIOS, Greedy, get_scenario


class Dice(Scenario):
    """One case whose trials draw a number from their seed."""

    name = "dice"
    title = "draws"
    paper = "none"
    default_trials = 2

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        return (("roll", trials),)

    def run_trial(self, trial: Trial) -> TrialResult:
        return TrialResult(trial, {"draw": float(np.random.default_rng(trial.seed).random())})

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        draws = [r.values["draw"] for r in results]
        return ScenarioResult(self.name, seed, tuple(results), (), {"mean": float(np.mean(draws))})


def test_an_added_scenario_is_found_by_name(monkeypatch: pytest.MonkeyPatch) -> None:
    # get_scenario read only the private registry: an added entry was "unknown".
    monkeypatch.setitem(SCENARIOS, "dice", Dice)
    assert get_scenario("dice") is Dice
    result = sweep("dice", trials=3, seeds=4, workers=1)
    assert result.summary == Dice().run(3, seed=4).summary
    assert [t.trial.case for t in result.trials] == ["roll"] * 3
    with pytest.raises(ValueError, match="known: demo, dice, diff-astar"):
        get_scenario("nosuch")


def test_a_replaced_or_removed_scenario_is_what_get_scenario_finds(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setitem(SCENARIOS, "greedy", Dice)
    assert get_scenario("greedy") is Dice
    monkeypatch.delitem(SCENARIOS, "demo")
    with pytest.raises(ValueError, match=r"unknown scenario 'demo'; known: diff-astar, greedy"):
        get_scenario("demo")
    monkeypatch.undo()
    assert get_scenario("greedy") is Greedy


@pytest.mark.parametrize("entry", [3, Greedy(), object, "greedy"])
def test_an_added_entry_that_is_no_scenario_class_is_named(
    monkeypatch: pytest.MonkeyPatch, entry: object
) -> None:
    monkeypatch.setitem(SCENARIOS, "bad", entry)
    with pytest.raises(TypeError, match=r"SCENARIOS\['bad'\] must be a Scenario subclass"):
        get_scenario("bad")


_LAZY = """
import json, sys
import navkit.sim.scenarios as scenarios
cls = scenarios.get_scenario("greedy")
try:
    scenarios.get_scenario("nosuch")
except ValueError as exc:
    message = str(exc)
print(json.dumps({
    "cls": cls.__name__,
    "message": message,
    "materialised": "SCENARIOS" in vars(scenarios),
    "modules": sorted(m for m in sys.modules if m.startswith("navkit.sim.scenarios._")),
}))
"""


def test_names_resolve_without_importing_the_other_scenarios() -> None:
    done = subprocess.run(
        [sys.executable, "-c", _LAZY], capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr[-2000:]
    out = json.loads(done.stdout.strip().splitlines()[-1])
    assert out["cls"] == "Greedy" and not out["materialised"]
    assert "known: demo, diff-astar, greedy, indoor-nav, omni-apf, soccer" in out["message"]
    others = [m for m in out["modules"] if not m.startswith("navkit.sim.scenarios._greedy")]
    assert others == ["navkit.sim.scenarios._data"], out["modules"]
