"""Kernel compile options are written in each kernel's own source file.

numba's cache keys a kernel's machine code on its own source file (modification
time and size) and never on its options: a kernel whose options come from a
dict in another file keeps loading code compiled with the old options after
that dict changes (until its own file changes too). The Field D* path and
polyline kernels took theirs from ``_dstar_heap.py``; each Field D* kernel
module now writes them itself. Checked here for every module of navkit (the
option sets of :mod:`navkit._shared.jit` are the one allowed outside source,
as ``RELEASES_GIL``'s test in ``tests/shared/test_review22_nogil_kernels.py``
allows), and that the four Field D* modules still compile with one set.
"""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

import navkit
from navkit._shared.jit import load_numba

SRC = Path(navkit.__file__).parent
JIT = "navkit._shared.jit"
FIELD_DSTAR = [
    "navkit.planning.grid._dstar_heap",
    "navkit.planning.grid._dstar_lite_kernels",
    "navkit.planning.grid._field_path_kernels",
    "navkit.planning.grid._polyline_kernels",
]


def foreign_options(source: str) -> list[str]:
    """Options of ``typed_njit(...)`` calls in ``source`` taken from another navkit module.

    Every ``**name`` and every keyword's value given by name must be defined in
    the module itself or come from :mod:`navkit._shared.jit`.
    """
    tree = ast.parse(source)
    imported = {
        alias.asname or alias.name: node.module
        for node in ast.walk(tree)
        if isinstance(node, ast.ImportFrom) and node.module
        for alias in node.names
    }
    found = []
    for node in ast.walk(tree):
        if not (isinstance(node, ast.Call) and ast.unparse(node.func) == "typed_njit"):
            continue
        for keyword in node.keywords:
            names = [n.id for n in ast.walk(keyword.value) if isinstance(n, ast.Name)]
            for name in names:
                module = imported.get(name)
                if module is not None and module != JIT:
                    found.append(f"line {node.lineno}: {name} from {module}")
    return found


def test_the_check_finds_options_from_another_module() -> None:
    # The path kernels' former lines.
    before = (
        "from navkit._shared.jit import RELEASES_GIL, typed_njit\n"
        "from navkit.planning.grid._dstar_heap import HELPER_OPTIONS, KERNEL_OPTIONS\n"
        "_kernel = typed_njit(**KERNEL_OPTIONS, **RELEASES_GIL)\n"
        "_helper = typed_njit(**HELPER_OPTIONS, forceinline=False)\n"
        "_other = typed_njit(error_model=MODEL)\n"
        "from navkit.x import MODEL\n"
    )
    assert foreign_options(before) == [
        "line 3: KERNEL_OPTIONS from navkit.planning.grid._dstar_heap",
        "line 4: HELPER_OPTIONS from navkit.planning.grid._dstar_heap",
        "line 5: MODEL from navkit.x",
    ]
    after = (
        "from navkit._shared.jit import NO_REFCOUNT, RELEASES_GIL, typed_njit\n"
        "KERNEL_OPTIONS = {**NO_REFCOUNT, 'error_model': 'numpy'}\n"
        "_kernel = typed_njit(**KERNEL_OPTIONS, **RELEASES_GIL)\n"
    )
    assert foreign_options(after) == []


@pytest.mark.parametrize("path", sorted(SRC.rglob("*.py")), ids=lambda p: str(p.relative_to(SRC)))
def test_every_module_writes_its_kernel_options_itself(path: Path) -> None:
    assert foreign_options(path.read_text(encoding="utf-8")) == []


def test_the_field_dstar_modules_compile_with_one_option_set() -> None:
    load_numba()
    from numba.core.dispatcher import Dispatcher

    modules = [importlib.import_module(name) for name in FIELD_DSTAR]
    helper_sets = {tuple(sorted(m.HELPER_OPTIONS.items())) for m in modules}
    assert len(helper_sets) == 1
    kernel_sets = {
        tuple(sorted(m.KERNEL_OPTIONS.items())) for m in modules if hasattr(m, "KERNEL_OPTIONS")
    }
    assert len(kernel_sets) == 1
    (helper,) = helper_sets
    assert dict(helper)["error_model"] == "numpy"
    # Every dispatcher defined in the four modules was compiled with them.
    seen = 0
    for module in modules:
        for value in vars(module).values():
            if isinstance(value, Dispatcher) and value.py_func.__module__ == module.__name__:
                options = value.targetoptions
                if options.get("inline") == "always":
                    continue  # corner_cost: numba copies its body into the caller's IR
                seen += 1
                assert options["error_model"] == "numpy", value.py_func.__qualname__
                assert options["_nrt"] is False, value.py_func.__qualname__
                assert type(value._cache).__name__ != "NullCache", value.py_func.__qualname__
    # 18 since review 53 folded the walk's four helpers into _candidates and the walk (22 before).
    assert seen >= 18
