"""Soccer's ``max_speed`` option over its documented range: no false minimum in the attraction.

With ``K_att`` fixed at 2 while the cone's gradient ``m`` followed ``max_speed``, a top speed
of 1.2 m/s or less made the blended attraction pull *outward* just beyond its threshold
radius (0.5 m), outside the 0.45 m where the ball is taken: every attack and support game
stalled there, with no opponent at all.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.sim.scenarios import Soccer
from navkit.sim.scenarios._soccer_play import player_attraction
from navkit.sim.scenarios._soccer_table6 import radial_minima


@pytest.mark.parametrize("max_speed", [0.2, 0.5, 0.8, 1.0, 1.2, 1.5, 2.0, 3.0, 5.0])
def test_player_attraction_has_one_minimum_at_the_goal(max_speed: float) -> None:
    field = player_attraction(max_speed)
    lows, _ = radial_minima(field)
    assert lows.size == 1
    assert lows[0] < 0.01  # at the goal (within 1 cm), not on a ring
    # Inward everywhere between the ball-taking radius and 3 m: by at least 5 % of the top
    # speed (the default's own margin, 0.075 m/s at 1.5 m/s, at 0.51 m).
    r = np.linspace(0.2, 3.0, 2801)
    inward = -field.force(np.column_stack((r, np.zeros_like(r))))[:, 0]
    assert inward.min() >= 0.049 * max_speed


def test_default_attraction_unchanged() -> None:
    field = player_attraction(1.5)
    assert (field.k_att, field.m, field.threshold_radius, field.width) == (2.0, 1.5, 0.5, 0.15)


@pytest.mark.parametrize("max_speed", [0.8, 1.0])
def test_slow_robot_scores_without_opponents(max_speed: float) -> None:
    scenario = Soccer(max_speed=max_speed, table_cells=100, duration=60.0)
    trial = scenario.trials(1, seed=0)[0]
    assert trial.case == "attack, no opponent"
    values = scenario.run_trial(trial).values
    assert values["stalled"] == 0.0
    assert values["reached"] == 1.0


def test_table_notes_state_the_gain_used() -> None:
    result = Soccer(max_speed=1.0, table_cells=100).run(trials=1, seed=0)
    notes = " ".join(n for t in result.tables for n in t.notes)
    assert "K_att 1.33" in notes
    assert "no false minimum" in notes
