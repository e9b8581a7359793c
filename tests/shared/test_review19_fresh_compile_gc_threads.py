"""compile_gc's pauses stay balanced over many compiles in two threads at once (review 19).

Session 22 made the end of a pause ask numba's compiler lock whether this
thread still holds it (``global_compiler_lock.is_locked()``, per thread)
instead of counting lock events. Two threads here compile alternately a
function marked as navkit's (its ``__module__``, as ``compile_gc`` tells them
apart) and a user's, each a new one, so that they contend for the lock and
hand it over in both orders. A sampler checks throughout that the collector is
never off while no pause is under way; at the end no pause is left, the
collector is on and numba's own methods are back (the shortcuts off). In a
fresh process (nothing paused or compiled before). A 1,000-compile run of the
same probe (500 a thread) took 195 s on the review machine and ended balanced.
"""

from __future__ import annotations

import pytest

from subprocess_probe import probe_outcome

_PROBE = """
import gc, json, sys, threading, time
import numba
from navkit._shared import compile_gc, compile_shortcuts, jit
jit.load_numba()
N = int(sys.argv[1])

def make(i, navkit_marked):
    namespace = {}
    exec(f"def f(x):\\n    return x * {i} + {i}", namespace)
    f = namespace["f"]
    f.__module__ = "navkit.review19_probe" if navkit_marked else "user_probe"
    return numba.njit(f)

bad = []
stop = False
def sampler():
    while not stop:
        with compile_gc._PAUSE_LOCK:
            if compile_gc._PAUSES == 0 and not gc.isenabled():
                bad.append(1)
        time.sleep(0.0005)

barrier = threading.Barrier(2)
errors = []
def worker(parity):
    try:
        barrier.wait()
        for i in range(N):
            make(2 * i + parity, (i + parity) % 2 == 0)(1.0)
    except BaseException as exc:
        errors.append(repr(exc))

watch = threading.Thread(target=sampler)
watch.start()
threads = [threading.Thread(target=worker, args=(p,)) for p in (0, 1)]
for t in threads: t.start()
for t in threads: t.join()
stop = True
watch.join()
print(json.dumps(dict(errors=errors, off_without_pause=len(bad), pauses=compile_gc._PAUSES,
    gc=gc.isenabled(), shortcuts=compile_shortcuts.active(), count=compile_shortcuts._COUNT,
    saved=len(compile_shortcuts._SAVED))))
"""


@pytest.mark.slow
def test_alternating_compiles_in_two_threads_leave_no_pause() -> None:
    out = probe_outcome(_PROBE, "30", timeout=600)
    assert out == {"errors": [], "off_without_pause": 0, "pauses": 0, "gc": True,
                   "shortcuts": False, "count": 0, "saved": 0}  # fmt: skip
