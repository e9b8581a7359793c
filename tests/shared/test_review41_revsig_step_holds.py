"""Review 41 (REVSIG): the main thread's signal holds in numba's lock steps, fresh eyes.

``compile_gc`` begins ``interrupts.StepHolds`` as the main thread starts to
take numba's compiler lock (numba's report of the acquire, before the wait),
so that a signal's handler raising in a lock step cannot leave the lock held.
Where the holds still let it happen, hang, or keep what they should not:

* A signal whose handler does not raise (a program's first Ctrl-C asking for a
  clean stop; the second stops at once) delivered after the holds begin but
  before the lock is taken (numba's report of the acquire, or the wait while
  another thread compiles) ended its hold (``StepHold.hold`` restores the hold
  when the lock is not held: meant for a wait ended by the handler's
  exception), though the wait went on and the compile followed with that
  signal unheld. The second Ctrl-C as numba let go of the lock then left the
  lock held by the main thread for good.
* A wait ended by one signal's exception, and a Ctrl-C in navkit's acquire
  wrapper before it ends the holds: the Ctrl-C's hold ended alone, the others
  stayed (``getsignal`` still navkit's), and the next compile reused them with
  Ctrl-C unheld: its Ctrl-C at numba's release left the lock held.
* With a profiler active (``sys.setprofile``: cProfile, profilers), a signal
  held in a step reached at a function's entry spun for ever: CPython 3.11
  checks for pending signals again at the same function entry after running a
  handler while tracing, and the hold made its signal pending again there each
  time. Review 41's WAKEUP fixes hand it on from a profile function instead,
  in front of a program's Python one (``sys.settrace``: coverage, pdb; or
  ``sys.setprofile`` with a function); under cProfile's C profiler (review 42,
  SIGFIX) from the trace slot.
* A handler installed during the compile (by another signal's handler run
  there) for a signal whose handler was ``SIG_DFL`` as the holds began was not
  held: its exception at numba's release left the lock held.
* The last ended holds stayed in ``compile_gc._LOCK_HOLD`` until the next
  compile, and with them the program's handlers from before (a bound method
  keeps its object alive after the program has dropped it).

Each probe runs in a fresh interpreter; the signals are raised at chosen points
(numba's event listeners, a profile function), not on timers.
"""

from __future__ import annotations

import signal
import sys

import pytest

from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

_SECOND_AT_THE_RELEASE = r"""
import json, signal, sys
import numba
from navkit._shared.jit import load_numba

load_numba()
from numba.core import event
from numba.core.compiler_lock import _CompilerLock, global_compiler_lock as lock

SIGNUM = int(sys.argv[1])
came = []

def graceful(signum, frame):
    # A program's handler: the first signal asks for a clean stop, the second stops now.
    came.append(signum)
    if len(came) >= 2:
        raise KeyboardInterrupt

signal.signal(SIGNUM, graceful)
sent = []

class FirstAtTheStart(event.Listener):
    # Registered after navkit's listener: numba's report of the outermost acquire,
    # navkit's holds begun, the lock not yet taken (as in a wait for another thread).
    def on_start(self, ev):
        if not sent and not lock.is_locked():
            sent.append("first")
            signal.raise_signal(SIGNUM)

    def on_end(self, ev):
        pass

event.register("numba:compiler_lock", FirstAtTheStart())
release = _CompilerLock.release.__code__

def second_at_the_release(frame, ev, arg):
    # The second signal as numba's outermost release begins (the lock held once).
    if ev == "call" and frame.f_code is release and len(sent) == 1:
        if "count=1" in repr(lock._lock):
            sent.append("second")
            sys.setprofile(None)
            signal.raise_signal(SIGNUM)

sys.setprofile(second_at_the_release)
try:
    try:
        numba.njit(lambda x: x + 1)(1)
    finally:
        sys.setprofile(None)
    len(())  # a signal held in a step comes at the next delivery point
    outcome = "ran"
except KeyboardInterrupt:
    outcome = "stopped"
back = signal.getsignal(SIGNUM) is graceful
print(json.dumps([sent, len(came), outcome, lock.is_locked(), back]))
"""


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGUSR1], ids=["SIGINT", "SIGUSR1"])
def test_a_signal_handled_before_the_lock_is_taken_is_still_held_in_its_steps(
    signum: signal.Signals,
) -> None:
    sent, calls, outcome, locked, back = probe_outcome(_SECOND_AT_THE_RELEASE, str(int(signum)))
    assert sent == ["first", "second"]
    assert calls == 2
    assert outcome == "stopped"
    assert back is True
    assert locked is False  # was True: numba's compiler lock held by the main thread for good


_HELD_WHILE_PROFILED = r"""
import cProfile, json, os, signal, sys
import numba
from numba.core import event
from numba.core.compiler_lock import global_compiler_lock as lock

MODE = sys.argv[1]
armed = []
sent = []

class AtTheRelease(event.Listener):
    # Registered before navkit's: numba's report of the outermost release runs this,
    # then navkit's listener, inside numba's release (a lock step).
    def on_start(self, ev):
        pass

    def on_end(self, ev):
        if armed and not sent and not lock.is_locked():
            sent.append(1)
            signal.raise_signal(signal.SIGINT)

event.register("numba:compiler_lock", AtTheRelease())
from navkit._shared import interrupts
from navkit._shared.jit import load_numba

# The step hold's handler, counted: run again and again at one delivery point is the
# spin (it never ended). Counted only: it calls navkit's, its frame one more outside.
handler = interrupts.StepHold.hold
runs = [0]

def counted(self, signum, frame):
    runs[0] += 1
    if runs[0] > 20000:
        print(json.dumps(["spins", runs[0], sent]), flush=True)
        os._exit(0)
    return handler(self, signum, frame)

interrupts.StepHold.hold = counted
load_numba()
armed.append(1)

def noted(frame, ev, arg):  # a profiler's or a debugger's function
    return None

profiler = cProfile.Profile()
if MODE == "cprofile":
    profiler.enable()
elif MODE == "profile":
    sys.setprofile(noted)
else:
    sys.settrace(noted)
try:
    try:
        numba.njit(lambda x: x + 1)(1)
    finally:
        profiler.disable()
        sys.setprofile(None)
        sys.settrace(None)
    len(())
    outcome = "ran"
except KeyboardInterrupt:
    outcome = "interrupted"
print(json.dumps([outcome, sent, lock.is_locked()]))
"""


def test_a_signal_held_while_a_debugger_traces_does_not_spin() -> None:
    # sys.settrace (coverage, pdb): spun before review 41's WAKEUP fix (32cf518), which
    # hands a held signal on from a profile function when the profile slot is free.
    out = probe_outcome(_HELD_WHILE_PROFILED, "trace")
    assert out == ["interrupted", [1], False]  # was ["spins", 20001, [1]]


def test_a_signal_held_while_a_python_profiler_runs_does_not_spin() -> None:
    # sys.setprofile with a Python function: spun until review 41's WAKEUP fix
    # (0376bbb), which calls it in front of navkit's watch.
    out = probe_outcome(_HELD_WHILE_PROFILED, "profile")
    assert out == ["interrupted", [1], False]  # was ["spins", 20001, [1]]


def test_a_signal_held_while_cprofile_runs_does_not_spin() -> None:
    out = probe_outcome(_HELD_WHILE_PROFILED, "cprofile")
    assert out == ["interrupted", [1], False]  # was ["spins", 20001, [1]]


_CTRL_C_AS_THE_WAIT_ENDS = r"""
import json, signal, sys
import numba
from navkit._shared import compile_gc
from navkit._shared.jit import load_numba

load_numba()
from numba.core import event
from numba.core.compiler_lock import _CompilerLock, global_compiler_lock as lock

def alarm(signum, frame):  # a time-out
    raise TimeoutError

def note(signum, frame):  # a service's SIGTERM handler noting a stop request
    pass

signal.signal(signal.SIGALRM, alarm)
signal.signal(signal.SIGTERM, note)
plan = []

class AlarmAtTheStart(event.Listener):
    # After navkit's listener: the holds begun, the lock not yet taken (as in a wait
    # for another thread); the alarm's exception ends the acquire.
    def on_start(self, ev):
        if plan == ["alarm"] and not lock.is_locked():
            plan.append("alarm sent")
            signal.raise_signal(signal.SIGALRM)

    def on_end(self, ev):
        pass

event.register("numba:compiler_lock", AlarmAtTheStart())
ending = compile_gc._end_lock_hold.__code__
release = _CompilerLock.release.__code__

def profile(frame, ev, arg):
    if ev != "call":
        return
    if frame.f_code is ending and plan == ["alarm", "alarm sent"]:
        # A Ctrl-C as navkit's acquire wrapper, its wait ended, ends the holds.
        plan.append("ctrl-c sent")
        sys.setprofile(None)
        signal.raise_signal(signal.SIGINT)
    elif frame.f_code is release and plan == ["release"] and "count=1" in repr(lock._lock):
        # The next compile's Ctrl-C as numba's outermost release begins.
        plan.append("ctrl-c sent")
        sys.setprofile(None)
        signal.raise_signal(signal.SIGINT)

def compile_once(value):
    sys.setprofile(profile)
    try:
        try:
            numba.njit(lambda x: x + value)(1)
        finally:
            sys.setprofile(None)
        len(())
        return "ran"
    except KeyboardInterrupt:
        return "interrupted"
    except TimeoutError:
        return "timed out"

plan.append("alarm")
first = compile_once(1)
back = [
    signal.getsignal(signal.SIGINT) is signal.default_int_handler,
    signal.getsignal(signal.SIGALRM) is alarm,
    signal.getsignal(signal.SIGTERM) is note,
]
plan[:] = ["release"]
second = compile_once(2)
print(json.dumps([first, back, second, plan, lock.is_locked()]))
"""


def test_a_ctrl_c_as_a_failed_waits_holds_end_leaves_no_hold_behind() -> None:
    first, back, second, plan, locked = probe_outcome(_CTRL_C_AS_THE_WAIT_ENDS)
    assert first == "interrupted"
    assert back == [True, True, True]  # SIGTERM's was navkit's hold
    assert second == "interrupted"
    assert plan == ["release", "ctrl-c sent"]
    assert locked is False  # was True: the next compile's Ctrl-C left the lock held


_HANDLERS_OBJECT = r"""
import gc, json, signal, weakref
import numba
from navkit._shared.jit import load_numba

load_numba()

class Node:
    # A program's object whose method handles a signal (a ROS 2 node's, a server's).
    def on_signal(self, signum, frame):
        pass

node = Node()
alive = weakref.ref(node)
signal.signal(signal.SIGUSR1, node.on_signal)
numba.njit(lambda x: x + 1)(1)  # the main thread's holds in front of it meanwhile
signal.signal(signal.SIGUSR1, signal.SIG_DFL)
del node
gc.collect()
print(json.dumps(alive() is None))
"""


def test_a_handlers_object_is_not_kept_after_the_holds_end() -> None:
    assert probe_outcome(_HANDLERS_OBJECT) is True


_INSTALLED_MID_COMPILE = r"""
import json, signal, sys
import numba
from navkit._shared.jit import load_numba

load_numba()
from numba.core import event
from numba.core.compiler_lock import _CompilerLock, global_compiler_lock as lock

def stop(signum, frame):  # a service's SIGTERM handler
    raise SystemExit(3)

def arm(signum, frame):  # a program's SIGUSR1 handler, installing the SIGTERM one
    signal.signal(signal.SIGTERM, stop)

signal.signal(signal.SIGUSR1, arm)
plan = []

class MidCompile(event.Listener):
    # numba's report of the compile's start: the lock taken, navkit's holds begun
    # (SIGTERM's handler still SIG_DFL then, so not held).
    def on_start(self, ev):
        if not plan:
            plan.append("usr1")
            signal.raise_signal(signal.SIGUSR1)

    def on_end(self, ev):
        pass

event.register("numba:compile", MidCompile())
release = _CompilerLock.release.__code__

def profile(frame, ev, arg):
    # SIGTERM as numba's outermost release begins (the lock held once).
    if ev == "call" and frame.f_code is release and plan == ["usr1"]:
        if "count=1" in repr(lock._lock):
            plan.append("term")
            sys.setprofile(None)
            signal.raise_signal(signal.SIGTERM)

sys.setprofile(profile)
try:
    try:
        numba.njit(lambda x: x + 1)(1)
    finally:
        sys.setprofile(None)
    len(())
    outcome = "ran"
except SystemExit:
    outcome = "exited"
print(json.dumps([plan, outcome, lock.is_locked()]))
"""


def test_a_handler_installed_during_the_compile_is_held_at_the_release() -> None:
    plan, outcome, locked = probe_outcome(_INSTALLED_MID_COMPILE)
    assert plan == ["usr1", "term"]
    assert outcome == "exited"
    assert locked is False  # was True: numba's compiler lock held for good
