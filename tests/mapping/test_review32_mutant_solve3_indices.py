"""The scan matcher's 3×3 solve reads only its 3×3 and 3-element inputs (review 32, mutants).

Review 31's test of ``_solve3`` against ``numpy.linalg.solve`` runs the
compiled kernel, which does not check indices: a mutant reading ``h[3, 1]``
or ``step[3]`` (one past the end) read whatever memory lay there and passed
or failed by chance. Here the kernel's own Python source runs on the same
systems (``py_func``: NumPy checks every index, as ``NUMBA_DISABLE_JIT``
would), against the same oracle: ``numpy.linalg.solve`` of ``H`` plus the
documented ridge (1e-9 of the largest diagonal entry), and ``h`` and ``g``
unchanged. Checked: the test fails on the index mutants of
``_scan_matcher_kernels.py``'s ``_solve3`` (every ``2`` and ``1`` index one
higher), on those making a threshold absolute or ``a00 >= 0``, and on the
one checking ``step[1]`` for ``step[0]``'s finiteness, and passes on HEAD.
(Checking ``step[0]`` twice is equivalent: back-substitution carries an
infinite ``step[2]`` or ``step[1]`` into ``step[0]`` as inf or NaN.)
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.mapping._scan_matcher_kernels import _solve3


def test_the_python_source_matches_numpy_and_reads_in_bounds() -> None:
    solve = _solve3.py_func
    rng = np.random.default_rng(32)
    for _ in range(50):
        a = rng.normal(size=(3, 3))
        h = a @ a.T + 0.1 * np.eye(3)
        g = rng.normal(size=3)
        h_in, g_in = h.copy(), g.copy()
        step = np.zeros(3)
        assert solve(h, g, step)
        ridge = 1e-9 * np.max(np.diag(h))
        expected = np.linalg.solve(h + ridge * np.eye(3), g)
        np.testing.assert_allclose(step, expected, rtol=1e-9, atol=1e-12)
        np.testing.assert_array_equal(h, h_in)
        np.testing.assert_array_equal(g, g_in)


def test_a_tiny_but_positive_definite_system_is_solved() -> None:
    # Every threshold of the factorisation is relative (the ridge, the pivots' 1e-12):
    # the system scaled by 1e-12 is solved as well, to the scaled answer. Mutants
    # making a threshold absolute (``a00 > 1e-9``, ``1e-12 / a11``) refused it.
    solve = _solve3.py_func
    rng = np.random.default_rng(320)
    for scale in (1e-12, 1e-30, 1e12):
        a = rng.normal(size=(3, 3))
        h = (a @ a.T + 0.1 * np.eye(3)) * scale
        g = rng.normal(size=3)
        step = np.zeros(3)
        assert solve(h, g, step)
        ridge = 1e-9 * np.max(np.diag(h))
        expected = np.linalg.solve(h + ridge * np.eye(3), g)
        np.testing.assert_allclose(step, expected, rtol=1e-9)


def test_a_zero_system_is_refused() -> None:
    # The Hessian of a scan that sees no slope: no pivot at all, so no step (False),
    # never a division by the zero pivot.
    step = np.zeros(3)
    assert not _solve3.py_func(np.zeros((3, 3)), np.ones(3), step)
    assert not _solve3(np.zeros((3, 3)), np.ones(3), step)


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_a_step_that_overflows_is_refused(axis: int) -> None:
    # Positive definite, but g / h overflows float64 along ``axis`` alone: the step
    # is no solution, whichever of its components is the infinite one.
    h = np.eye(3)
    h[axis, axis] = 1e-12
    g = np.zeros(3)
    g[axis] = 1e300
    step = np.zeros(3)
    # As Python the divisions are NumPy scalars', which warn where the kernel does not.
    with np.errstate(over="ignore", invalid="ignore"):
        assert not _solve3.py_func(h, g, step)
    assert math.isinf(step[axis])
    step = np.zeros(3)
    assert not _solve3(h, g, step)
    assert math.isinf(step[axis])
