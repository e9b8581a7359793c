"""RegulatedPurePursuit on a path with a small loop: the documented Nav2-like cut.

The path runs along +x, makes a full counter-clockwise circle of radius ``R``
tangent to the axis at x = 1 (reaching y = 2R), and goes on along +x. Nav2's
lookahead point is the first pose at least ``L`` from the robot and its
closest-pose search jumps past short loops, so a loop inside the lookahead circle
is cut; the docstring states when navkit's tracker cuts one and when it drives it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.control import RegulatedPurePursuit


def loop_path(radius: float, n: int = 81) -> np.ndarray:
    t = np.linspace(0.0, 2.0 * math.pi, n)[1:-1]
    loop = np.column_stack([1.0 + radius * np.sin(t), radius * (1.0 - np.cos(t))])
    before = np.column_stack([np.linspace(0.0, 1.0, 11), np.zeros(11)])
    after = np.column_stack([np.linspace(1.0, 3.0, 21), np.zeros(21)])
    return np.vstack([before, loop, after])


def highest_y(closed_loop: Callable[..., Any], radius: float, **options: Any) -> float:
    run = closed_loop(RegulatedPurePursuit(**options), loop_path(radius), (0.0, 0.0, 0.0),
                      t_max=60.0)
    assert run.done
    assert run.goal_error() <= 0.25
    return float(run.poses[:, 1].max())


@pytest.mark.parametrize("radius", [0.1, 0.15, 0.3])
def test_default_lookahead_cuts_loops_inside_it(closed_loop: Callable[..., Any],
                                                radius: float) -> None:
    # L reaches 0.75-0.9 m at speed: the loop lies inside the circle and is skipped.
    assert highest_y(closed_loop, radius) < 0.2 * (2.0 * radius)


def test_short_lookahead_drives_a_loop_twice_as_wide(closed_loop: Callable[..., Any]) -> None:
    top = highest_y(closed_loop, 0.3, min_lookahead=0.3, max_lookahead=0.3)
    assert top == pytest.approx(0.6, abs=0.03)


def test_a_loop_within_the_search_detour_is_cut_by_any_lookahead(
    closed_loop: Callable[..., Any],
) -> None:
    # Radius 0.1 m: the loop never leads 0.25 m farther than the closest point, so the
    # closest-point search passes through it even with a 5 cm lookahead.
    assert highest_y(closed_loop, 0.1, min_lookahead=0.05, max_lookahead=0.05) < 0.05
    # A loop wide enough for both rules is driven round with that lookahead.
    assert highest_y(closed_loop, 0.2, min_lookahead=0.05, max_lookahead=0.05) == pytest.approx(
        0.4, abs=0.03)
