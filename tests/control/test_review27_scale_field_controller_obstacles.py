"""PotentialFieldController.step among very many obstacle points (the lens of scale).

Each step builds a new Khatib repulsion from the obstacles given. Beyond 2**18
points the field finds the pairs in reach with a k-d tree of every obstacle,
which pays off for a field queried at many points but not for the
controller's one query: the tree, built from scratch every step, cost
O(M log M) (a step among 300,000 points took 176 ms, among 10**6 609 ms,
against 9 and 41 ms when only the obstacles in reach, which the step already
finds, are handed to the field).

The step now builds the field from the rows within ``influence_radius`` only.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D
from navkit.planning import KhatibRepulsion


def test_step_among_many_far_obstacles_builds_no_tree(monkeypatch: pytest.MonkeyPatch) -> None:
    rng = np.random.default_rng(27)
    # 300,000 points 5-50 m away (beyond 2**18, where a field uses its tree)
    # and three within the influence radius.
    radius = rng.uniform(5.0, 50.0, 300_000)
    angle = rng.uniform(-np.pi, np.pi, 300_000)
    far = np.column_stack((radius * np.cos(angle), radius * np.sin(angle)))
    near = np.array([[0.3, 0.1], [-0.2, 0.4], [0.1, -0.35]])
    obstacles = np.concatenate((far[:100_000], near[:1], far[100_000:], near[1:]))
    given = obstacles.copy()
    trees: list[int] = []
    real_tree = KhatibRepulsion._tree

    def counted(self: Any) -> Any:
        trees.append(len(self.obstacles_xy))
        return real_tree(self)

    monkeypatch.setattr(KhatibRepulsion, "_tree", counted)
    pose, target = Pose2D(0.0, 0.0, 0.0), Pose2D(4.0, 1.0, 0.0)
    command = PotentialFieldController().step(pose, target, 0.05, obstacles=obstacles)
    alone = PotentialFieldController().step(pose, target, 0.05, obstacles=near)
    assert np.array_equal(obstacles, given)
    # The far points push nothing: the command is the one the near points give
    # (summed in the order given, as for fewer obstacles).
    assert command == alone
    assert trees == []
