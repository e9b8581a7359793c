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

import json
import os
import subprocess
import sys
import tempfile

import pytest

_FIRST_USE = """
import json
import numpy as np
from numba.core import event
compiled = []
class _Listener(event.Listener):
    def on_start(self, ev):
        d = ev.data["dispatcher"]
        compiled.append((d.py_func.__module__, d.py_func.__qualname__, str(ev.data["args"])))
    def on_end(self, ev):
        pass
event.register("numba:compile", _Listener())
from navkit.planning import FieldDStar
costs = np.ones((30, 40))
costs[5:25, 20] = np.inf
planner = FieldDStar(costs)
planner.plan_cells((0, 0), (29, 39))
planner.update_costs([(10, 10)], [np.inf])
planner.replan()
print(json.dumps(compiled))
"""


@pytest.mark.slow
def test_a_first_field_dstar_use_compiles_each_kernel_once() -> None:
    with tempfile.TemporaryDirectory(prefix="navkit-review38-") as cache:
        out = subprocess.run(
            [sys.executable, "-c", _FIRST_USE],
            check=True, capture_output=True, text=True, timeout=600,
            env=dict(os.environ, NUMBA_CACHE_DIR=cache),
        )  # fmt: skip
    compiled = [tuple(row) for row in json.loads(out.stdout.strip().splitlines()[-1])]
    ours = [(module, name) for module, name, _ in compiled if module.startswith("navkit.")]
    kernels = "navkit.planning.grid._dstar_lite_kernels"
    assert (kernels, "_lower_neighbour") in ours
    assert (kernels, "_pairs_through") in ours
    # One compilation per kernel: no literal specialisation of the ring index.
    assert len(ours) == len(set(ours)), sorted(ours)
