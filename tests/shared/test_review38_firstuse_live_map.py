"""The compile shortcut for numba's liveness analysis: the same live sets as numba's own.

:mod:`navkit._shared.compile_shortcuts` replaces, while a navkit kernel
compiles, numba's ``analysis.compute_live_map`` (also bound by name in
``numba.core.ir_utils``) by the same fix-point sweeps on ints with a bit per
variable (issue 17: 0.72 -> 0.13 s of ``navkit warmup``'s simulation step).
These tests compare it with numba's on random control-flow graphs (self
loops, nested loops, blocks no path reaches) and on the IR of real navkit
kernels, and check that it is in place only while navkit compiles.
"""

from __future__ import annotations

import importlib
from typing import Any

from hypothesis import given, settings
from hypothesis import strategies as st

from navkit._shared import compile_shortcuts
from navkit._shared.jit import load_numba

load_numba()
# Any: numba is not typed in every supported version.
analysis: Any = importlib.import_module("numba.core.analysis")
ir_utils: Any = importlib.import_module("numba.core.ir_utils")
controlflow: Any = importlib.import_module("numba.core.controlflow")
compiler: Any = importlib.import_module("numba.core.compiler")

_NUMBA_LIVE_MAP = analysis.compute_live_map
_OURS = compile_shortcuts._live_map_function(_NUMBA_LIVE_MAP)


@st.composite
def _graphs(draw: Any) -> tuple[Any, dict[int, None], dict[int, set[str]], dict[int, set[str]]]:
    """A control-flow graph of 1-12 blocks, each with its used and defined variables."""
    n = draw(st.integers(1, 12))
    names = [f"v{i}" for i in range(draw(st.integers(1, 10)))]
    variables = st.sets(st.sampled_from(names), max_size=len(names))
    cfg = controlflow.CFGraph()
    for node in range(n):
        cfg.add_node(node)
    edges = draw(st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)), max_size=3 * n))
    for src, dest in set(edges):  # self loops and back edges included
        cfg.add_edge(src, dest)
    cfg.set_entry_point(0)
    cfg.process()  # drops the nodes no path from 0 reaches; the blocks keep them
    blocks = dict.fromkeys(range(n))
    use = {node: draw(variables) for node in range(n)}
    defs = {node: draw(variables) for node in range(n)}
    return cfg, blocks, use, defs


@settings(max_examples=100, deadline=None)
@given(_graphs())
def test_random_graphs_give_numbas_live_sets(
    graph: tuple[Any, dict[int, None], dict[int, set[str]], dict[int, set[str]]],
) -> None:
    cfg, blocks, use, defs = graph
    use_before = {node: set(value) for node, value in use.items()}
    defs_before = {node: set(value) for node, value in defs.items()}
    expected = _NUMBA_LIVE_MAP(cfg, blocks, use, defs)
    got = _OURS(cfg, blocks, use, defs)
    assert got == expected
    assert list(got) == list(expected)  # the blocks in numba's order
    assert all(type(value) is set for value in got.values())
    assert (use, defs) == (use_before, defs_before)  # its inputs left as they were


def _kernel_ir(py_func: Any) -> tuple[Any, Any, Any]:
    func_ir = compiler.run_frontend(py_func)
    blocks = func_ir.blocks
    cfg = analysis.compute_cfg_from_blocks(blocks)
    usedefs = analysis.compute_use_defs(blocks)
    return cfg, blocks, usedefs


def test_real_kernels_give_numbas_live_sets() -> None:
    from navkit.estimation import _fusion_kernels
    from navkit.planning.grid import _field_path_kernels
    from navkit.sim import _clearance_kernels, _segment_kernels

    kernels = [
        _segment_kernels.run_segment, _segment_kernels.run_edge_segment,
        _segment_kernels._sweep_static, _clearance_kernels.footprint_clearance,
        _fusion_kernels._planar_step, _field_path_kernels.extract_path,
    ]  # fmt: skip
    for kernel in kernels:
        cfg, blocks, usedefs = _kernel_ir(kernel.py_func)
        expected = _NUMBA_LIVE_MAP(cfg, blocks, usedefs.usemap, usedefs.defmap)
        got = _OURS(cfg, blocks, usedefs.usemap, usedefs.defmap)
        assert len(blocks) > 5
        assert got == expected, kernel.py_func.__qualname__
        assert list(got) == list(expected)


#: Whether numba's own sweeps the blocks in topological order (numba 0.68's does,
#: 0.62's does not): only then is the shortcut put in its place.
_SWEEPS_IN_ORDER = "topo_order" in _NUMBA_LIVE_MAP.__code__.co_names


def test_in_place_only_while_navkit_compiles() -> None:
    assert analysis.compute_live_map is _NUMBA_LIVE_MAP
    assert ir_utils.compute_live_map is _NUMBA_LIVE_MAP
    compile_shortcuts.begin()
    try:
        ours = analysis.compute_live_map
        if not _SWEEPS_IN_ORDER:
            assert ours is _NUMBA_LIVE_MAP  # another numba's order: its own is kept
            return
        assert ours is not _NUMBA_LIVE_MAP
        assert ir_utils.compute_live_map is ours  # numba's dead-code removal calls it by name
        cfg, blocks, usedefs = _kernel_ir(compile_shortcuts._live_map_function)
        assert ours(cfg, blocks, usedefs.usemap, usedefs.defmap) == _NUMBA_LIVE_MAP(
            cfg, blocks, usedefs.usemap, usedefs.defmap
        )
    finally:
        compile_shortcuts.end()
    assert analysis.compute_live_map is _NUMBA_LIVE_MAP
    assert ir_utils.compute_live_map is _NUMBA_LIVE_MAP


def test_disabled_shortcuts_leave_numbas_own(monkeypatch: Any) -> None:
    monkeypatch.setattr(compile_shortcuts, "ENABLED", False)
    compile_shortcuts.begin()
    try:
        assert analysis.compute_live_map is _NUMBA_LIVE_MAP
    finally:
        compile_shortcuts.end()
