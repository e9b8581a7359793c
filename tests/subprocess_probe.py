"""Run a probe script in a fresh Python process and read the JSON it prints last.

For what only a fresh process shows: numba not yet imported, signal handlers as
at start-up, the collector and numba's settings untouched by the test session.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

#: Probe source defining ``unheld()``: whether a Ctrl-C raised now would meet what a
#: real one meets (Python's own handler, or navkit's ``StepHold`` of numba's and
#: llvmlite's lock steps), not one of navkit's deferrals. The probe imports ``signal``.
UNHELD_SIGINT = """
def unheld():
    # What a real Ctrl-C meets: Python's own handler, or navkit's hold of the
    # locks' steps (review 39: in place while the main thread holds numba's
    # compiler lock), not one of navkit's deferrals.
    handler = signal.getsignal(signal.SIGINT)
    held_in_steps = type(getattr(handler, "__self__", None)).__name__ == "StepHold"
    return handler is signal.default_int_handler or held_in_steps
"""


#: Source of ``send_during_the_wait(signums, all_sent)`` for probes whose main thread
#: forks while another thread holds numba's compiler lock: a thread to run it sends
#: each signal once the fork's hook is seen waiting for the lock (not on timers,
#: which a loaded machine can make fire after ``os.fork`` has returned), then sets
#: the event ``all_sent``. And of ``in_the_forks_wait()``: whether the main thread's
#: fork is waiting in its hook now, for the thread holding the lock to ask as it
#: lets go (whether the fork waited for it, told without a clock: a loaded machine
#: can pause the main thread longer than any margin). Imports what it uses.
FORK_WAIT_SENDER = """
import os, sys, threading, time

def in_the_forks_wait():
    frame = sys._current_frames().get(threading.main_thread().ident)
    while frame is not None and frame.f_code.co_name != "_take_for_fork":
        frame = frame.f_back  # (a held signal's handler may be running above it)
    return frame is not None

def send_during_the_wait(signums, all_sent):
    main, frame = threading.main_thread().ident, None
    while frame is None or frame.f_code.co_name != "_take_for_fork":
        time.sleep(0.002)  # until the fork's hook waits for the compiler lock
        frame = sys._current_frames().get(main)
    for signum in signums:
        os.kill(os.getpid(), signum)
        time.sleep(0.05)
    all_sent.set()
"""


#: Source of ``send_in_the_lock_wait(signum)`` for probes whose main thread waits for
#: numba's compiler lock held by another thread: run in a thread of its own, it sends
#: ``signum`` to the main thread once that thread is seen in the wait (in numba's
#: ``acquire``, at its call of the lock's own), not after a fixed sleep or timer, which
#: a loaded machine can outlast before the main thread gets there. Imports what it uses.
LOCK_WAIT_SENDER = """
import signal, sys, threading, time

def send_in_the_lock_wait(signum):
    from numba.core.compiler_lock import _CompilerLock
    code = _CompilerLock.acquire.__code__
    lines = __import__("inspect").getsourcelines(code)
    line = lines[1] + next(i for i, text in enumerate(lines[0]) if "_lock.acquire(" in text)
    main, frame = threading.main_thread().ident, None
    while frame is None or frame.f_code is not code or frame.f_lineno != line:
        time.sleep(0.002)
        frame = sys._current_frames().get(main)
    del frame
    time.sleep(0.05)  # (the lock's wait began as the main thread let go of the GIL)
    signal.pthread_kill(main, signum)
"""


def probe_outcome(script: str, *args: str, timeout: float = 300) -> Any:
    """The JSON value on the last line ``script`` prints (it must exit 0).

    Python warnings are off in the probe (``PYTHONWARNINGS=ignore``), so that a
    dependency's warning cannot land on the line read.
    """
    done = subprocess.run(
        [sys.executable, "-c", script, *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        env={**os.environ, "PYTHONWARNINGS": "ignore"},
        check=False,
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


def jit_outcome(
    script: str, *, disable_jit: bool, warnings_as_errors: bool = False, timeout: float = 300
) -> Any:
    """The JSON value on the last line ``script`` prints, run with numba's JIT on or
    off (``NUMBA_DISABLE_JIT=1``, any inherited ``NUMBA_DISABLE_JIT*`` dropped).

    With ``warnings_as_errors`` the probe runs under ``-W error``: a warning the
    kernels raise only as plain Python (numpy's overflow notices) fails it.
    """
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_DISABLE_JIT")}
    if disable_jit:
        env["NUMBA_DISABLE_JIT"] = "1"
    flags = ["-W", "error"] if warnings_as_errors else []
    done = subprocess.run(
        [sys.executable, *flags, "-c", script],
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


#: Put first in a :func:`cold_outcome` script: ``compiled`` then lists, as
#: ``(module, qualname)``, every function numba compiles (its ``numba:compile``
#: events; a module numba does not know is "").
COMPILES_LISTED = """
from numba.core import event as _event
compiled = []
class _CompileListener(_event.Listener):
    def on_start(self, ev):
        d = ev.data["dispatcher"]
        compiled.append((d.py_func.__module__ or "", d.py_func.__qualname__))
    def on_end(self, ev):
        pass
_event.register("numba:compile", _CompileListener())
"""


def cold_outcome(script: str, *, timeout: float = 300) -> Any:
    """The JSON value on the last line ``script`` prints, run with an empty numba cache.

    A new temporary ``NUMBA_CACHE_DIR`` of its own: every kernel the script
    meets is compiled, as on a user's first use (it must exit 0).
    """
    with tempfile.TemporaryDirectory(prefix="navkit-cold-probe-") as cache:
        done = subprocess.run(
            [sys.executable, "-c", script],
            env={**os.environ, "NUMBA_CACHE_DIR": cache},
            capture_output=True,
            text=True,
            timeout=timeout,
            check=False,
        )
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


#: Run before a bounds-checked script: the checks are on, or the process fails.
_CHECKS_ON = """
import numba as _numba, numpy as _np
@_numba.njit
def _past_the_end(a):
    return a[len(a)]
try:
    _past_the_end(_np.zeros(2))
except IndexError:
    pass
else:
    raise SystemExit("numba's bounds checks are off: NUMBA_BOUNDSCHECK=1 had no effect")
"""


def bounds_checked(script: str, cache: Path, *, timeout: float = 900) -> list[str]:
    """The lines ``script`` prints, run compiled with numba's bounds checks on (it must exit 0).

    A fresh process with ``NUMBA_BOUNDSCHECK=1`` and the empty numba cache
    ``cache`` of its own (a cached kernel compiled without the checks would be
    loaded otherwise), where an index past an array's end raises ``IndexError``;
    ``NUMBA_DISABLE_JIT`` is dropped, since compiled code is what is checked.
    The process first checks that an index past an array's end does raise.
    """
    env = dict(os.environ, NUMBA_BOUNDSCHECK="1", NUMBA_CACHE_DIR=str(cache))
    env.pop("NUMBA_DISABLE_JIT", None)
    done = subprocess.run(
        [sys.executable, "-c", _CHECKS_ON + script],
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout.splitlines()
