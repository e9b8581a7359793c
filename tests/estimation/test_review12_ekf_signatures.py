"""The general EKF's helpers are compiled once for every size (issue 17, review 12).

``ExtendedKalmanFilter`` runs a predict kernel per state size n and an update
kernel per pair (n, m), each with its sizes as compile-time constants. The work
(and the small matrix helpers) sits in functions those kernels call with the
sizes; passed as Python ints, numba typed the sizes as literals and compiled
every helper once per value (three times each for one 3-state filter with 1-
and 2-D measurements). Now they take plain int64 values: one compilation each
serves every size, and LLVM, inlining them, still sees the sizes as constants.

The test runs filters of two sizes with several measurement sizes in a fresh
process with an empty numba cache (a kernel loaded from the cache brings its
callees' code with it, so they would not show) and reads the signatures.
"""

from __future__ import annotations

from pathlib import Path

from kernel_signatures import compiled_signatures

SCRIPT = """
import os
os.environ["NUMBA_CACHE_DIR"] = {cache!r}  # before numba is imported: compile everything
import numpy as np
from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation import _ekf_kernels

for n, sizes in ((2, (1, 2)), (3, (1, 3))):
    ekf = ExtendedKalmanFilter(np.zeros(n), np.eye(n), angle_states=(n - 1,))
    jac = np.eye(n)
    jac[0, n - 1] = 0.1
    ekf.predict(lambda x: jac @ x, jac, 0.01 * np.eye(n))
    for m in sizes:
        h = np.eye(m, n)
        ekf.update(np.full(m, 0.1), lambda x: h @ x, h, 0.1 * np.eye(m),
                   angle_measurements=(0,), gate=50.0)
# The kernels themselves: one per size, each compiled once.
kernels = _ekf_kernels.kernel_dispatchers()  # (the filter calls their compiled entries)
assert len(kernels) == 6, len(kernels)
assert all(len(kernel.signatures) == 1 for kernel in kernels)
"""

HELPERS = (
    "_wrap", "_finite_mat", "_equal", "_mul", "_mul_t_lower", "_add_lower",
    "_positive_definite", "_mirror_checked", "_predict", "_update",
)  # fmt: skip


def test_every_ekf_helper_is_compiled_once_for_all_sizes(tmp_path: Path) -> None:
    signatures = compiled_signatures(
        SCRIPT.format(cache=str(tmp_path)), ["navkit.estimation._ekf_kernels"]
    )
    names = {name.rsplit(".", 1)[1]: sigs for name, sigs in signatures.items()}
    repeated = {name: sigs for name, sigs in names.items() if len(sigs) != 1}
    assert not repeated
    literal = {name: sigs for name, sigs in names.items() if "Literal" in sigs[0]}
    assert not literal
    assert set(HELPERS) <= set(names), sorted(names)
