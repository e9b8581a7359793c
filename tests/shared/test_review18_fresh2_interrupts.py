"""Ctrl-C while navkit imports numba outside ``load_numba`` (a fresh-eyes review).

``navkit warmup`` asks whether numba's JIT is disabled before it loads numba
(``jit_disabled``), which imported numba without holding a Ctrl-C back: from
Python (``navkit.cli.main(["warmup"])`` in a notebook) an interrupt landing in
that import left numba half imported, and every later navkit kernel call in
the process failed ("module 'numba' has no attribute 'core'").
"""

from __future__ import annotations

import signal
import sys

import pytest

from interrupt_points import CTRL_C_IN_NUMBA_IMPORT
from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(
    not hasattr(signal, "raise_signal") or sys.platform == "win32",
    reason="needs POSIX signals raised in-process",
)

_INTERRUPTED_WARMUP = r"""
import contextlib, io, json, signal, sys
import numpy as np

""" + CTRL_C_IN_NUMBA_IMPORT + r"""
from navkit.cli import main
from navkit.mapping import OccupancyGrid
assert "numba" not in sys.modules
sys.meta_path.insert(0, Interrupt())
outcome = {}
err = io.StringIO()
with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
    try:
        outcome["code"] = main(["warmup"])
    except KeyboardInterrupt:
        outcome["code"] = "KeyboardInterrupt"
outcome["said"] = err.getvalue().strip().splitlines()
outcome["fired"] = Interrupt.fired
outcome["handler restored"] = signal.getsignal(signal.SIGINT) is signal.default_int_handler
grid = OccupancyGrid(np.zeros((4, 5)), resolution=0.5)
try:
    outcome["later"] = grid.world_to_cell([[0.3, 1.2], [2.2, 0.1]]).tolist()
except Exception as exc:
    outcome["later"] = f"{type(exc).__name__}: {exc}"
print(json.dumps(outcome))
"""


def test_ctrl_c_in_warmups_first_question_leaves_navkit_working() -> None:
    outcome = probe_outcome(_INTERRUPTED_WARMUP)
    assert outcome["fired"]
    # The command stops as on any Ctrl-C: one line, exit code 130 ...
    assert outcome["code"] == 130
    assert outcome["said"] == ["navkit: interrupted"]
    assert outcome["handler restored"]
    # ... and navkit keeps working in the process afterwards.
    assert outcome["later"] == [[2, 0], [0, 4]]


_WAIT_FOR_ANOTHER_COMPILE = r"""
import gc, json, os, signal, threading
import numpy as np
import numba  # the program uses numba itself
from numba.core.compiler_lock import global_compiler_lock
from navkit.planning import astar

holding, release, released = threading.Event(), threading.Event(), threading.Event()

def users_compile():
    # Stands for a long compile of the program's own kernel in another thread.
    with global_compiler_lock:
        holding.set()
        release.wait(20)
    released.set()

threading.Thread(target=users_compile, daemon=True).start()
holding.wait()
threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT)).start()
outcome = {}
try:
    astar(np.ones((6, 6)), (0, 0), (5, 5))  # navkit's first kernel call: loads numba
    outcome["first"] = "returned"
except KeyboardInterrupt:
    outcome["first"] = "KeyboardInterrupt"
outcome["while the other compile ran"] = not released.is_set()
release.set()
released.wait(20)
outcome["later"] = len(astar(np.ones((6, 6)), (0, 0), (5, 5)).cells)
outcome["gc"] = gc.isenabled()
print(json.dumps(outcome))
"""


def test_ctrl_c_while_waiting_for_another_threads_compile_arrives_at_once() -> None:
    # Only numba's import is held back: navkit's first call waiting for numba's
    # compiler lock (another thread compiling, for as long as that takes) is
    # interrupted as usual, and loads numba at the next call.
    outcome = probe_outcome(_WAIT_FOR_ANOTHER_COMPILE)
    assert outcome["first"] == "KeyboardInterrupt"
    assert outcome["while the other compile ran"]
    assert outcome["later"] == 6
    assert outcome["gc"]
