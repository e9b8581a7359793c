"""Field D*'s unrolled neighbour loop compiles each helper once (review 38, FDSEARCH).

A lowered node's eight neighbours are eight calls of ``_lower_neighbour``,
LLVM-inlined with the ring index a known constant at each site (a fresh plan on
1024² random 20 % about 6 % faster, expansions unchanged). The index is passed
as ``zero + m``: written as the literals 0-7, numba compiled the helper once per
value, and ``_pairs_through`` nine times, 2.4 s more at first use. This test
(slow: a fresh process with an empty cache) lists what a first Field D* plan,
cost update and replan compile.
"""

from __future__ import annotations

import tempfile

import pytest

from kernel_signatures import compiled_signatures

_FIRST_USE = """
import os
os.environ["NUMBA_CACHE_DIR"] = %r  # empty: every kernel compiles (none loads)
import numpy as np
from navkit.planning import FieldDStar
costs = np.ones((30, 40))
costs[5:25, 20] = np.inf
planner = FieldDStar(costs)
planner.plan_cells((0, 0), (29, 39))
planner.update_costs([(10, 10)], [np.inf])
planner.replan()
"""


@pytest.mark.slow
def test_a_first_field_dstar_use_compiles_each_kernel_once() -> None:
    with tempfile.TemporaryDirectory(prefix="navkit-review38-") as cache:
        compiled = compiled_signatures(
            _FIRST_USE % cache,
            ["navkit.planning.grid._dstar_lite_kernels", "navkit.planning.grid._dstar_heap"],
        )
    assert len(compiled["_dstar_lite_kernels._lower_neighbour"]) == 1
    assert len(compiled["_dstar_lite_kernels._pairs_through"]) == 1
    # One compilation per kernel: no literal specialisation of the ring index.
    assert all(len(signatures) == 1 for signatures in compiled.values()), compiled
