"""The repulsion potential over several blocks of points (review 31, mutants).

``_PointRepulsion`` evaluates large problems in blocks of points (k-d tree pairs
per block). The block tests read the force only: the potential of a block not
starting at point 0 was never computed, so ``minlength=block.stop +
block.start`` for ``block.stop - block.start`` in ``_potential`` passed the
suite (it fails with a shape error on the second block). Oracle: Khatib's
closed form ``U = Σ ½ k (1/d - 1/d0)²`` over obstacles within ``d0``, summed
here with NumPy. Checked: the test fails on that mutant of ``_repulsion.py``
and passes on HEAD.
"""

from __future__ import annotations

import numpy as np

from navkit.planning.reactive import KhatibRepulsion


def test_the_potential_of_many_points_is_the_closed_form_sum() -> None:
    rng = np.random.default_rng(31)
    obstacles = rng.uniform(0.0, 10.0, size=(1000, 2))
    # 5000 points x 1000 obstacles: more pairs than one block holds (2**22 // 1000
    # points a block), so the points are split into two blocks.
    points = rng.uniform(0.0, 10.0, size=(5000, 2))
    k_rep, d0 = 0.7, 0.3
    field = KhatibRepulsion(obstacles, k_rep=k_rep, influence_radius=d0)
    # The closed form for points of both blocks (the second starts at point 4194).
    checked = np.r_[0:300, 4000:5000]
    chunk = points[checked]
    d = np.hypot(
        chunk[:, None, 0] - obstacles[None, :, 0], chunk[:, None, 1] - obstacles[None, :, 1]
    )
    near = d <= d0
    terms = np.where(near, 0.5 * k_rep * (1.0 / np.where(near, d, 1.0) - 1.0 / d0) ** 2, 0.0)
    expected = terms.sum(axis=1)
    assert np.count_nonzero(expected) > 100
    np.testing.assert_allclose(field.potential(points)[checked], expected, rtol=1e-12, atol=1e-15)
