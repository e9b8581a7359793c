"""The garbage collector pauses while numba compiles navkit's kernels, and only then.

Each check runs in a fresh interpreter with an empty numba cache, so that the
kernels really compile.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

# A listener registered after navkit's: it records, at the start of every
# compile, which function compiles and whether the collector is enabled.
_RECORDER = """
import gc
from navkit._shared.jit import load_numba
load_numba()
from numba.core import event
seen = []
class Recorder(event.Listener):
    def on_start(self, ev):
        seen.append((ev.data["dispatcher"].py_func.__module__, gc.isenabled()))
    def on_end(self, ev):
        pass
event.register("numba:compile", Recorder())
"""


def _run(code: str, cache: Path) -> str:
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    out = subprocess.run(
        [sys.executable, "-c", _RECORDER + textwrap.dedent(code)],
        check=True, capture_output=True, text=True, timeout=600, env=env,
    )  # fmt: skip
    return out.stdout.strip()


# What compiles: one kernel (a few seconds cold) or astar's several (the slow run).
_COMPILES = [
    pytest.param(
        "OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.1)"
        ".world_to_cell(np.zeros((2, 2)), continuous=True)",
        id="one-kernel",
    ),
    pytest.param("astar(np.ones((4, 4)), (0, 0), (3, 3))", id="astar", marks=pytest.mark.slow),
]


@pytest.mark.parametrize("call", _COMPILES)
@pytest.mark.parametrize("enabled", [True, False])
def test_compiling_a_navkit_kernel_pauses_and_restores_the_collector(
    enabled: bool, call: str, tmp_path: Path
) -> None:
    out = _run(
        f"""
        import numpy as np
        from navkit.mapping import OccupancyGrid
        from navkit.planning import astar
        if not {enabled}:
            gc.disable()
        {call}
        navkit_compiles = [on for module, on in seen if module.startswith("navkit")]
        print(len(navkit_compiles) > 0, any(navkit_compiles), gc.isenabled())
        """,
        tmp_path,
    )
    # Compiled with the collector off; afterwards in the state the caller left it.
    assert out == f"True False {enabled}"


def test_a_users_own_kernel_compiles_with_the_collector_running(tmp_path: Path) -> None:
    out = _run(
        """
        from numba import njit
        @njit
        def twice(x):
            return 2 * x
        twice(3)
        print([on for module, on in seen if module == "__main__"], gc.isenabled())
        """,
        tmp_path,
    )
    assert out == "[True] True"


def test_a_failed_compile_restores_the_collector(tmp_path: Path) -> None:
    out = _run(
        """
        import numpy as np
        from navkit.mapping._grid_kernels import world_to_continuous_kernel
        out = np.zeros((1, 2))
        try:  # a string where an array belongs: numba starts compiling, then fails typing
            world_to_continuous_kernel("points", 0.0, 0.0, 0.0, 1.0, out)
        except Exception as error:
            failed = type(error).__name__
        print(failed, [on for module, on in seen if module.startswith("navkit")], gc.isenabled())
        """,
        tmp_path,
    )
    assert out == "TypingError [False] True"



def test_loading_numba_from_inside_a_users_compile_keeps_the_pause_whole(tmp_path: Path) -> None:
    """A user's kernel that calls a navkit kernel loads numba in the middle of its compile.

    The listeners were then installed inside numba's compiler lock: its releases
    outnumbered the acquires they had seen, the count stayed low for good, and
    every later pause ended at an inner release of the lock (45 collections
    during astar's first compile instead of 1).
    """
    code = """
        import gc
        from numba import njit
        from navkit._shared import se2, jit
        assert not jit.numba_loaded()

        @njit
        def users(x):
            return se2.sinc(x) + 1.0  # typing it loads numba, inside the compile

        users(0.5)
        import numpy as np
        from navkit.planning import astar
        grid = np.ones((4, 4))
        runs = []
        gc.callbacks.append(lambda phase, info: runs.append(info) if phase == "start" else None)
        astar(grid, (0, 0), (3, 3))  # compiles several navkit kernels
        print(len(runs) < 10, gc.isenabled())
        """
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    out = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        check=True, capture_output=True, text=True, timeout=600, env=env,
    )  # fmt: skip
    assert out.stdout.strip() == "True True"
