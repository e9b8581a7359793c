"""A Ctrl-C as llvmlite's LLVM lock is taken leaves it held for good (review 38, NUMBAINT).

Found by NUMBAINT's sampled interrupts of a kernel's cache load: llvmlite takes
its global LLVM lock around every LLVM call (``ffi._LLVMLock.__enter__``: the
lock's ``acquire``, then the callbacks numba registers, which report the
``numba:llvm_lock`` event, Python code). A Ctrl-C arriving in a callback raised
``KeyboardInterrupt`` out of ``__enter__`` after the lock was taken: the ``with``
never began, and the main thread held the LLVM lock for the rest of the process.
Its own later calls work (the lock is re-entrant), but any other thread's compile
or cache load waits for ever. Where the LLVM call was made by a finalizer (an
llvmlite object's ``__del__`` during the load), Python also reported the
interrupt as ignored, and the user's Ctrl-C was lost.

Fixed in review 39 (NUMBAINT2): while the main thread holds numba's compiler
lock, navkit's handler holds a Ctrl-C back only inside the locks' own steps and
the object-cache callbacks (``navkit._shared.interrupts.StepHold``, begun by
``navkit._shared.compile_gc``), and delivers it at the next delivery point after.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from subprocess_probe import UNHELD_SIGINT, probe_outcome

_PROBE = r"""
import json, os, signal, sys, threading
import numba
import numpy as np
from navkit._shared.jit import load_numba
from navkit.geometry import rollout
import llvmlite.binding.ffi as ffi

load_numba()
fired = []

""" + UNHELD_SIGINT + r"""
def profile(frame, event, arg):
    # A Ctrl-C in numba's callback as llvmlite takes its LLVM lock (Python's handler in place).
    if (
        event == "call"
        and frame.f_code.co_name == "enter_fn"
        and frame.f_back is not None
        and frame.f_back.f_code.co_name == "__enter__"
        and unheld()
    ):
        fired.append(True)
        sys.setprofile(None)
        signal.raise_signal(signal.SIGINT)

sys.setprofile(profile)
try:
    rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.5]]), 0.5)
except KeyboardInterrupt:
    pass
finally:
    sys.setprofile(None)
held = bool(ffi.lib._lock._lock._is_owned())

@numba.njit
def user(x):
    return x + 1

box = []
thread = threading.Thread(target=lambda: box.append(user(1)), daemon=True)
thread.start()
thread.join(60)
print(json.dumps([bool(fired), held, box == [2]]))
os._exit(0)  # the thread may still wait for the lock
"""


def test_a_ctrl_c_as_llvmlite_takes_its_lock_leaves_it_free(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))  # a cold compile in the probe
    fired, held, thread_compiled = probe_outcome(_PROBE, timeout=300)
    assert fired, "llvmlite no longer calls numba's lock callbacks"
    assert not held
    assert thread_compiled
