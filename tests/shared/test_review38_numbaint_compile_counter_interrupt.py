"""A Ctrl-C as a helper's compile ends must not make its callers uncompilable (review 38).

Found by NUMBAINT's hunt for interrupts that break numba for the process: numba
counts each dispatcher's compiles under way (``with self._compiling_counter:``
around every compile and cache load) and takes a call to a dispatcher counted as
compiling, met while typing another kernel, for recursion. Its counter's
``__exit__`` is Python code, where CPython runs a pending signal handler on
entry: a Ctrl-C arriving there left a navkit helper counted as compiling for
good, and every later compile of a kernel calling it failed ("unsupported
recursion"): A*'s first call, interrupted there, could not be made again in the
process. navkit's dispatchers now count in a C lock (``jit._CompileDepth``).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from subprocess_probe import probe_outcome

_PROBE = r"""
import json, signal, sys
import numpy as np
from navkit._shared.jit import load_numba
from navkit.geometry import rollout
from navkit.planning import AStarPlanner

load_numba()
from numba.core.dispatcher import CompilingCounter, Dispatcher

fired = []

def helper(dispatcher):
    return bool(getattr(dispatcher, "targetoptions", {}).get("no_cpython_wrapper"))

def profile(frame, event, arg):
    # A Ctrl-C as a helper's compile leaves its count of compiles: numba's counter's
    # __exit__ entered, or the C lock's __exit__ returned (the next point after it).
    if fired:
        return
    if event == "call" and frame.f_code is CompilingCounter.__exit__.__code__:
        dispatcher = frame.f_back.f_locals.get("self")
    elif (
        event == "c_return"
        and frame.f_code is Dispatcher.compile.__code__
        and getattr(arg, "__name__", "") == "__exit__"
        and getattr(arg, "__self__", None)
        is getattr(frame.f_locals["self"]._compiling_counter, "_lock", 0)
    ):
        dispatcher = frame.f_locals["self"]
    else:
        return
    if helper(dispatcher):
        fired.append(dispatcher.py_func.__name__)
        sys.setprofile(None)
        signal.raise_signal(signal.SIGINT)

grid = np.ones((6, 7))
grid[2, 1:6] = np.inf
sys.setprofile(profile)
try:
    AStarPlanner(grid).plan((0, 0), (5, 6))
    first = "ran"
except KeyboardInterrupt:
    first = "interrupted"
finally:
    sys.setprofile(None)
later = []
for call in (
    lambda: AStarPlanner(grid).plan((0, 0), (5, 6)).cost,
    lambda: rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.0]]), 1.0)[-1, 0].item(),
):
    try:
        later.append(round(call(), 9))
    except Exception as exc:
        later.append(f"{type(exc).__name__}: {exc}"[:300])
print(json.dumps([fired, first, later]))
"""


def test_a_ctrl_c_as_a_helpers_compile_ends_leaves_its_callers_compilable(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))  # a cold compile in the probe
    fired, first, later = probe_outcome(_PROBE, timeout=600)
    assert fired, "no helper compiled: the probe no longer reaches a helper's count"
    assert first == "interrupted"
    # Round the wall's open end: 3 straight steps, 2 diagonal ones, 4 straight.
    assert later == [round(7 + 2 * 2**0.5, 9), 1.0]
