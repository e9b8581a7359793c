"""The compile shortcuts of issue 17's first-use round: the same answers as numba's own.

:mod:`navkit._shared.compile_shortcuts` also answers, while a navkit kernel
compiles, numba's typing of operator and builtin calls from a memo
(``Function.get_call_type``), LLVM type sizes from a memo
(``BaseContext.get_abi_sizeof``), whether lowering implementations take a
``loc`` from a memo (``numba.core.base._has_loc``), and lists an IR
statement's variables without a call per leaf (``Inst._rec_list_vars``).
These tests check each against numba's own (hypothesis for the variable
lists), that calls answered by an ``@overload`` are left to numba, that the
four are on only while navkit compiles, and (slow, in fresh interpreters
with empty caches) that the Field D* and jump point search kernels compile
to the same LLVM IR with the shortcuts as without.
"""

from __future__ import annotations

import importlib
import operator
import os
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit._shared import compile_shortcuts
from navkit._shared.jit import load_numba

load_numba()
# Any: numba is not typed in every supported version.
types: Any = importlib.import_module("numba.core.types")
functions: Any = importlib.import_module("numba.core.types.functions")
ir: Any = importlib.import_module("numba.core.ir")
base: Any = importlib.import_module("numba.core.base")
registry: Any = importlib.import_module("numba.core.registry")
numba_errors: Any = importlib.import_module("numba.core.errors")
target_extension: Any = importlib.import_module("numba.core.target_extension")
extending: Any = importlib.import_module("numba.extending")
llvmir: Any = importlib.import_module("llvmlite.ir")

TYPING = registry.cpu_target.typing_context
TARGET = registry.cpu_target.target_context


def _memo_method() -> Any:
    assert "get_call_type" not in vars(functions.Function)  # numba's own in place
    return compile_shortcuts._call_type_method(
        functions.Function, functions.Function.get_call_type, target_extension.get_local_target
    )


_ARRAY = types.Array(types.float64, 1, "C")
_CALLS = [
    (operator.add, (types.int64, types.int64)),
    (operator.add, (types.int64, types.IntegerLiteral(1))),
    (operator.add, (types.float64, types.int64)),
    (operator.mul, (types.float64, types.float64)),
    (operator.lt, (types.float64, types.float64)),
    (operator.getitem, (_ARRAY, types.int64)),
    (operator.setitem, (_ARRAY, types.int64, types.float64)),
    (bool, (types.float64,)),
    (abs, (types.int64,)),
]


@pytest.mark.parametrize(("function", "args"), _CALLS)
def test_a_typed_call_is_answered_as_numba_answers_it(function: Any, args: tuple[Any, ...]) -> None:
    TYPING.refresh()
    fnty = TYPING.resolve_value_type(function)
    expected = fnty.get_call_type(TYPING, args, {})
    impl = fnty._impl_keys[expected.args]
    memo = _memo_method()
    first = memo(fnty, TYPING, args, {})
    fnty._impl_keys[expected.args] = "overwritten meanwhile"
    second = memo(fnty, TYPING, args, {})  # from the memo
    assert first == expected and second is first
    assert fnty._impl_keys[expected.args] is impl  # written again, as numba writes it
    assert (fnty, TYPING, target_extension.get_local_target(TYPING), args, ()) in (
        compile_shortcuts._CALL_TYPES
    )


def _doubled(x: Any) -> Any:  # pragma: no cover - typed, never run
    return 2 * x


_CALLS_MADE: list[Any] = []


@extending.overload(_doubled)
def _doubled_overload(x: Any) -> Any:
    _CALLS_MADE.append(x)
    if isinstance(x, types.Integer):

        def impl(x: Any) -> Any:  # pragma: no cover - compiled
            return 2 * x

        return impl
    return None


def test_a_call_answered_by_an_overload_goes_to_numba_every_time() -> None:
    TYPING.refresh()
    fnty = TYPING.resolve_value_type(_doubled)
    memo = _memo_method()
    args = (types.int16,)
    sig = memo(fnty, TYPING, args, {})
    assert sig is not None and sig.return_type == types.int64
    assert fnty._impl_keys[sig.args] is not fnty.typing_key  # compiled code of its own
    assert not any(key[0] is fnty for key in compile_shortcuts._CALL_TYPES)
    with pytest.raises(numba_errors.TypingError, match="_doubled"):  # numba's own, raised
        memo(fnty, TYPING, (types.float64,), {})


def test_another_class_of_function_type_goes_to_numba() -> None:
    seen: list[Any] = []

    def numbas(self: Any, context: Any, args: Any, kws: Any) -> str:
        seen.append(self)
        return "numba's answer"

    class Other(functions.Function):  # type: ignore[misc]  # (a class of Any)
        pass

    memo = compile_shortcuts._call_type_method(
        functions.Function, numbas, target_extension.get_local_target
    )
    other = Other.__new__(Other)
    assert memo(other, TYPING, (types.int64,), {}) == "numba's answer"
    assert seen == [other]


_LLVM_TYPES = [
    llvmir.IntType(1),
    llvmir.IntType(64),
    llvmir.DoubleType(),
    llvmir.IntType(8).as_pointer(),
    llvmir.ArrayType(llvmir.DoubleType(), 7),
    llvmir.LiteralStructType([llvmir.IntType(8), llvmir.DoubleType(), llvmir.IntType(32)]),
    TARGET.get_value_type(_ARRAY),
    TARGET.get_value_type(types.UniTuple(_ARRAY, 3)),
]


def test_abi_sizes_are_numbas() -> None:
    numbas = base.BaseContext.get_abi_sizeof
    memo = compile_shortcuts._abi_size_method(numbas)
    for ty in _LLVM_TYPES * 2:  # the second time from the memo
        assert memo(TARGET, ty) == numbas(TARGET, ty)
    assert compile_shortcuts._ABI_SIZES[(id(TARGET), str(_LLVM_TYPES[-1]))][0] is TARGET


def test_an_identified_structure_is_sized_by_numba_every_time() -> None:
    calls: list[Any] = []

    def numbas(self: Any, ty: Any) -> int:
        calls.append(ty)
        return 24

    memo = compile_shortcuts._abi_size_method(numbas)
    named = llvmir.global_context.get_identified_type("navkit_test_review22_cold")
    assert memo(TARGET, named) == memo(TARGET, named) == 24
    assert calls == [named, named]


def _takes_loc(context: Any, builder: Any, sig: Any, args: Any, loc: Any = None) -> None:
    """A lowering implementation taking ``loc``."""


def _no_loc(context: Any, builder: Any, sig: Any, args: Any) -> None:
    """One that does not."""


def test_whether_an_implementation_takes_loc_is_numbas_answer() -> None:
    numbas = base._has_loc
    memo = compile_shortcuts._has_loc_function(numbas)
    for fn in (_takes_loc, _no_loc, _takes_loc, _no_loc, TARGET.get_function):
        assert memo(fn) is numbas(fn)
    assert memo(_takes_loc) is True and memo(_no_loc) is False
    assert compile_shortcuts._HAS_LOC[id(_no_loc)] == (_no_loc, False)


# --- variable lists ------------------------------------------------------------------------

_LOC = ir.Loc("test.py", 1)
_SCOPE = ir.Scope(None, _LOC)
_VARS = [ir.Var(_SCOPE, f"v{i}", _LOC) for i in range(4)]


class _Listed(ir.Stmt):  # type: ignore[misc]  # (a class of Any)
    """A statement whose variables are listed from its attributes, as numba's are."""

    def __init__(self, **attributes: Any) -> None:
        self.__dict__.update(attributes)


class _Fixed(ir.Stmt):  # type: ignore[misc]
    """A statement listing its own variables (as numba's Yield and EnterWith do)."""

    def list_vars(self) -> list[Any]:
        return [_VARS[3]]


_LEAVES = st.sampled_from([_LOC, "name", 3, None, 2.5, types.int64, operator.add])
_VALUES = st.recursive(
    st.one_of(_LEAVES, st.sampled_from(_VARS), st.just(_Fixed())),
    lambda inner: st.one_of(
        st.lists(inner, max_size=4),
        st.lists(inner, max_size=4).map(tuple),
        st.dictionaries(st.sampled_from(["a", "b", "c"]), inner, max_size=3),
        st.dictionaries(st.sampled_from(["x", "y"]), inner, max_size=2).map(
            lambda attributes: _Listed(**attributes)
        ),
    ),
    max_leaves=12,
)


@given(_VALUES)
def test_variables_are_listed_as_numba_lists_them(value: Any) -> None:
    numbas = ir.Inst._rec_list_vars
    fast = compile_shortcuts._list_vars_method(ir.Var, ir.Inst)
    stmt = _Listed(value=value, loc=_LOC)
    expected = numbas(stmt, value)
    got = fast(stmt, value)
    assert [id(v) for v in got] == [id(v) for v in expected]


def test_variables_of_real_ir_are_listed_as_numba_lists_them() -> None:
    compiler: Any = importlib.import_module("numba.core.compiler")
    from navkit.planning.grid import _field_path_kernels

    func_ir = compiler.run_frontend(_field_path_kernels.extract_path.py_func)
    numbas = ir.Inst._rec_list_vars
    fast = compile_shortcuts._list_vars_method(ir.Var, ir.Inst)
    checked = 0
    for block in func_ir.blocks.values():
        for stmt in block.body:
            for value in (
                stmt.__dict__,
                *getattr(getattr(stmt, "value", None), "_kws", {}).values(),
            ):
                assert fast(stmt, value) == numbas(stmt, value)
                checked += 1
    assert checked > 500


# --- switched on only while navkit compiles ------------------------------------------------


def test_on_and_off_with_navkits_compiles() -> None:
    numbas = (ir.Inst._rec_list_vars, base.BaseContext.get_abi_sizeof, base._has_loc)
    compile_shortcuts.begin()
    try:
        assert "get_call_type" in vars(functions.Function)
        assert ir.Inst._rec_list_vars is not numbas[0]
        assert base.BaseContext.get_abi_sizeof is not numbas[1]
        assert base._has_loc is not numbas[2]
    finally:
        compile_shortcuts.end()
    assert "get_call_type" not in vars(functions.Function)
    assert (ir.Inst._rec_list_vars, base.BaseContext.get_abi_sizeof, base._has_loc) == numbas


# --- a real first use ---------------------------------------------------------------------

_COMPILED = """
import re, sys
import numpy as np
from navkit._shared import compile_shortcuts
compile_shortcuts.ENABLED = {enabled}
from navkit.planning import FieldDStar, astar
costs = np.ones((10, 10))
costs[3:7, 5] = 3.0
planner = FieldDStar(costs)
planner.plan((0, 0), (10, 7))
planner.update_costs([(3, 1), (3, 2)], np.inf)
planner.replan()
astar(np.where(costs > 1.0, np.inf, 1.0), (0, 0), (9, 9), method="jps")
from numba.core.dispatcher import Dispatcher
found = []
for module_name, module in sorted(sys.modules.items()):
    if not module_name.startswith("navkit.") or module is None:
        continue
    for name, value in sorted(vars(module).items()):
        if isinstance(value, Dispatcher) and value.py_func.__module__ == module_name:
            for sig in value.signatures:
                ir = re.sub(
                    "(?<=pickledata[.])[0-9]+|(?<=picklebuf[.])[0-9]+", "N", value.inspect_llvm(sig)
                )
                found.append(module_name + name + str(sig) + ir)
print(len(found), hash("".join(found)) if found else None)
"""


def _run(code: str, cache: Path) -> str:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache), "PYTHONHASHSEED": "0"}
    out = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        check=True, capture_output=True, text=True, timeout=300, env=env,
    )  # fmt: skip
    return out.stdout.strip()


@pytest.mark.slow
def test_field_dstar_and_jps_compile_to_the_same_ir_with_the_shortcuts(tmp_path: Path) -> None:
    on = _run(_COMPILED.format(enabled=True), tmp_path / "on")
    off = _run(_COMPILED.format(enabled=False), tmp_path / "off")
    assert int(on.split()[0]) >= 20  # the search, the walk, their helpers, the polyline, JPS
    assert on == off
