"""The mapping kernels' first use compiles none of numba's builtin overloads (review 51).

Issue 17 (first use with an empty numba cache): numba compiles each call of
the ``int``, ``min`` and ``max`` builtins as an overload of its own, once per
argument types and process. ``navkit warmup`` compiled two, both
``int(float64)`` in the scan matcher's kernels: the bilinear interpolation's
cell of a point (``_interpolate``, LLVM-inlined into ``accumulate``) and the
correlative search's nearest cell. They are ``np.int64`` now: the same
truncation (numba lowers both as one ``fptosi``), and the same machine code
for ``accumulate``, ``match_level`` and ``correlative_search_kernel``
(numba 0.68.1, the assembly compared line for line but for block labels).

Checked here: in a fresh process with an empty cache, the ``mapping`` step of
``navkit warmup`` compiles the scan matcher's kernels and no builtin overload;
and the interpolation truncates a coordinate to its cell as ``int`` does,
also a hair below a cell centre, where rounding instead would pick the next cell.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from navkit._shared.jit import jit_disabled
from navkit.mapping._scan_matcher_kernels import interpolate_batch
from subprocess_probe import COMPILES_LISTED, cold_outcome

_FIRST_USE = COMPILES_LISTED + """
import json
from navkit.sim import warmup
warmup(workers=1, only=["mapping"])
print(json.dumps(compiled))
"""


@pytest.mark.skipif(jit_disabled(), reason="nothing is compiled with the JIT disabled")
def test_mapping_first_use_compiles_no_builtin_overload() -> None:
    compiled = [tuple(row) for row in cold_outcome(_FIRST_USE)]
    ours = {name for module, name in compiled if module == "navkit.mapping._scan_matcher_kernels"}
    # The kernels that called int() were compiled here (the interpolation inlined by LLVM).
    for kernel in ("_interpolate", "accumulate", "match_level", "correlative_search_kernel"):
        assert kernel in ours, sorted(ours)
    builtins = [f"{module}.{name}" for module, name in compiled if module.startswith("numba.")]
    assert builtins == [], builtins


def _bilinear(logodds: np.ndarray, row: float, col: float) -> tuple[float, float, float]:
    """``(M, ∂M/∂row, ∂M/∂col)`` inside the map's centres, the cell found by ``int()``."""
    p = 1.0 / (1.0 + np.exp(-logodds.astype(np.float64)))
    r0, c0 = int(row), int(col)
    b, a = row - r0, col - c0
    p00, p01, p10, p11 = p[r0, c0], p[r0, c0 + 1], p[r0 + 1, c0], p[r0 + 1, c0 + 1]
    m = (1 - b) * ((1 - a) * p00 + a * p01) + b * ((1 - a) * p10 + a * p11)
    d_row = (1 - a) * (p10 - p00) + a * (p11 - p01)
    d_col = (1 - b) * (p01 - p00) + b * (p11 - p10)
    return float(m), float(d_row), float(d_col)


def test_interpolation_truncates_coordinates_to_their_cell() -> None:
    rng = np.random.default_rng(51)
    logodds = rng.normal(0.0, 3.0, (6, 7)).astype(np.float32)
    # A hair below a centre the cell is the one before it: M is continuous there,
    # but its gradient across that line is not (the next cell's slope differs).
    below = np.nextafter(np.arange(1.0, 5.0), 0.0)  # 0.999..., 1.999..., ...
    coords = np.array([[r, c] for r in [*below, 0.0, 2.5, 4.0] for c in [*below, 0.0, 3.25, 5.0]])
    out = np.empty((coords.shape[0], 3))
    interpolate_batch(logodds, coords, out)
    expected = np.array([_bilinear(logodds, row, col) for row, col in coords])
    # exp runs in float32 in the kernel (see its module notes): agreement to about
    # 1e-7, while the neighbouring cells' slopes differ by 0.01 or more.
    np.testing.assert_allclose(out, expected, rtol=0.0, atol=1e-6)
