"""The compile shortcuts for numba's use-def and dead-variable analyses: numba's answers.

:mod:`navkit._shared.compile_shortcuts` replaces, while a navkit kernel
compiles, numba's ``analysis.compute_use_defs`` (each statement's variables
listed once, without a call per value) and ``analysis.compute_dead_maps``
(its check that every live variable dies somewhere made in place), also
where numba's modules imported them by name (issue 17: 0.89 -> 0.38 s and
0.42 -> 0.27 s of ``navkit warmup``). These tests compare them with numba's
own: on the IR of real navkit kernels, at every call while numba compiles a
kernel of loops, tuples, calls and a raise (the same sets, built in the same
order), on statements of kinds the shortcut leaves to numba's steps, and on
numba's errors; and they check that both are in place only while navkit
compiles.
"""

from __future__ import annotations

import importlib
import operator
from typing import Any

import numpy as np
import pytest

from navkit._shared import compile_shortcuts
from navkit._shared.jit import load_numba

load_numba()
# Any: numba is not typed in every supported version.
numba: Any = importlib.import_module("numba")
ir: Any = importlib.import_module("numba.core.ir")
analysis: Any = importlib.import_module("numba.core.analysis")
compiler: Any = importlib.import_module("numba.core.compiler")

_NUMBA_USE_DEFS = analysis.compute_use_defs
_NUMBA_DEAD_MAPS = analysis.compute_dead_maps
_USE_DEFS = compile_shortcuts._use_defs_function(
    _NUMBA_USE_DEFS, ir, analysis.ir_extension_usedefs, analysis._use_defs_result
)
_DEAD_MAPS = compile_shortcuts._dead_maps_function(_NUMBA_DEAD_MAPS, analysis._dead_maps_result)
#: numba's modules holding the two analyses by name (imported by numba's compiler).
_IMPORTERS = [
    importlib.import_module(name)
    for name in ("numba.core.ir_utils", "numba.core.lowering", "numba.core.transforms",
                 "numba.core.untyped_passes", "numba.core.inline_closurecall")
]  # fmt: skip


def _in_order(mapping: Any) -> list[tuple[Any, list[str]]]:
    """Each block's set as its items in iteration order (equal sets may iterate otherwise)."""
    return [(block, list(items)) for block, items in mapping.items()]


def _same_use_defs(blocks: Any) -> Any:
    expected = _NUMBA_USE_DEFS(blocks)
    got = _USE_DEFS(blocks)
    assert type(got) is type(expected)
    assert _in_order(got.usemap) == _in_order(expected.usemap)
    assert _in_order(got.defmap) == _in_order(expected.defmap)
    return expected


def _same_dead_maps(cfg: Any, blocks: Any, live_map: Any, defmap: Any) -> Any:
    expected = _NUMBA_DEAD_MAPS(cfg, blocks, live_map, defmap)
    got = _DEAD_MAPS(cfg, blocks, live_map, defmap)
    assert type(got) is type(expected)
    for mine, numbas in zip(got, expected, strict=True):
        assert type(mine) is type(numbas)
        assert getattr(mine, "default_factory", None) is getattr(numbas, "default_factory", None)
        assert _in_order(mine) == _in_order(numbas)
    return expected


def test_real_kernels_give_numbas_use_defs_and_dead_maps() -> None:
    from navkit.estimation import _fusion_kernels
    from navkit.mapping import _raycast_kernels
    from navkit.planning.grid import _field_path_kernels
    from navkit.sim import _clearance_kernels, _segment_kernels

    kernels = [
        _segment_kernels.run_segment, _segment_kernels._sweep_static,
        _clearance_kernels.footprint_clearance, _fusion_kernels._planar_step,
        _field_path_kernels.extract_path, _raycast_kernels.integrate_beams,
    ]  # fmt: skip
    for kernel in kernels:
        blocks = compiler.run_frontend(kernel.py_func).blocks
        usedefs = _same_use_defs(blocks)
        cfg = analysis.compute_cfg_from_blocks(blocks)
        live_map = analysis.compute_live_map(cfg, blocks, usedefs.usemap, usedefs.defmap)
        _same_dead_maps(cfg, blocks, live_map, usedefs.defmap)
        assert len(blocks) > 5, kernel.py_func.__qualname__


def _kernel(a: Any, b: tuple[int, int], n: int) -> float:
    total = 0.0
    pairs = [(i, i * 2) for i in range(n)]
    for i, j in pairs:
        if i > b[0] and j < b[1]:
            total += a[i] * np.sqrt(abs(a[j % a.shape[0]]))
        elif i == 3:
            continue
        else:
            total -= min(i, j)
    x, y = b
    while x < y:
        x += 1
        if x > 100:
            raise ValueError("too far")
    return total + x


def test_every_call_of_a_real_compile_gives_numbas_answers(monkeypatch: pytest.MonkeyPatch) -> None:
    # Numba's whole pipeline (untyped and typed passes, SSA, inlining, lowering):
    # each call of the two analyses answered both ways on the IR of the moment.
    calls = {"use_defs": 0, "dead_maps": 0}

    def use_defs(blocks: Any) -> Any:
        calls["use_defs"] += 1
        return _same_use_defs(blocks)

    def dead_maps(cfg: Any, blocks: Any, live_map: Any, defmap: Any) -> Any:
        calls["dead_maps"] += 1
        return _same_dead_maps(cfg, blocks, live_map, defmap)

    for module in [analysis, *_IMPORTERS]:
        if vars(module).get("compute_use_defs") is _NUMBA_USE_DEFS:
            monkeypatch.setattr(module, "compute_use_defs", use_defs)
        if vars(module).get("compute_dead_maps") is _NUMBA_DEAD_MAPS:
            monkeypatch.setattr(module, "compute_dead_maps", dead_maps)
    compiled = numba.njit(_kernel)
    assert compiled(np.arange(5.0), (1, 4), 6) == _kernel(np.arange(5.0), (1, 4), 6)
    assert calls["use_defs"] > 10 and calls["dead_maps"] > 10


def _assign(value: Any, target: str, scope: Any, loc: Any) -> Any:
    return ir.Assign(value, ir.Var(scope, target, loc), loc)


def _block(scope: Any, loc: Any, body: list[Any]) -> Any:
    block = ir.Block(scope, loc)
    for stmt in body:
        block.append(stmt)
    return block


def test_statements_the_shortcut_leaves_to_numbas_steps() -> None:
    loc = ir.Loc("f.py", 1)
    scope = ir.Scope(None, loc)

    class OwnListing(ir.Assign):  # lists its variables its own way
        def list_vars(self) -> list[Any]:
            return [ir.Var(scope, "extra", loc), *super().list_vars()]

    class Extension(ir.Stmt):  # an extension's statement, with its own use-defs
        def __init__(self, name: str) -> None:
            self.name, self.loc = name, loc

    def extension_usedefs(stmt: Any, use_set: set[str], def_set: set[str]) -> None:
        use_set.add(stmt.name + "_used")
        def_set.add(stmt.name + "_defined")

    x, y = ir.Var(scope, "x", loc), ir.Var(scope, "y", loc)
    tagged = _assign(ir.Expr.binop(operator.add, x, y, loc), "t", scope, loc)
    tagged.note = ir.Var(scope, "noted", loc)  # a field numba lists as any other
    reordered = ir.Assign.__new__(ir.Assign)  # fields in another order
    reordered.target, reordered.value, reordered.loc = ir.Var(scope, "r", loc), y, loc
    body = [
        _assign(ir.Arg("x", 0, loc), "x", scope, loc),
        _assign(ir.Const(1.5, loc), "y", scope, loc),
        _assign(ir.Expr.binop(operator.add, x, ir.Var(scope, "z", loc), loc), "x", scope, loc),
        _assign(ir.Expr.call(ir.Var(scope, "f", loc), [x, y], (("k", x),), loc), "w", scope, loc),
        OwnListing(ir.Var(scope, "w", loc), ir.Var(scope, "v", loc), loc),
        tagged,
        reordered,
        Extension("e"),
        ir.SetItem(x, y, ir.Var(scope, "u", loc), loc),
        ir.Del("u", loc),
        ir.Return(ir.Var(scope, "w", loc), loc),
    ]
    blocks = {0: _block(scope, loc, body)}
    analysis.ir_extension_usedefs[Extension] = extension_usedefs
    try:
        usedefs = _same_use_defs(blocks)
    finally:
        del analysis.ir_extension_usedefs[Extension]
    assert {"extra", "noted", "z", "e_used"} <= usedefs.usemap[0]
    assert {"x", "y", "t", "r", "e_defined"} <= usedefs.defmap[0]


def test_an_assignment_numba_cannot_read_raises_numbas_error() -> None:
    loc = ir.Loc("f.py", 1)
    scope = ir.Scope(None, loc)
    odd = ir.Assign(ir.Const(1, loc), ir.Var(scope, "a", loc), loc)
    odd.value = object()  # neither an instruction, a variable, nor a constant
    blocks = {0: _block(scope, loc, [odd, ir.Return(ir.Var(scope, "a", loc), loc)])}
    with pytest.raises(AssertionError) as numbas:
        _NUMBA_USE_DEFS(blocks)
    with pytest.raises(AssertionError) as ours:
        _USE_DEFS(blocks)
    assert ours.value.args == numbas.value.args


def test_a_live_variable_dying_nowhere_raises_numbas_error() -> None:
    loc = ir.Loc("f.py", 1)
    scope = ir.Scope(None, loc)
    blocks = {
        0: _block(scope, loc, [_assign(ir.Const(1, loc), "a", scope, loc), ir.Jump(1, loc)]),
        1: _block(scope, loc, [ir.Return(ir.Var(scope, "a", loc), loc)]),
    }
    cfg = analysis.compute_cfg_from_blocks(blocks)
    usedefs = analysis.compute_use_defs(blocks)
    live_map = analysis.compute_live_map(cfg, blocks, usedefs.usemap, usedefs.defmap)
    _same_dead_maps(cfg, blocks, live_map, usedefs.defmap)
    live_map[7] = {"ghost"}  # live at the entry of a block not in the IR: dead nowhere
    with pytest.raises(RuntimeError, match="liveness info missing") as numbas:
        _NUMBA_DEAD_MAPS(cfg, blocks, live_map, usedefs.defmap)
    with pytest.raises(RuntimeError) as ours:
        _DEAD_MAPS(cfg, blocks, live_map, usedefs.defmap)
    assert str(ours.value) == str(numbas.value)


def test_in_place_only_while_navkit_compiles() -> None:
    def installed() -> list[Any]:
        return [
            vars(module).get(name)
            for module in (analysis, *_IMPORTERS)
            for name in ("compute_use_defs", "compute_dead_maps")
        ]

    before = installed()
    assert _NUMBA_USE_DEFS in before and _NUMBA_DEAD_MAPS in before
    compile_shortcuts.begin()
    try:
        during = installed()
        assert _NUMBA_USE_DEFS not in during and _NUMBA_DEAD_MAPS not in during
        assert analysis.compute_use_defs is not _NUMBA_USE_DEFS
        blocks = compiler.run_frontend(_kernel).blocks
        assert analysis.compute_use_defs(blocks) == _NUMBA_USE_DEFS(blocks)
    finally:
        compile_shortcuts.end()
    assert installed() == before


def test_disabled_shortcuts_leave_numbas_own(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(compile_shortcuts, "ENABLED", False)
    compile_shortcuts.begin()
    try:
        assert analysis.compute_use_defs is _NUMBA_USE_DEFS
        assert analysis.compute_dead_maps is _NUMBA_DEAD_MAPS
    finally:
        compile_shortcuts.end()
