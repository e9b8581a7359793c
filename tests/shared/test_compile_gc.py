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


@pytest.mark.parametrize("enabled", [True, False])
def test_compiling_a_navkit_kernel_pauses_and_restores_the_collector(
    enabled: bool, tmp_path: Path
) -> None:
    out = _run(
        f"""
        import numpy as np
        from navkit.planning import astar
        if not {enabled}:
            gc.disable()
        astar(np.ones((4, 4)), (0, 0), (3, 3))
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
