"""Field D* kernels: one compilation per kernel, and the path buffer's regrowth."""

from __future__ import annotations

import numpy as np
import pytest

from kernel_signatures import compiled_signatures
from navkit._shared.jit import jit_disabled
from navkit.planning import FieldDStar
from navkit.planning.grid import _field_dstar as field_dstar_module

#: Every Field D* entry point with every option that selects another kernel, then
#: arrays of other types (read-only, float32), as the source of a fresh process.
_EXERCISE = """
import numpy as np
from navkit.planning import FieldDStar
from navkit.sim import warmup
warmup(workers=1, only=["field_dstar"])
FieldDStar(np.ones((6, 6))).plan_cells((0, 0), (5, 5))
readonly = np.ones((5, 5))
readonly.flags.writeable = False
FieldDStar(readonly).plan((0, 0), (5, 5))
FieldDStar(np.ones((5, 5), dtype=np.float32)).plan((0, 0), (5, 5))
"""


# Compiled signatures are what is counted: with the JIT disabled the kernels are
# plain functions, with none.
@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: plain functions")
def test_every_kernel_is_compiled_for_one_signature() -> None:
    # Each distinct argument type set compiles a kernel again (read-only vs
    # writable arrays, int32 vs int64, C vs A layout): the public layer passes
    # one type set, so every entry point shares one compilation. (Kernels
    # loaded from numba's cache list only the signatures called from Python.)
    # In a fresh process: this one's kernels keep the signatures of every earlier
    # test's direct calls (a read-only cost array passed to polyline_cost, say),
    # which ran before this test under another order or split of the suite (xdist).
    compiled = compiled_signatures(
        _EXERCISE,
        [f"navkit.planning.grid.{name}" for name in (
            "_dstar_heap", "_dstar_lite_kernels", "_field_path_kernels", "_polyline_kernels"
        )],
    )  # fmt: skip
    assert "_field_path_kernels.extract_path" in compiled
    assert "_polyline_kernels._polyline" in compiled
    assert {name: sigs for name, sigs in compiled.items() if len(sigs) != 1} == {}


@pytest.mark.parametrize("interpolate", [True, False])
def test_a_full_path_buffer_repeats_the_walk_with_the_same_result(
    monkeypatch: pytest.MonkeyPatch, interpolate: bool
) -> None:
    rng = np.random.default_rng(7)
    costs = rng.uniform(1.0, 4.0, (24, 24))
    costs[rng.random((24, 24)) < 0.15] = np.inf
    costs[0, 0] = costs[-1, -1] = 1.0
    expected = FieldDStar(costs, interpolate=interpolate).plan((0, 0), (24, 24))
    # Room for a single point: the walk fills the buffer again and again.
    monkeypatch.setattr(field_dstar_module, "_POINTS_PER_SIDE", 0)
    planner = FieldDStar(costs, interpolate=interpolate)
    got = planner.plan((0, 0), (24, 24))
    np.testing.assert_array_equal(got.points, expected.points)
    assert got.cost == expected.cost
    assert got.expanded >= expected.expanded
    planner.update_costs([(12, 12), (12, 13)], np.inf)
    fresh_costs = costs.copy()
    fresh_costs[12, 12:14] = np.inf
    np.testing.assert_array_equal(
        planner.replan().points,
        FieldDStar(fresh_costs, interpolate=interpolate).plan((0, 0), (24, 24)).points,
    )
