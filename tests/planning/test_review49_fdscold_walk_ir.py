"""Field D*'s first use: how much LLVM IR numba emits for the path walk and polyline kernels.

numba's passes (translation, typing, lowering) cost a first use in proportion to
the IR they emit, and the walk and polyline kernels are over half of what a
first Field D* plan emits though they are not its hot loop (issue 17). Review
49 (FDSCOLD) passed them their buffers flat (a 2-D element access lowered to
about twice the instructions of a flat one) and the walk's helpers their arrays
and scalars one by one (the ``st``/``prm`` tuples were taken apart and rebuilt
at every helper call): 13,299 -> 11,874 instructions with numba 0.68.1. Review
53 (FDWALK) folded the straight corner step (``_descend``) and the helpers
``_edge_min``, ``_settled_value`` and ``_line_cost`` into ``_candidates``, one
loop with one value read and one row write: 11,874 (12,168 with ``_line_cost``,
which the list left out) -> 10,097. The count is
numba's own (its lowering output, before LLVM optimises it), the same
in every run of one numba version: other versions emit other counts, so the
budget is checked on numba 0.68.1 only.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from navkit._shared.jit import jit_disabled

#: A first plan, cost update and replan (the cold-start benchmark's Field D* entry),
#: with numba's lowering output counted per code library (a kernel's name).
_COUNT = """
import json
import numpy as np
from navkit._shared.jit import load_numba
load_numba()
from numba.core import codegen
counts = {}
add = codegen.CPUCodeLibrary.add_llvm_module
def counted(self, module):
    n = sum(len(list(block.instructions)) for fn in module.functions for block in fn.blocks)
    counts[self.name] = counts.get(self.name, 0) + n
    return add(self, module)
codegen.CPUCodeLibrary.add_llvm_module = counted
from navkit.planning import FieldDStar
costs = np.ones((10, 10))
costs[3:7, 5] = 3.0
planner = FieldDStar(costs)
planner.plan((0, 0), (10, 7))
planner.update_costs([(3, 1), (3, 2)], np.inf)
planner.replan()
print(json.dumps(counts))
"""

#: The path walk's kernels and the polyline kernel (its Python wrapper included).
_WALK = ("extract_path", "_candidates", "_polyline")

#: 10,291 with numba 0.68.1 after review 53 (FDWALK 10,097, FDWALK2's hypot
#: shortcuts +194; 11,874 after review 49, 13,299 before), plus room for small
#: changes.
_BUDGET = 10_500


def _numba_version() -> str:
    import numba

    return str(numba.__version__)


@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: nothing is compiled")
def test_the_walk_and_polyline_kernels_lower_to_at_most_the_budget(tmp_path: Path) -> None:
    # One release exactly: a patch release may lower differently, and CI takes the newest.
    if _numba_version() != "0.68.1":
        pytest.skip(f"the budget is numba 0.68.1's instruction count (numba {_numba_version()})")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))  # empty: everything compiles
    out = subprocess.run(
        [sys.executable, "-c", _COUNT], check=True, capture_output=True, text=True, env=env
    )
    counts: dict[str, int] = json.loads(out.stdout.strip().splitlines()[-1])
    assert set(_WALK) <= set(counts), counts
    # Every other kernel was compiled too (the search and its heap): nothing was loaded.
    assert {"settle", "change", "segment_cost"} <= set(counts), counts
    walk = sum(counts[name] for name in _WALK)
    assert walk <= _BUDGET, {name: counts[name] for name in _WALK}
