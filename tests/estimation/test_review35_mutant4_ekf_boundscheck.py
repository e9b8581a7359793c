"""The EKF's kernels run with numba's bounds checks on (review 35, MUTANT4).

numba does not check array indices by default. The EKF kernels take views of
one ``state`` array for x, P, Q and their scratch blocks (``state[2n+2 : 3n+2]``
and so on); mutants that cut a view one row short (Q, F P or the predicted P's
block ending a row early, or the predicted P's block starting a row late, over
the factorisation's scratch) survived every test, since without bounds checks
the missing row is read from the same memory (or from scratch rows not yet
written). Here the predict and update kernels of three states (one to three
components), the positive-definite Q kernel and the cancelled-update and gated
paths run in a fresh process with ``NUMBA_BOUNDSCHECK=1`` and an empty cache
of their own (about 10 s of compilation), where any index outside a view
raises ``IndexError``. Each of those mutants fails this test (checked when it
was written).
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from subprocess_probe import bounds_checked

_SCRIPT = textwrap.dedent(
    """
    import numpy as np
    from navkit.estimation import ExtendedKalmanFilter

    for n in (3,):
        ekf = ExtendedKalmanFilter(np.linspace(0.1, 0.3, n), np.eye(n), angle_states=(0,))
        f = np.eye(n)
        if n > 1:
            f[0, 1] = 0.1
        q_diag = 0.01 * np.eye(n)
        q_cv = q_diag.copy()
        if n > 1:
            q_cv[0, 0], q_cv[0, 1], q_cv[1, 0], q_cv[1, 1] = 1 / 3, 0.5, 0.5, 1.0
        for step in range(4):
            ekf.predict(lambda x: f @ x, f, q_cv if step % 2 else q_diag)
            for m in range(1, n + 1):
                h = np.eye(m, n)
                z = h @ ekf.x + 0.01 * (step + 1)
                ekf.update(z, lambda x: h @ x, h, 0.1 * np.eye(m), angle_measurements=(0,))
        h = np.eye(1, n)
        ekf.update(h @ ekf.x + 1e-3, lambda x: h @ x, h, [[1e-12]])  # a variance shrinks
        gated = ekf.update(h @ ekf.x + 1e3, lambda x: h @ x, h, [[1e-6]], gate=9.0)
        assert not gated.accepted
        assert np.isfinite(ekf.x).all() and np.isfinite(ekf.P).all()
    print("in bounds")
    """
)


@pytest.mark.slow  # exhaustive (review 42: the default suite's budget)
def test_the_ekf_kernels_stay_in_bounds(tmp_path: Path) -> None:
    assert bounds_checked(_SCRIPT, tmp_path) == ["in bounds"]
