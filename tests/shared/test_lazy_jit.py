"""numba is imported on first use: kernels are stand-ins until then (issue 17).

Each check runs in a fresh interpreter, where numba has not been imported yet.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap


def _run(code: str) -> str:
    out = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        check=True, capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    return out.stdout.strip()


MODULES = ["navkit", "navkit.geometry", "navkit.mapping", "navkit.planning",
           "navkit.estimation", "navkit.control", "navkit.sim"]  # fmt: skip


def test_importing_navkit_does_not_import_numba() -> None:
    # One interpreter imports them in turn: after each import, is numba loaded? (An
    # import that loads numba shows at its own line: each later one would too.)
    out = _run(
        f"""
        import importlib, sys
        for module in {MODULES!r}:
            importlib.import_module(module)
            print(module, "numba" in sys.modules)
        """
    )
    assert out.splitlines() == [f"{module} False" for module in MODULES]


def test_first_call_loads_numba_and_puts_dispatchers_in_place_of_stand_ins() -> None:
    out = _run(
        """
        import sys
        import numpy as np
        from navkit._shared.jit import LazyKernel, numba_loaded
        from navkit.planning import astar
        import navkit.planning.grid._astar as public_layer
        import navkit.planning.grid._astar_kernels as kernels
        before = (numba_loaded(), type(kernels.grid_search) is LazyKernel,
                  type(public_layer.grid_search) is LazyKernel)
        path = astar(np.ones((5, 5)), (0, 0), (4, 4))
        from numba.core.dispatcher import Dispatcher
        stand_ins = [
            f"{name}.{key}" for name, module in list(sys.modules.items())
            if name.startswith("navkit")
            for key, value in vars(module).items() if type(value) is LazyKernel
        ]
        print(before, numba_loaded(), isinstance(kernels.grid_search, Dispatcher),
              public_layer.grid_search is kernels.grid_search, stand_ins, len(path.cells))
        """
    )
    assert out == "(False, True, True) True True True [] 5"


def test_a_stand_in_keeps_working_where_it_was_copied() -> None:
    out = _run(
        """
        import numpy as np
        from navkit.mapping._grid_kernels import world_to_cell_kernel as held
        from navkit._shared.jit import LazyKernel
        kept = {"k": held}  # a container the loader does not look into
        out = np.empty((1, 2), dtype=np.int64)
        ok = kept["k"](np.array([[0.7, 0.2]]), 0.0, 0.0, 0.0, 0.5, out)
        import navkit.mapping._grid_kernels as module
        print(type(kept["k"]) is LazyKernel, ok, out.tolist(), len(kept["k"].signatures),
              kept["k"].py_func is module.world_to_cell_kernel.py_func)
        """
    )
    assert out == "True True [[0, 1]] 1 True"


def test_functions_decorated_after_loading_are_dispatchers_at_once() -> None:
    out = _run(
        """
        from navkit._shared.jit import typed_njit
        from numba.core.dispatcher import Dispatcher
        def make():
            @typed_njit(cache=False)
            def inner(x):
                return x + 1
            return inner
        closure = make()  # a closure loads numba when it is made
        @typed_njit(cache=False)
        def late(x):
            return 3 * x
        print(isinstance(closure, Dispatcher), isinstance(late, Dispatcher), closure(1), late(2))
        """
    )
    assert out == "True True 2 6"


def test_bound_numba_names_arrive_with_numba() -> None:
    out = _run(
        """
        from navkit._shared.jit import bind_numba_names, load_numba
        namespace = {}
        bind_numba_names(namespace, "numba.cpython.unsafe.numbers", ctz="trailing_zeros")
        before = "ctz" in namespace
        load_numba()
        print(before, namespace["ctz"].__name__)
        """
    )
    assert out == "False trailing_zeros"


def test_stand_in_reports_missing_dunder_attributes_without_loading_numba() -> None:
    out = _run(
        """
        import copy, sys
        from navkit._shared.jit import LazyKernel
        def f(x):
            return x
        kernel = LazyKernel(f, {"cache": False})
        print(hasattr(kernel, "__len__"), kernel.__name__, kernel.__wrapped__ is f,
              "numba" in sys.modules)
        """
    )
    assert out == "False f True False"
