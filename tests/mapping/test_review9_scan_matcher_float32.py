"""The scan matcher's single-precision ``exp`` stays within its documented error.

``_scan_matcher_kernels`` computes each cell's occupancy probability from its
float32 log-odds with a float32 ``exp`` (for speed) and documents ``M`` and its
gradient within 2e-8 of a float64 computation. The reference here is the
docstring's bilinear formula evaluated in float64 NumPy.
"""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

from navkit.mapping._scan_matcher_kernels import interpolate_batch


def _reference(logodds: np.ndarray, coords: np.ndarray) -> np.ndarray:
    with np.errstate(over="ignore"):  # exp(1e6) = inf: p = 0, as intended
        p = 1.0 / (1.0 + np.exp(-logodds.astype(np.float64)))
    r0 = np.floor(coords[:, 0]).astype(int)
    c0 = np.floor(coords[:, 1]).astype(int)
    b = coords[:, 0] - r0
    a = coords[:, 1] - c0
    p00, p01 = p[r0, c0], p[r0, c0 + 1]
    p10, p11 = p[r0 + 1, c0], p[r0 + 1, c0 + 1]
    m = (1 - b) * ((1 - a) * p00 + a * p01) + b * ((1 - a) * p10 + a * p11)
    d_col = (1 - b) * (p01 - p00) + b * (p11 - p10)
    d_row = (1 - a) * (p10 - p00) + a * (p11 - p01)
    return np.column_stack((m, d_row, d_col))


def test_probability_and_gradient_within_documented_error() -> None:
    rng = np.random.default_rng(2026)
    logodds = rng.uniform(-20.0, 20.0, (60, 60)).astype(np.float32)
    # Saturated cells too (exp overflows / underflows in float32, not in float64).
    logodds[rng.random((60, 60)) < 0.1] = 1e6
    logodds[rng.random((60, 60)) < 0.1] = -1e6
    logodds[rng.random((60, 60)) < 0.1] = 95.0
    logodds[rng.random((60, 60)) < 0.1] = -95.0
    coords = rng.uniform(0.0, 58.999, (20000, 2))
    out = np.empty((coords.shape[0], 3))
    interpolate_batch(logodds, coords, out)
    error = np.abs(out - _reference(logodds, coords))
    assert error.max() <= 2e-8


def test_saturated_free_cells_interpolate_as_python_too() -> None:
    """Log-odds far below -709 interpolate without an OverflowError.

    As Python (``NUMBA_DISABLE_JIT=1``) ``math.exp`` of such a cell's
    -log-odds raised where the compiled float32 ``exp`` gives inf; the kernels
    cap the argument where float32 already overflows, so both give p = 0 there
    (as Python about 2e-39) and the compiled results are unchanged.
    """
    rng = np.random.default_rng(7)
    logodds = np.full((40, 40), -1e4, dtype=np.float32)  # free beyond any exp
    logodds[:, 20:] = 50.0  # occupied, p = 1
    logodds[rng.random((40, 40)) < 0.05] = -800.0
    coords = rng.uniform(0.0, 38.999, (500, 2))
    out = np.empty((coords.shape[0], 3))
    interpolate_batch(logodds, coords, out)
    assert np.all(np.isfinite(out))
    np.testing.assert_allclose(out, _reference(logodds, coords), atol=1e-30)
    left = coords[:, 1] < 19.0  # between free cells only: M = 0 (2e-39 as Python)
    assert np.all(np.abs(out[left]) <= 1e-38)


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX subprocess environment")
def test_saturated_free_cells_interpolate_with_the_jit_disabled() -> None:
    # The check above, run as Python in a child (the suite runs compiled).
    env = {**os.environ, "NUMBA_DISABLE_JIT": "1"}
    code = (
        "import sys; sys.path.insert(0, sys.argv[1]); "
        "import test_review9_scan_matcher_float32 as t; "
        "t.test_saturated_free_cells_interpolate_as_python_too(); print('ok')"
    )
    here = os.path.dirname(os.path.abspath(__file__))
    done = subprocess.run(
        [sys.executable, "-c", code, here], env=env, capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == "ok"
