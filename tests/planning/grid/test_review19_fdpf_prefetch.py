"""Field D* (review 19): the prefetch of fresh searches changes no result.

Fresh searches (``params(..., fresh=True)``) prefetch the records of the next
heap top's neighbours after each pop; repairs do not. A prefetch is a hint and
must leave every value, the heap and the path bit for bit as without it: a
fresh plan run with the flag off (patched in) must end with the same records,
heap, path, cost and expansion count. The intrinsic must not fault on
addresses outside the array, and with the JIT disabled its Python stand-in
does nothing.
"""

from __future__ import annotations

from typing import Any
from unittest import mock

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from numba import njit

from hypothesis_twins import slow_twin
from navkit._shared.jit import load_numba
from navkit.planning import FieldDStar
from navkit.planning.grid import _dstar_lite_kernels
from navkit.planning.grid._dstar_lite_kernels import params
from subprocess_probe import probe_outcome


def _plan(costs: np.ndarray, interp: bool, fresh: bool | None) -> tuple[Any, ...]:
    """Path, cost, expansions and the planner's arrays after a fresh plan corner to corner.

    ``fresh=False`` runs the fresh search with the prefetch flag off; ``None``
    leaves the planner as it is.
    """
    rows, cols = costs.shape
    planner = FieldDStar(costs, interpolate=interp)
    if fresh is None:
        path = planner.plan((0, 0), (rows, cols))
    else:
        original = FieldDStar._params

        def forced(self: FieldDStar, walk: int | None = None, flag: bool = False) -> Any:
            return original(self, walk, fresh)

        with mock.patch.object(FieldDStar, "_params", forced):
            path = planner.plan((0, 0), (rows, cols))
    nodes, keys, pos, size = planner._heap
    n = int(size[0])
    return (
        path.points.copy(), path.cost, path.expanded, planner._vals.copy(),
        nodes[:n].copy(), keys[:n].copy(), pos.copy(),
    )  # fmt: skip


def _assert_same(a: tuple[Any, ...], b: tuple[Any, ...]) -> None:
    for x, y in zip(a, b, strict=True):
        if isinstance(x, np.ndarray):
            assert x.dtype == y.dtype and x.shape == y.shape
            # Bit patterns: -0.0 / 0.0 or NaN payloads would differ too.
            np.testing.assert_array_equal(x.view(np.uint8), y.view(np.uint8))
        else:
            assert x == y


@st.composite
def maps(draw: Any) -> np.ndarray:
    rows = draw(st.integers(1, 40))
    cols = draw(st.integers(1, 40))
    seed = draw(st.integers(0, 2**32 - 1))
    blocked = draw(st.sampled_from([0.0, 0.1, 0.25, 0.4]))
    rng = np.random.default_rng(seed)
    costs = rng.choice([1.0, 1.0, 1.5, 2.0, 4.0], size=(rows, cols))
    costs[rng.random((rows, cols)) < blocked] = np.inf
    costs[0, 0] = costs[-1, -1] = 1.0
    return costs


@settings(max_examples=40, deadline=None)
@given(costs=maps(), interp=st.booleans())
def test_fresh_search_with_and_without_prefetch_is_bit_identical(
    costs: np.ndarray, interp: bool
) -> None:
    try:
        with_prefetch = _plan(costs, interp, True)
    except Exception as error:  # no path: both must refuse alike
        try:
            _plan(costs, interp, False)
        except Exception as other:
            assert type(other) is type(error) and str(other) == str(error)
            return
        raise AssertionError("only the prefetching search failed") from error
    _assert_same(with_prefetch, _plan(costs, interp, False))


test_fresh_search_with_and_without_prefetch_is_bit_identical_thoroughly = slow_twin(
    test_fresh_search_with_and_without_prefetch_is_bit_identical, max_examples=300
)


def test_plans_run_fresh_searches_with_the_prefetch_and_replans_without() -> None:
    seen: list[bool] = []
    original = _dstar_lite_kernels.params

    def spy(*args: Any, **kwargs: Any) -> tuple[Any, ...]:
        prm = original(*args, **kwargs)
        seen.append(prm[11])
        return prm

    rng = np.random.default_rng(19)
    costs = rng.uniform(1.0, 3.0, (30, 30))
    planner = FieldDStar(costs)
    with mock.patch("navkit.planning.grid._field_dstar.params", spy):
        fresh = planner.plan((0, 0), (30, 30))
        planner.update_costs([(10, 10), (10, 11)], np.inf)
        n_fresh = len(seen)
        replanned = planner.replan()
    assert fresh.expanded > 0 and replanned.expanded > 0
    assert n_fresh >= 1 and all(seen[:n_fresh])
    assert len(seen) > n_fresh and not any(seen[n_fresh:])
    # The same results as a planner left alone.
    again = FieldDStar(costs)
    again.plan((0, 0), (30, 30))
    again.update_costs([(10, 10), (10, 11)], np.inf)
    np.testing.assert_array_equal(again.replan().points, replanned.points)


def test_params_carry_the_fresh_flag_as_a_bool_last() -> None:
    base = (12, 5, 13, (0, 0), 64, 0.0, True, 0.7, -1, -1)
    assert params(*base)[11] is False
    assert params(*base, fresh=True)[11] is True
    assert params(*base, fresh=np.bool_(True))[11] is True
    assert len(params(*base)) == 12


def _prefetch_far_kernel() -> Any:
    """A kernel prefetching lines well outside ``arr`` (either side), returning its sum."""
    load_numba()  # binds _prefetch (navkit binds numba names when it loads numba)
    prefetch = _dstar_lite_kernels._prefetch

    @njit(cache=False)
    def far(arr: np.ndarray, step: int) -> float:
        total = 0.0
        for k in range(-8, 9):
            prefetch(arr, k * step)
        for v in arr:
            total += v
        return total

    return far


def test_the_prefetch_never_faults_and_changes_nothing() -> None:
    _prefetch_far = _prefetch_far_kernel()
    arr = np.arange(10.0)
    before = arr.copy()
    # Indices up to 8 * 2**40 elements away from the array: never mapped.
    for step in (1, 100, 2**20, 2**40):
        assert _prefetch_far(arr, step) == 45.0
    np.testing.assert_array_equal(arr, before)


_DISABLED = r"""
import json, os
os.environ["NUMBA_DISABLE_JIT"] = "1"
import numpy as np
from navkit.planning import FieldDStar
costs = np.ones((5, 6)); costs[2, 1:5] = np.inf
path = FieldDStar(costs).plan((0, 0), (5, 6))
print(json.dumps([path.cost, path.expanded, path.points.tolist()]))
"""


def test_a_fresh_plan_with_the_jit_disabled_equals_the_compiled_one() -> None:
    costs = np.ones((5, 6))
    costs[2, 1:5] = np.inf
    path = FieldDStar(costs).plan((0, 0), (5, 6))
    cost, expanded, points = probe_outcome(_DISABLED)
    assert cost == path.cost and expanded == path.expanded
    np.testing.assert_array_equal(np.array(points), path.points)
