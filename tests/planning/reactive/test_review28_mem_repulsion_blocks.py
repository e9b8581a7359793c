"""Point repulsions against 10**5+ obstacles evaluate bounded blocks of pairs (review 28)."""

from __future__ import annotations

import numpy as np

from memory_peak import peak_bytes
from navkit.planning import KhatibRepulsion


def test_many_pairs_in_reach_peak_memory_is_bounded() -> None:
    # 250k obstacles at 25 per m², reach 1 m: about 78 pairs in reach per point,
    # 4.05M pairs for 52k points. One block of them all took 430 MB (615 MB at
    # 10**6 obstacles); blocks of 1M pairs, their locals dropped before
    # evaluation, peak at 145 MB whatever the number of pairs.
    rng = np.random.default_rng(28)
    obstacles = rng.uniform(0.0, 100.0, (250_000, 2))
    points = rng.uniform(0.0, 100.0, (52_000, 2))
    field = KhatibRepulsion(obstacles, k_rep=1.0, influence_radius=1.0)
    peak, force = peak_bytes(lambda: field.force(points))
    assert peak < 300e6, f"peak {peak / 1e6:.0f} MB"
    # The same sums as a call on some of those points alone (other blocks, another tree).
    np.testing.assert_allclose(force[:2000], field.force(points[:2000]), rtol=1e-12, atol=0.0)
    assert np.isfinite(force).all()
