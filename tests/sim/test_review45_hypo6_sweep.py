"""keep_traces changes nothing but the traces, whatever the seeds (review 45, HYPO6).

test_review45_trace_memory checks one seed per registered scenario; here random
base seeds, sequences of seeds and trial counts, by ``Scenario.run`` and by
``sweep``, on the two scenarios that need no data folder.
"""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.sim import Scenario, ScenarioResult, sweep
from scenario_results import SMALL, comparable

_SCENARIOS: dict[str, Scenario] = {name: SMALL[name]() for name in ("demo", "omni-apf")}
_SEEDS = st.integers(0, 2**64 - 1)


@settings(max_examples=15, deadline=None)
@given(
    name=st.sampled_from(sorted(_SCENARIOS)),
    trials=st.integers(1, 3),
    seeds=st.one_of(_SEEDS, st.lists(st.integers(0, 2**63), min_size=1, max_size=3)),
    by_sweep=st.booleans(),
)
def test_without_traces_the_result_is_the_same_but_the_traces(
    name: str, trials: int, seeds: int | list[int], by_sweep: bool
) -> None:
    scenario = _SCENARIOS[name]

    def run(keep: bool) -> ScenarioResult:
        if isinstance(seeds, list):  # one base seed per trial index
            return sweep(scenario, seeds=seeds, workers=1, keep_traces=keep)
        if by_sweep:
            return sweep(scenario, trials=trials, seeds=seeds, workers=1, keep_traces=keep)
        return scenario.run(trials, seed=seeds, keep_traces=keep)

    full, lean = run(True), run(False)
    assert all(r.trace is not None for r in full.trials)
    assert all(r.trace is None for r in lean.trials) and lean.traces == ()
    assert comparable(lean) == comparable(full)
