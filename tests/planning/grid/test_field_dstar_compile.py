"""Field D* kernels: one compilation per kernel, and the path buffer's regrowth."""

from __future__ import annotations

import numpy as np
import pytest

from navkit.planning import FieldDStar
from navkit.planning.grid import (
    _dstar_heap,
    _dstar_lite_kernels,
    _field_path_kernels,
    _polyline_kernels,
)
from navkit.planning.grid import _field_dstar as field_dstar_module
from navkit.sim import warmup


def _exercise() -> None:
    # Every Field D* entry point with every option that selects another kernel.
    warmup(workers=1, only=["field_dstar"])
    FieldDStar(np.ones((6, 6))).plan_cells((0, 0), (5, 5))


def test_every_kernel_is_compiled_for_one_signature() -> None:
    # Each distinct argument type set compiles a kernel again (read-only vs
    # writable arrays, int32 vs int64, C vs A layout): the public layer passes
    # one type set, so every entry point shares one compilation. (Kernels
    # loaded from numba's cache list only the signatures called from Python.)
    _exercise()
    readonly = np.ones((5, 5))
    readonly.flags.writeable = False
    FieldDStar(readonly).plan((0, 0), (5, 5))
    FieldDStar(np.ones((5, 5), dtype=np.float32)).plan((0, 0), (5, 5))
    compiled = {}
    for module in (_dstar_heap, _dstar_lite_kernels, _field_path_kernels, _polyline_kernels):
        for name, obj in vars(module).items():
            signatures = getattr(obj, "signatures", None)
            if signatures:
                compiled[f"{module.__name__}.{name}"] = len(signatures)
    assert "navkit.planning.grid._field_path_kernels.extract_path" in compiled
    assert "navkit.planning.grid._polyline_kernels._polyline" in compiled
    assert {name: n for name, n in compiled.items() if n != 1} == {}


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
