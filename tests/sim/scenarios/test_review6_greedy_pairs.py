"""Greedy refuses start/goal pairs without a route when built, not after a whole run."""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

import pytest

from navkit.sim.scenarios import Greedy
from navkit.sim.scenarios import _greedy as greedy_module
from navkit.sim.scenarios._greedy import MAP

GOOD = ((-2.0, -0.5), (-1.0, -0.5))


@pytest.mark.parametrize(
    ("bad", "reason"),
    [
        (((0.0, 0.0), (1.0, 0.0)), "start"),  # the centre pillar
        (((1.27, -0.88), (1.5, 1.5)), "start"),  # the body grazes a pillar, A*'s cell is free
        (((-2.0, -0.5), (20.0, 0.5)), "goal .* outside the map"),
        (((-2.0, -0.5), (-1.1, -0.95)), "goal .* obstacle"),
    ],
)
def test_a_pair_without_a_route_is_refused_when_built(
    shared_data: Path, bad: Any, reason: str
) -> None:
    with pytest.raises(ValueError, match=rf"pairs\[1\]: .*{reason}"):
        Greedy(data_dir=str(shared_data), pairs=[GOOD, bad])


def test_good_pairs_are_accepted(shared_data: Path) -> None:
    assert Greedy(data_dir=str(shared_data), pairs=[GOOD]).pairs == (GOOD,)


def test_a_map_found_only_at_run_time_is_checked_before_the_run(
    tmp_path: Path, shared_data: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    scenario = Greedy(data_dir=str(tmp_path), pairs=[((0.0, 0.0), (1.0, 0.0))])  # no map yet
    source = (shared_data / MAP).parent
    shutil.copytree(source, tmp_path / Path(MAP).parent)

    def no_run(*args: object, **kwargs: object) -> None:
        raise AssertionError("the simulation was built for a pair without a route")

    monkeypatch.setattr(greedy_module, "Simulation", no_run)
    with pytest.raises(ValueError, match=r"pairs\[0\]: .*start"):
        scenario.run_trial(scenario.trials(1)[0])
