"""A* and JPS first use: the helpers rewritten to compile less give the same values.

Issue 17 (any entry point's first use <= 3 s with an empty numba cache): the
grid searches no longer call the ``min``/``max``/``int`` builtins in their
kernels (numba compiles each as an overload of its own on first use) but
selects and ``np.int64``, and the heap's sift-down is compiled once rather
than copied into each heap operation that uses it. These tests check that the
rewritten helpers compute exactly what the builtins did, and (slow, in a
fresh process with an empty cache) that a first use of A* and of jump point
search compiles none of those builtin overloads and each kernel once.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.planning.grid._astar_kernels import _cells_to_goal
from navkit.planning.grid._limits import INF_BITS, _scan_cost_bits
from navkit.planning.grid._search_heap import node_of, tie_key

_COORD = st.integers(-(2**31), 2**31 - 1)


@settings(max_examples=300, deadline=None)
@given(_COORD, _COORD, _COORD, _COORD, st.booleans())
def test_cells_to_goal_equals_the_min_max_formula(
    r: int, c: int, gr: int, gc: int, octile: bool
) -> None:
    dr, dc = abs(r - gr), abs(c - gc)
    expected = max(dr, dc) + (math.sqrt(2.0) - 1.0) * min(dr, dc) if octile else float(dr + dc)
    got = _cells_to_goal(r, c, gr, gc, octile)
    assert got == expected  # the same operations: bit for bit


@settings(max_examples=300, deadline=None)
@given(
    st.one_of(
        st.floats(0.0, 2.0**17, allow_nan=False, exclude_max=True),
        st.sampled_from([0.0, 1.0 / 16, 65535.9375, 65536.0, 2.0**17 - 1.0 / 16]),
    ),
    st.integers(0, 2**32 - 1),
)
def test_tie_key_quantises_and_keeps_the_node(tie: float, node: int) -> None:
    # No saturation since review 38 (it was at 16 tie = 2**20 - 1): a search
    # picks a resolution that keeps every tie of its grid below 2**21
    # (tests/planning/grid/test_review38_astartie_tie_key_range.py).
    expected = math.floor(tie * 16.0) * float(2**32) + node
    key = tie_key(tie, node, 16.0)
    assert key == expected
    assert node_of(key) == node


@settings(max_examples=200, deadline=None)
@given(
    st.lists(
        st.one_of(st.integers(-(2**63), 2**63 - 1), st.just(INF_BITS)), min_size=1, max_size=300
    )
)
def test_cost_scan_equals_numpy_min_and_max(values: list[int]) -> None:
    bits = np.array(values, dtype=np.int64)
    before = bits.copy()
    lo, hi = _scan_cost_bits(bits, INF_BITS)
    finite = bits[bits != INF_BITS]
    assert lo == bits.min()
    assert hi == (max(int(finite.max()), -1) if finite.size else -1)
    assert np.array_equal(bits, before)


def test_cost_scan_of_real_costs_orders_them_as_floats() -> None:
    costs = np.array([3.0, 1.0, np.inf, 2.5, 1e6, np.inf])
    lo, hi = _scan_cost_bits(costs.view(np.int64), INF_BITS)
    assert np.array([lo, hi], dtype=np.int64).view(np.float64).tolist() == [1.0, 1e6]


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
from navkit.planning import astar
costs = np.ones((40, 50))
costs[5:30, 20] = np.inf
astar(costs, (0, 0), (39, 49))
astar(costs, (0, 0), (39, 49), method="jps")
astar(costs, (0, 0), (39, 49), method="jps", corner_cutting=True)
print(json.dumps(compiled))
"""


@pytest.mark.slow
def test_first_use_compiles_each_kernel_once_and_no_builtin_overload() -> None:
    with tempfile.TemporaryDirectory(prefix="navkit-review16-") as cache:
        out = subprocess.run(
            [sys.executable, "-c", _FIRST_USE],
            check=True, capture_output=True, text=True,
            env=dict(os.environ, NUMBA_CACHE_DIR=cache),
        )  # fmt: skip
    compiled = [tuple(row) for row in json.loads(out.stdout.strip().splitlines()[-1])]
    ours = [(module, name) for module, name, _ in compiled if module.startswith("navkit.")]
    assert ("navkit.planning.grid._astar_kernels", "grid_search") in ours
    assert ("navkit.planning.grid._jps_kernels", "jps_search") in ours
    assert ("navkit.planning.grid._search_heap", "_rec_sift_down") in ours
    # One compilation per kernel: no literal or second dtype specialisation.
    assert len(ours) == len(set(ours)), sorted(ours)
    # min(), max(), int() on scalars are numba overloads compiled on first use.
    builtins = [row for row in compiled if row[0] == "numba.cpython.builtins"]
    assert not builtins
