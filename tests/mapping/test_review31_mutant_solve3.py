"""The scan matcher's 3×3 Cholesky solve against NumPy (review 31, mutants).

``_solve3`` solves the Gauss-Newton system ``H step = g`` of the scan matcher.
The matcher iterates, so a wrong step still converged in the suite's cases:
sign and index mutants of the factorisation and of the substitutions (``a11 +
l10²``, ``h[2, 1] + l20 l10``, ``y1 + l21 step[2]`` and three index shifts)
passed it. Oracle: ``numpy.linalg.solve`` of ``H`` plus the documented ridge
(1e-9 of the largest diagonal entry). Checked: the test fails on those mutants
of ``_scan_matcher_kernels.py`` and passes on HEAD.
"""

from __future__ import annotations

import numpy as np

from navkit.mapping._scan_matcher_kernels import _solve3


def test_solve3_matches_numpy_on_positive_definite_systems() -> None:
    rng = np.random.default_rng(31)
    for _ in range(50):
        a = rng.normal(size=(3, 3))
        h = a @ a.T + 0.1 * np.eye(3)
        g = rng.normal(size=3)
        step = np.zeros(3)
        assert _solve3(h.copy(), g.copy(), step)
        ridge = 1e-9 * np.max(np.diag(h))
        expected = np.linalg.solve(h + ridge * np.eye(3), g)
        np.testing.assert_allclose(step, expected, rtol=1e-9, atol=1e-12)
