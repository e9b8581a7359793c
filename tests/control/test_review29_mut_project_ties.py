"""Review 29 (MUTATE): the path projection's documented tie rule, smallest ``s`` wins.

A mutant that let later segments win ties (``d2 <= best_d2`` in the kernel
``project``) passed the whole control suite: every earlier test's nearest point
was unique. Here the robot is exactly equidistant from the outgoing and the
returning leg of a U-turn (all coordinates and distances exact in binary), so
only the tie rule decides; a tracker that took the later leg would skip the turn.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.control._path_following import Polyline

# Out along y = 0, up, back along y = 2: arc lengths 0-4, 4-6, 6-10.
_U_TURN = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0]])


@pytest.mark.parametrize("s_from", [0.0, 1.0, 2.0])
def test_a_point_equidistant_from_both_legs_projects_onto_the_first(s_from: float) -> None:
    # (2, 1) is 1 m from (2, 0) at s = 2 and from (2, 2) at s = 8, and 2 m from the
    # middle leg: the smallest s among the two nearest points is 2.
    line = Polyline(_U_TURN)
    assert line.project(2.0, 1.0, s_from, line.length) == (2.0, 1.0)


def test_the_tie_rule_holds_for_every_point_on_the_midline() -> None:
    # Each point (x, 1) with 0 <= x <= 4 is 1 m from both long legs (at s = x and
    # s = 10 - x) and 4 - x from the middle leg: the first leg wins while 4 - x > 1.
    line = Polyline(_U_TURN)
    for x in (0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 2.75):
        assert line.project(x, 1.0, 0.0, line.length) == (x, 1.0)
