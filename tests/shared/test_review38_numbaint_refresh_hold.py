"""numba's registry refreshes are held against Ctrl-C (review 38, NUMBAINT).

numba refreshes its registries at every compile and cache load, reading them
through generators (``numba.core.utils.stream_list``) that a KeyboardInterrupt
ends for good: every later compile or cache load in the process failed with
"generator raised StopIteration" (REVMM's test,
``test_review38_revmm_numba_refresh_interrupt.py``, a navkit kernel's first
call). ``navkit._shared.jit`` now holds a Ctrl-C back during the refreshes of
numba's CPU target and typing contexts. These tests pin what that means for a
user's own kernels compiled in the same process, for threads, and that the
wrappers are put in place once. Each runs in a fresh process (numba's contexts
are the process's).
"""

from __future__ import annotations

from subprocess_probe import probe_outcome

_USER_KERNEL = r"""
import json, signal, sys
import numba
import numpy as np
from navkit._shared.jit import load_numba
from navkit.geometry import rollout

load_numba()

@numba.njit
def user(x):
    return x + 1

fired = []

def profile(frame, event, arg):
    # A Ctrl-C as numba reads its registry stream, in the refresh of the user's compile.
    if event == "c_return" and frame.f_code.co_name == "stream_list" and not fired:
        fired.append(True)
        sys.setprofile(None)
        signal.raise_signal(signal.SIGINT)

sys.setprofile(profile)
try:
    user(1)
    first = "ran"
except KeyboardInterrupt:
    first = "interrupted"
finally:
    sys.setprofile(None)

@numba.njit
def other(x):
    return 2.0 * x

later = []
for call in (
    lambda: user(2),
    lambda: other(1.5),
    lambda: rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.0]]), 1.0)[-1, 0].item(),
):
    try:
        later.append(call())
    except Exception as exc:
        later.append(f"{type(exc).__name__}: {exc}")
default = signal.getsignal(signal.SIGINT) is signal.default_int_handler
print(json.dumps([bool(fired), first, later, default]))
"""


def test_a_ctrl_c_in_a_users_compile_is_raised_and_numba_keeps_working() -> None:
    # The user's own kernels refresh the same contexts: the Ctrl-C is held to the
    # refresh's end, then raised out of their compile as before; numba (theirs and
    # navkit's) works afterwards. Before the fix: RuntimeError for every later compile.
    fired, first, later, default = probe_outcome(_USER_KERNEL, timeout=300)
    assert fired, "numba no longer reads its registries through stream_list"
    assert first == "interrupted"
    assert later == [3, 3.0, 1.0]
    assert default  # Python's handler is back


_WHO_HOLDS = r"""
import json, signal, sys, threading
import numba
from navkit._shared.jit import load_numba
from navkit._shared import interrupts

load_numba()
from numba.core.registry import cpu_target

seen = {}

def watch(name):
    def profile(frame, event, arg):
        # The SIGINT handler in place while numba reads a registry stream.
        if event == "call" and frame.f_code.co_name == "stream_list" and name not in seen:
            handler = signal.getsignal(signal.SIGINT)
            seen[name] = getattr(handler, "__func__", None) is interrupts._Hold.hold
    return profile

def compile_one(name):
    @numba.njit
    def kernel(x):
        return x - 1
    sys.setprofile(watch(name))
    try:
        return kernel(5)
    finally:
        sys.setprofile(None)

results = {"main": compile_one("main")}
thread = threading.Thread(target=lambda: results.__setitem__("thread", compile_one("thread")))
thread.start()
thread.join()

# Installed once: load_numba's wrappers are there, and a second install changes nothing.
from navkit._shared import jit
target, typing = cpu_target.target_context, cpu_target.typing_context
before = (target.refresh, typing.refresh)
jit._hold_refreshes(target)
once = (target.refresh, typing.refresh) == before
marked = all(getattr(f, jit._HELD_MARK, False) for f in before)
# A refresh takes one hold, not one per nested refresh (the target's calls the typing's).
holds = []
start = interrupts._Hold.start
def counting(self):
    if type(self).__name__ != "StepHold":  # the compiler lock's (review 39), not a refresh's
        holds.append(1)
    return start(self)
interrupts._Hold.start = counting
target.refresh()
typing.refresh()
interrupts._Hold.start = start
print(json.dumps([seen, results, once, marked, len(holds),
                  signal.getsignal(signal.SIGINT) is signal.default_int_handler]))
"""


def test_the_hold_is_on_the_main_thread_only_installed_once_and_not_nested() -> None:
    seen, results, once, marked, holds, default = probe_outcome(_WHO_HOLDS, timeout=300)
    # Held while the main thread's compile reads the registries (not before the fix);
    # a worker thread's compile, where no signal lands, installs no handler.
    assert seen == {"main": True, "thread": False}
    assert results == {"main": 4, "thread": 4}
    assert once and marked
    assert holds == 2  # one each for the two refreshes, the nested one not held again
    assert default
