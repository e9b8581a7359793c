"""The soccer player steps its controller by the time its command is held (review 27).

At 30 Hz of control on 100 Hz physics the simulation runs the controller every
3 or 4 steps; the player passed ``1 / 30`` s to
``PotentialFieldController.step`` every time, so each step's acceleration
limits and stall clock were up to a fifth off. It now passes
``Observation.dt`` (0.03 or 0.04 s).
"""

from __future__ import annotations

import math
from typing import Any

import pytest

from navkit.control import PotentialFieldController
from navkit.sim.scenarios import Soccer


def test_the_player_passes_the_held_time(monkeypatch: pytest.MonkeyPatch) -> None:
    seen: list[float] = []
    real_step = PotentialFieldController.step

    def spy(self: PotentialFieldController, *args: Any, **kwargs: Any) -> Any:
        seen.append(kwargs["dt"])
        return real_step(self, *args, **kwargs)

    monkeypatch.setattr(PotentialFieldController, "step", spy)
    scenario = Soccer(table_cells=200, duration=5.0)
    first = scenario.trials(1, seed=0)[0]  # attack, no opponent
    result = scenario.run_trial(first)
    assert result.trace is not None
    assert len(seen) > 100
    assert set(seen) == {0.03, 0.04}
    # The holds before the last add up to the time of the last control step, which
    # is within a hold of the end of the run.
    end = float(result.trace.times[-1])
    assert end - 0.04 - 1e-9 <= math.fsum(seen[:-1]) <= end + 1e-9
