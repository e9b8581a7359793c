"""A Khatib scan beam shorter than 1e-9 m pushes as one of 1e-9 m (review 31, mutants).

``repulsive_force_from_scan`` documents the saturation (as ``KhatibRepulsion``):
a beam nearer than ``MIN_DISTANCE`` = 1e-9 m pushes with the finite force of
one at 1e-9 m, ``k_rep (1e9 - 1/d0) 1e18``. No test read the force of such a
beam, so saturating at 1.02e-9 m (``0.98 / min_distance`` in the kernel) and
dropping every beam up to 1e-9 m (``r > 1e-9`` for ``r > 0.0``) passed the
suite; so did dropping them from the piecewise sum, where any beam nearer than
``obstacle_radius`` pushes with ``delta``. Checked: the tests fail on those
three mutants of ``_scan_repulsion_kernels.py`` and pass on HEAD.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping import LaserScan
from navkit.planning.reactive import (
    piecewise_repulsive_force_from_scan,
    repulsive_force_from_scan,
)


@pytest.mark.parametrize("r", [1e-9, 5e-10, 1e-15])
def test_a_beam_nearer_than_a_nanometre_pushes_as_one_at_a_nanometre(r: float) -> None:
    k_rep, d0 = 2.0, 1.5
    # The closed form at d = 1e-9 m, pushing away from the beam (angle 0: along -x).
    push = k_rep * (1e9 - 1.0 / d0) * 1e18
    scan = LaserScan(
        np.array([r]), angle_min=0.0, angle_increment=0.1, range_min=0.0, range_max=9.0
    )
    force = repulsive_force_from_scan(scan, k_rep=k_rep, influence_radius=d0)
    np.testing.assert_allclose(force, [-push, 0.0], rtol=1e-12, atol=0.0)


def test_a_beam_just_beyond_a_nanometre_is_not_saturated() -> None:
    k_rep, d0, r = 1.0, 1.0, 1.01e-9
    push = k_rep * (1.0 / r - 1.0 / d0) / (r * r)
    scan = LaserScan(
        np.array([r]), angle_min=0.0, angle_increment=0.1, range_min=0.0, range_max=9.0
    )
    force = repulsive_force_from_scan(scan, k_rep=k_rep, influence_radius=d0)
    np.testing.assert_allclose(force, [-push, 0.0], rtol=1e-12, atol=0.0)


@pytest.mark.parametrize("r", [1e-9, 5e-10, 1e-300])
def test_a_piecewise_beam_nearer_than_a_nanometre_pushes_with_delta(r: float) -> None:
    scan = LaserScan(
        np.array([r]), angle_min=0.5, angle_increment=0.1, range_min=0.0, range_max=9.0
    )
    force = piecewise_repulsive_force_from_scan(
        scan, delta=3.0, beta=1.0, obstacle_radius=0.5, spread=1.0
    )
    np.testing.assert_allclose(force, [-3.0 * np.cos(0.5), -3.0 * np.sin(0.5)], rtol=1e-12)
