"""Trial seeds never coincide for different (base, case, trial) triples, large values included.

NumPy's SeedSequence cuts each int into 32-bit words and pads the whole to four
words with zeros, so feeding it the three values as they are made
``trial_seed(2**32, 0, k)`` equal ``trial_seed(0, 1, k)``: one sweep with
``seeds=[2**32, 0]`` ran two trials of one case on the same seed.
"""

from __future__ import annotations

from collections.abc import Sequence

from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.sim import Scenario, ScenarioResult, Table, Trial, TrialResult, sweep, trial_seed

_WIDE = st.integers(0, 2**64 - 1)
_SMALL = st.integers(0, 3)


class _Cases(Scenario):
    """Three cases whose trials report their own seeds (no simulation)."""

    name = "seed-cases"
    title = "trials reporting their seeds"
    paper = "none"
    default_trials = 2

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        return (("a", trials), ("b", trials), ("c", trials))

    def run_trial(self, trial: Trial) -> TrialResult:
        return TrialResult(trial, {"seed_bits": float(trial.seed % 2**20)})

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        rows = tuple((r.trial.case, r.values["seed_bits"]) for r in results)
        table = Table("seeds", ("case", "bits"), rows)
        return ScenarioResult(self.name, seed, tuple(results), (table,))


def test_a_sweep_with_a_large_and_a_small_base_seed_gives_every_trial_its_own_seed() -> None:
    result = sweep(_Cases(), seeds=[2**32, 0], workers=1)
    seeds = [r.trial.seed for r in result.trials]
    assert len(seeds) == 6
    assert len(set(seeds)) == len(seeds)


def test_base_seeds_beyond_32_bits_do_not_alias_a_later_case() -> None:
    for hi in range(1, 4):
        for low in (0, 5, 2**32 - 1):
            for k in range(3):
                assert trial_seed(low + hi * 2**32, 0, k) != trial_seed(low, hi, k)
                assert trial_seed(low, 0, k + hi * 2**32) != trial_seed(low, 0, k)
                assert trial_seed(low, hi * 2**32, k) != trial_seed(low, 0, hi)


@settings(max_examples=60, deadline=None)
@given(_WIDE, _SMALL, _SMALL, _WIDE, _SMALL, _SMALL)
def test_distinct_triples_have_distinct_seeds(
    b1: int, c1: int, k1: int, b2: int, c2: int, k2: int
) -> None:
    if (b1, c1, k1) != (b2, c2, k2):
        assert trial_seed(b1, c1, k1) != trial_seed(b2, c2, k2)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**31), _SMALL, _SMALL)
def test_wide_triples_never_meet_their_split_words(low: int, hi: int, k: int) -> None:
    # The words SeedSequence saw for (low + hi * 2**32, c, k) were those of (low, hi, c, k).
    wide = trial_seed(low + (hi + 1) * 2**32, 0, k)
    assert wide != trial_seed(low, hi + 1, 0)
    assert wide != trial_seed(low, hi + 1, k)
