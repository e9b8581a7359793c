"""Point repulsions against many obstacles query the k-d trees in few blocks (review 8)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
import scipy.spatial

from navkit.planning import KhatibRepulsion, PiecewiseRepulsion


@pytest.mark.parametrize(
    "field",
    [
        lambda obs: KhatibRepulsion(obs, k_rep=1.0, influence_radius=0.5),
        lambda obs: PiecewiseRepulsion(obs, delta=1.0, beta=1.0, spread=0.5),
    ],
)
def test_many_obstacles_take_few_tree_queries(field: Any, monkeypatch: pytest.MonkeyPatch) -> None:
    # 20k obstacles made blocks of 209 points (_TREE_BLOCK // m): 10 tree queries
    # for 2000 scattered points, each walking most of the obstacles' tree (a cost
    # growing with m²). Sized by the pairs in reach, one block holds them all.
    rng = np.random.default_rng(3)
    obstacles = rng.uniform(0.0, 50.0, (20_000, 2))
    points = rng.uniform(0.0, 50.0, (2000, 2))
    repulsion = field(obstacles)
    calls = []
    original = scipy.spatial.cKDTree.sparse_distance_matrix

    class Counting(scipy.spatial.cKDTree):  # type: ignore[misc]
        def sparse_distance_matrix(self, *args: Any, **kwargs: Any) -> Any:
            calls.append(self.n)
            return original(self, *args, **kwargs)

    monkeypatch.setattr(scipy.spatial, "cKDTree", Counting)
    force = repulsion.force(points)
    potential = repulsion.potential(points)
    assert len(calls) == 2  # one block each for force and potential
    # The same sums as the all-pairs evaluation, two points at a time.
    ref = np.concatenate([repulsion.force(points[i : i + 2]) for i in range(0, 200, 2)])
    ref_u = np.concatenate([repulsion.potential(points[i : i + 2]) for i in range(0, 200, 2)])
    np.testing.assert_allclose(force[:200], ref, rtol=1e-12, atol=0.0)
    np.testing.assert_allclose(potential[:200], ref_u, rtol=1e-12, atol=0.0)
