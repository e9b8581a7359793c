"""The scan matcher past the map's edge reads unknown cells (review 50, FOUND2).

``M`` read 0 with no gradient past the map's edge (Hector SLAM's value for a
point out of its map's bounds, whose maps are wide margins of unknown cells). A
room whose walls lie in its edge cells' outer halves then matched worse than
the same map padded with unknown cells as soon as the guess put points past
the edge: 16-28 mm mean error (32-38 mm worst) from guesses 1-4 cm off with
walls 0.05 cell inside the edge, against 3-4 mm padded, every match
``"converged"``. The cells past the edge now count as unknown without end: the
tight map is the padded one.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping import ScanMatcher
from navkit.mapping._scan_matcher_kernels import correlative_search

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_review47_degen_matcher_edges import _RES, _room, _scan


@pytest.mark.parametrize(("inset", "spread"), [(0.05, 0.02), (0.05, 0.04), (0.2, 0.02)])
def test_a_tight_map_matches_as_the_padded_one_from_guesses_off_the_edge(
    inset: float, spread: float
) -> None:
    rng = np.random.default_rng(5002)
    tight, padded = _room(0), _room(8)
    matcher = ScanMatcher()
    errors = []
    for _ in range(10):
        x, y, theta = rng.uniform(0.6, 1.4), rng.uniform(0.6, 1.4), rng.uniform(-3.0, 3.0)
        scan = _scan(x, y, theta, inset)
        guess = (
            x + rng.normal(0, spread),
            y + rng.normal(0, spread),
            theta + rng.normal(0, spread),
        )
        found = matcher.match(tight, scan, guess)
        reference = matcher.match(padded, scan, guess)
        assert found.reason == reference.reason == "converged"
        # The same pose as the padded map's (to rounding: the frames differ by the
        # margin) and the same score.
        assert math.hypot(found.pose.x - reference.pose.x, found.pose.y - reference.pose.y) <= 1e-9
        assert found.pose.theta == pytest.approx(reference.pose.theta, abs=1e-9)
        assert found.score == pytest.approx(reference.score, abs=1e-9)
        errors.append(math.hypot(found.pose.x - x, found.pose.y - y))
    # Walls drawn on whole cells: within a fifth of a cell of the truth (before:
    # 16-28 mm mean at these insets and spreads, on 5 cm cells).
    assert max(errors) <= 0.2 * _RES


def test_the_correlative_search_takes_off_map_points_as_unknown() -> None:
    # A map of unknown cells: a point off it costs what a point on it does, so the
    # search has no reason to move the points onto the map (before: a point off
    # the map cost 1, on unknown cells 1/4, and the search moved the scan).
    unknown = np.zeros((10, 10), dtype=np.float32)
    points = np.array([[0.45, 0.0], [0.0, 0.45], [-0.45, 0.0], [0.0, -0.45]])
    start = np.array([0.1, 0.5, 0.0])  # the left point 0.35 m off the map
    pose = start.copy()
    cost = correlative_search(unknown, 0.0, 0.0, 0.0, 0.1, points, pose, 3, 0.1, 2, 0.1, 0.0, 0.0)
    assert cost == 0.25
    assert pose.tolist() == start.tolist()
