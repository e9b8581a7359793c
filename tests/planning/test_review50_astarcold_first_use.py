"""First use of the grid planners (issue 17): less to compile, the same answers (review 50).

* The distance field's kernels: the grid's padding also fills the padded field
  with inf, and the bucket queue's kernel crops the finished field in place,
  so two kernels with Python wrappers of their own (``fill_inf``, ``crop``)
  are gone; the queue's bucket index and fullest segment are ``np.int64``
  and a select instead of the ``int`` and ``max`` builtins, which numba
  compiles as overloads of their own on first use. A cold
  ``distance_field`` compiled about 0.13 s less (0.73-0.78 -> 0.62-0.63 s
  CPU, numba imported before the clock, three alternating pairs).
* The search heaps' comparisons are written out where they compare instead of
  calls numba copies and types again at each site (``inline="always"``):
  the same machine code (numba 0.68.1: the assembly of ``grid_search``,
  ``jps_search`` and ``jps_cut_search`` unchanged, line for line).

Checked here: the kernels' new contracts (the padding fills the field, the
queue's kernel leaves the field cropped, equal to the heap Dijkstra's bit for
bit), and, in a fresh process with an empty cache, that a first
``distance_field`` compiles no builtin overload and neither removed kernel,
and that no heap operation or search kernel calls a comparison helper.
"""

from __future__ import annotations

import dis

import numpy as np
import pytest

from navkit._shared.jit import jit_disabled
from navkit.planning import AStarPlanner, distance_field
from navkit.planning.grid import (
    _astar_kernels,
    _distance_field_kernels,
    _jps_cut_kernels,
    _jps_kernels,
    _search_heap,
)
from navkit.planning.grid._distance_field_kernels import DONE, bucket_field, pad_grid
from subprocess_probe import COMPILES_LISTED, cold_outcome


def _grid(seed: int, rows: int = 23, cols: int = 17, uniform: bool = False) -> np.ndarray:
    rng = np.random.default_rng(seed)
    costs = np.ones((rows, cols)) if uniform else rng.uniform(1.0, 4.0, (rows, cols))
    costs[rng.random((rows, cols)) < 0.2] = np.inf
    return costs


@pytest.mark.parametrize("uniform", [True, False])
def test_padding_fills_the_padded_field_with_inf(uniform: bool) -> None:
    costs = _grid(1, uniform=uniform)
    rows, cols = costs.shape
    n = (rows + 2) * (cols + 2)
    free = np.full(n, 7, dtype=np.uint8)
    padded = np.full(0 if uniform else n, -5.0)
    dist = np.full(n, -1.0)  # garbage: every entry must be overwritten
    flat = costs.reshape(-1).copy()
    pad_grid(flat, rows, cols, free, padded, uniform, dist)
    assert np.all(dist == np.inf)
    inner = free.reshape(rows + 2, cols + 2)
    np.testing.assert_array_equal(inner[1:-1, 1:-1], np.isfinite(costs).astype(np.uint8))
    assert not inner[0].any() and not inner[-1].any()
    assert not inner[:, 0].any() and not inner[:, -1].any()
    if not uniform:
        field = padded.reshape(rows + 2, cols + 2)
        np.testing.assert_array_equal(field[1:-1, 1:-1], costs)
        assert np.all(field[0] == np.inf) and np.all(field[:, -1] == np.inf)
    np.testing.assert_array_equal(flat, costs.reshape(-1))  # the input is not modified


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("eight", [True, False])
@pytest.mark.parametrize("cutting", [True, False])
def test_the_queue_kernel_leaves_the_field_cropped(seed: int, eight: bool, cutting: bool) -> None:
    costs = _grid(seed, uniform=seed % 2 == 0)
    rows, cols = costs.shape
    goal = tuple(int(x) for x in np.argwhere(np.isfinite(costs))[seed])
    n = (rows + 2) * (cols + 2)
    free = np.empty(n, dtype=np.uint8)
    uniform = seed % 2 == 0
    padded = np.empty(0 if uniform else n)
    dist = np.empty(n)
    pad_grid(costs.reshape(-1).copy(), rows, cols, free, padded, uniform, dist)
    source = (goal[0] + 1) * (cols + 2) + goal[1] + 1
    dist[source] = 0.0
    n_slots, cap = 16, 8 * (rows + cols)
    buckets = np.empty(n_slots * cap, dtype=np.int32)
    buckets[0] = source
    counts = np.zeros(n_slots, dtype=np.int64)
    counts[0] = 1
    state = np.array([0, 0, 1], dtype=np.int64)
    status = bucket_field(free, padded, 1.0 if uniform else 0.0, rows, cols, eight, cutting,
                          1.0 / (1.0 - 2.0**-10), n_slots - 1, dist, buckets, cap, counts,
                          state)  # fmt: skip
    assert status == DONE
    want = AStarPlanner(
        costs, connectivity=8 if eight else 4, corner_cutting=cutting
    ).distance_field(goal)
    np.testing.assert_array_equal(dist[: rows * cols].reshape(rows, cols), want)


@pytest.mark.parametrize("seed", range(6))
def test_distance_field_equals_the_heap_dijkstra_bit_for_bit(seed: int) -> None:
    costs = _grid(10 + seed, rows=31 + seed, cols=9 + 5 * seed, uniform=seed % 3 == 0)
    goal = tuple(int(x) for x in np.argwhere(np.isfinite(costs))[-1 - seed])
    for eight in (True, False):
        for cutting in (True, False):
            connectivity = 8 if eight else 4
            field = distance_field(costs, goal, connectivity=connectivity, corner_cutting=cutting)
            want = AStarPlanner(
                costs, connectivity=connectivity, corner_cutting=cutting
            ).distance_field(goal)
            np.testing.assert_array_equal(field, want)


_COMPARISONS = {"_precedes", "_bits_precede"}


def _names_called(function: object) -> set[str]:
    code = function.py_func.__code__  # type: ignore[attr-defined]
    return {ins.argval for ins in dis.get_instructions(code) if ins.opname == "LOAD_GLOBAL"}


@pytest.mark.parametrize(
    "module",
    [_search_heap, _astar_kernels, _jps_kernels, _jps_cut_kernels],
    ids=lambda m: m.__name__,
)
def test_no_kernel_calls_a_comparison_helper(module: object) -> None:
    """Written out: a call of an ``inline="always"`` helper is copied and typed at each site."""
    for name, value in vars(module).items():
        if name in _COMPARISONS or not hasattr(value, "py_func"):
            continue  # not a kernel (LazyKernel and numba's dispatcher both have py_func)
        assert not _names_called(value) & _COMPARISONS, name


_FIRST_USE = COMPILES_LISTED + """
import json
import numpy as np
from navkit.planning import distance_field
costs = np.ones((30, 40))
costs[5:25, 20] = np.inf
distance_field(costs, (0, 0))
distance_field(costs + np.eye(30, 40), (0, 0), corner_cutting=True)
print(json.dumps(compiled))
"""


@pytest.mark.skipif(jit_disabled(), reason="nothing is compiled with the JIT disabled")
def test_distance_field_first_use_compiles_no_builtin_and_its_kernels_once() -> None:
    compiled = [tuple(row) for row in cold_outcome(_FIRST_USE)]
    # min(), max(), int() on scalars are numba overloads compiled on first use.
    assert not [row for row in compiled if row[0] == "numba.cpython.builtins"], compiled
    ours = [name for module, name in compiled if module == _distance_field_kernels.__name__]
    assert sorted(ours) == ["_relax", "bucket_field", "pad_grid"]
