"""The paraboloid attraction's force is exactly zero at its goal (review 32, mutants).

``ParaboloidAttraction._force`` writes ``0.0 - 2 sx dx`` so that the force at
the goal is +0.0, not -0.0. A mutant writing ``1e-9 - 2 sx dx`` survived the
field tests, whose gradient checks compare with a tolerance: the force at the
goal was 1e-9 N along x. Oracle: the potential ``sx dx² + sy dy²`` has its
minimum at the goal, where its gradient is exactly zero. Checked: the test
fails on that mutant of ``_attraction.py`` and passes on HEAD.
"""

from __future__ import annotations

import numpy as np

from navkit.planning.reactive import ParaboloidAttraction


def test_the_force_at_the_goal_is_exactly_positive_zero() -> None:
    field = ParaboloidAttraction(goal_xy=(1.5, -2.0), k_att=3.0, c=2.0, a=0.5, b=4.0)
    force = field.force([1.5, -2.0])
    assert force.tolist() == [[0.0, 0.0]]
    assert not np.signbit(force).any()
