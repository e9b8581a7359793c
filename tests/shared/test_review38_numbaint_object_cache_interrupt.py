"""A Ctrl-C in llvmlite's object-cache callback during a cache load crashes the process.

Found by NUMBAINT's sampled interrupts of a kernel's load from numba's cache
(review 38): LLVM asks llvmlite for a kernel's cached object code through a
ctypes callback (``ExecutionEngine._raw_object_cache_getbuffer``, Python code). A
``KeyboardInterrupt`` raised inside it is reported by ctypes as ignored ("Exception
ignored on calling ctypes callback function") and the callback returns without
filling in the buffer: LLVM reads garbage and the process dies with SIGSEGV (a
notebook's kernel dies; exit code -11). navkit holds Ctrl-C only during numba's
import and its registry refreshes, not during the machine code's loading.

Fixed in review 39 (NUMBAINT2): while the main thread holds numba's compiler
lock, navkit's handler holds a Ctrl-C back only inside the locks' own steps and
the object-cache callbacks (``navkit._shared.interrupts.StepHold``, begun by
``navkit._shared.compile_gc``), and delivers it at the next delivery point after.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from subprocess_probe import UNHELD_SIGINT, probe_outcome

_CALL = "rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.5]]), 0.5)"

_PROBE = r"""
import json, signal, sys
import numpy as np
from navkit._shared.jit import load_numba
from navkit.geometry import rollout

load_numba()
fired = []

""" + UNHELD_SIGINT + r"""
def profile(frame, event, arg):
    # A Ctrl-C as LLVM's object-cache callback runs (Python's handler in place).
    back = frame.f_back
    if (
        event == "call"
        and back is not None
        and back.f_code.co_name == "_raw_object_cache_getbuffer"
        and unheld()
    ):
        fired.append(True)
        sys.setprofile(None)
        signal.raise_signal(signal.SIGINT)

sys.setprofile(profile)
try:
    CALL
    first = "ran"
except KeyboardInterrupt:
    first = "interrupted"
finally:
    sys.setprofile(None)
again = CALL[-1, 0].item()
print(json.dumps([bool(fired), first, round(again, 9)]))
""".replace("CALL", _CALL)


def test_a_ctrl_c_as_a_kernel_loads_from_the_cache_does_not_crash(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    cold = subprocess.run(  # fills the cache
        [sys.executable, "-c", "import numpy as np\nfrom navkit.geometry import rollout\n" + _CALL],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert cold.returncode == 0, cold.stderr
    fired, first, again = probe_outcome(_PROBE, timeout=300)
    assert fired, "llvmlite no longer loads cached object code through a Python callback"
    assert first == "interrupted"
    assert again == pytest.approx(0.494807918509, abs=1e-9)  # the kernel works after
