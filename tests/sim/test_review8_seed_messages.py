"""A scenario's seed is refused under the caller's name, and huge seeds are shortened."""

from __future__ import annotations

import pytest

from navkit.sim import sweep
from navkit.sim.scenarios import Demo


@pytest.mark.parametrize("bad", [-1, 2**64, "3", 1.5, [1, 2]])
def test_trials_and_run_name_seed(bad: object) -> None:
    # trials() said "base must ..." (trial_seed's parameter), run() "seeds must ...".
    for call in (Demo().trials, Demo().run):
        with pytest.raises((TypeError, ValueError), match=r"^seed must be"):
            call(1, seed=bad)  # type: ignore[arg-type]


def test_sweep_shortens_a_huge_seed() -> None:
    with pytest.raises(ValueError, match="seeds must be in") as info:
        sweep(Demo(), trials=1, seeds=10**400)
    assert len(str(info.value)) < 100
