"""The use-def and dead-variable shortcuts give numba's answers on users' kernels too (review 40).

:mod:`navkit._shared.compile_shortcuts` replaces numba's
``analysis.compute_use_defs`` and ``compute_dead_maps`` process-wide while a
navkit kernel compiles (review 39, FIRSTUSE3), so a user's kernel compiled
meanwhile (one calling a navkit kernel, typed inside the user's compile) goes
through them too. navkit's kernels have no ``try``, generators, object-mode
blocks, closures or ``literal_unroll``; users' do, and their IR has statements
navkit's never makes (``ir.EnterWith``, ``ir.Yield`` values, try-block
branches, parfors). Review 39 compared the shortcuts on navkit's kernels and
on one kernel of loops and a raise; here every call during the compile of such
users' kernels is answered both ways (the same sets in the same order, or the
same error), with the shortcuts switched on as a navkit compile switches them.
"""

from __future__ import annotations

import importlib
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit._shared import compile_shortcuts
from navkit._shared.jit import load_numba

load_numba()
numba: Any = importlib.import_module("numba")
analysis: Any = importlib.import_module("numba.core.analysis")
# A global of that name: numba's unroll pass looks for it.
literal_unroll: Any = numba.literal_unroll

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_review39_firstuse3_use_defs import _in_order  # noqa: E402

_MODULES = (
    "numba.core.analysis", *compile_shortcuts._IMPORTERS,
)  # fmt: skip


def _compare_every_call(monkeypatch: pytest.MonkeyPatch) -> dict[str, int]:
    """Switch the shortcuts on, then answer each call of the two analyses both ways."""
    compile_shortcuts.begin()
    ours = {
        name: vars(analysis)[name] for name in ("compute_use_defs", "compute_dead_maps")
    }  # fmt: skip
    numbas = {
        name: replaced
        for owner, name, _, replaced in compile_shortcuts._SAVED
        if owner is analysis and name in ours
    }
    assert set(numbas) == set(ours), "the shortcuts are in place while navkit compiles"
    assert all(ours[name] is not numbas[name] for name in ours)
    calls = {"use_defs": 0, "dead_maps": 0}

    def use_defs(blocks: Any) -> Any:
        calls["use_defs"] += 1
        expected = numbas["compute_use_defs"](blocks)
        got = ours["compute_use_defs"](blocks)
        assert type(got) is type(expected)
        assert _in_order(got.usemap) == _in_order(expected.usemap)
        assert _in_order(got.defmap) == _in_order(expected.defmap)
        return expected

    def dead_maps(cfg: Any, blocks: Any, live_map: Any, defmap: Any) -> Any:
        calls["dead_maps"] += 1
        expected = numbas["compute_dead_maps"](cfg, blocks, live_map, defmap)
        got = ours["compute_dead_maps"](cfg, blocks, live_map, defmap)
        for mine, numbas_map in zip(got, expected, strict=True):
            assert type(mine) is type(numbas_map)
            assert _in_order(mine) == _in_order(numbas_map)
        return expected

    for name in _MODULES:
        module = sys.modules.get(name)
        if module is None:
            continue
        if vars(module).get("compute_use_defs") is ours["compute_use_defs"]:
            monkeypatch.setattr(module, "compute_use_defs", use_defs)
        if vars(module).get("compute_dead_maps") is ours["compute_dead_maps"]:
            monkeypatch.setattr(module, "compute_dead_maps", dead_maps)
    return calls


@pytest.fixture
def compared(monkeypatch: pytest.MonkeyPatch) -> Any:
    calls = _compare_every_call(monkeypatch)
    yield calls
    monkeypatch.undo()
    compile_shortcuts.end()
    assert not compile_shortcuts.active()


def _with_try(x: Any) -> float:
    total = 0.0
    for i in range(x.size):
        try:
            if x[i] < 0:
                raise ValueError("negative")
            total += x[i]
        except Exception:
            total -= 1.0
    return total


def _generator(n: int) -> Any:
    for i in range(n):
        if i % 2:
            yield i * 2
        else:
            yield -i


def _closure(x: Any) -> list[float]:
    k = 3.0

    def times(a: float) -> float:
        return a * k

    return [times(v) for v in x]


def _unrolled(values: tuple[Any, ...]) -> float:
    total = 0.0
    for v in literal_unroll(values):
        total += v
    return total


def _object_mode(x: Any) -> float:
    with numba.objmode(y="float64"):
        y = float(np.sum(x))
    return y


def test_users_kernels_of_every_kind_get_numbas_sets(compared: dict[str, int]) -> None:
    x = np.arange(5.0) - 2.0
    generator = numba.njit(_generator)

    def consume(n: int) -> int:
        total = 0
        for v in generator(n):
            total += v
        return total

    assert numba.njit(_with_try)(x) == _with_try(x) == 1.0
    assert numba.njit(consume)(7) == sum(_generator(7))
    assert numba.njit(_closure)(x) == [3.0 * v for v in x]
    assert numba.njit(_unrolled)((1, 2.5, 3)) == 6.5
    assert numba.njit(_object_mode)(x) == float(np.sum(x))
    assert compared["use_defs"] > 100 and compared["dead_maps"] > 100


def _parallel(x: Any) -> float:
    total = 0.0
    for i in numba.prange(x.size):
        total += x[i] ** 2
    return total + (x * 2.0 + 1.0).sum()


@pytest.mark.slow
def test_a_users_parallel_kernel_gets_numbas_sets(compared: dict[str, int]) -> None:
    # Parfors: numba's parfor statements answer through ir_extension_usedefs.
    x = np.arange(5.0) - 2.0
    assert numba.njit(parallel=True)(_parallel)(x) == float(np.sum(x**2) + np.sum(x * 2 + 1))
    assert compared["use_defs"] > 10
