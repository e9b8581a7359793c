"""The held-signal watch's slots and hand-on (review 42, SIGFIX).

``interrupts.StepHold`` holds a signal that lands in a step which must not be
cut short and sets ``interrupts._watch`` as the main thread's profile function
until the step is done; the watch hands the signal on after the step. These
probes check what review 41 left: the watch put back by a program that saved
``sys.getprofile()`` while it was in place (it stayed for good), and cProfile
in the profile slot (the signal made pending again at every point of the step:
a byte each, and on Python 3.11 a spin at a function's entry, REVSIG's strict
xfail). Each runs in a fresh interpreter; the signals are sent at fixed points,
not on timers.
"""

from __future__ import annotations

import sys

import pytest
from test_review41_wakeup_held_signal_wakeup_fd import _SETUP as WAKEUP_SETUP

from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")

#: Probe preamble: review 41's (a wakeup fd, SIGUSR1/SIGUSR2 handlers noting their calls,
#: ``holds(inside)`` and ``written()``), with the wakeup fd set.
_SETUP = WAKEUP_SETUP + "signal.set_wakeup_fd(writer.fileno())\n"

_SAVED_AND_RESTORED = (
    _SETUP
    + r"""
MODE = sys.argv[1]

def program(frame, event, arg):  # a program's own profile function
    pass

if MODE == "program":
    sys.setprofile(program)
before = sys.getprofile()
inside = [True]
steps = holds(inside)
os.kill(os.getpid(), signal.SIGUSR1)  # held in the step: the watch in place
saved = sys.getprofile()  # a library saving the profile function around its work
len(str(calls))
inside[0] = False
len(str(calls))  # SIGUSR1 handed on: the watch gone
sys.setprofile(saved)  # the library putting back what it saved
for _ in range(3):
    len(())
back = sys.getprofile() is before
# A signal in a later step: handed on once, after it.
inside[0] = True
os.kill(os.getpid(), signal.SIGUSR2)
for _ in range(20):
    len(str(calls))
held = list(calls)
inside[0] = False
len(str(calls))
for _ in range(3):
    len(())
back_again = sys.getprofile() is before
sys.setprofile(None)
steps.end()
print(json.dumps([saved is interrupts._watch, back, held, calls, back_again, written()]))
"""
)


@pytest.mark.parametrize("mode", ["none", "program"])
def test_a_watch_saved_and_put_back_by_the_program_leaves(mode: str) -> None:
    # Before: the watch stayed the profile function for good (a walk of the stack
    # at every event), and with a program's profile function in front of it that
    # function was lost (the watch called nothing, the program's events stopped).
    saved_watch, back, held, calls, back_again, written = probe_outcome(
        _SAVED_AND_RESTORED, mode, timeout=120
    )
    assert saved_watch  # the library saved the watch
    assert back  # was False: the watch in place for good
    assert held == [10]
    assert calls == [10, 12]
    assert back_again
    assert written == [10, 12]  # one byte a signal


_UNDER_CPROFILE = (
    _SETUP
    + r"""
import cProfile

def work():
    return len(str(calls))

inside = [True]
steps = holds(inside)
profiler = cProfile.Profile()
profiler.enable()
in_place = sys.getprofile()
os.kill(os.getpid(), signal.SIGUSR1)
for _ in range(20):
    work()  # function entries inside the step: held
held = list(calls)
inside[0] = False
work()  # handed on at this entry
after = list(calls)
kept = sys.getprofile() is in_place
tracer = sys.gettrace()
profiler.disable()
steps.end()
print(json.dumps([held, after, kept, tracer is None, steps.restored, written()]))
"""
)


def test_under_cprofile_a_held_signal_comes_once_after_its_step() -> None:
    # Before: made pending again at every point of the step, a byte each (20 or
    # more), and on Python 3.11 the process hung at a function's entry in the step
    # (the time-out: REVSIG's spin).
    outcome = probe_outcome(_UNDER_CPROFILE, timeout=60)
    held, after, kept, no_tracer, restored, written = outcome
    assert held == [] and after == [10]
    assert kept and no_tracer and restored
    assert written == [10]


_UNDER_CPROFILE_AND_A_TRACER = (
    _SETUP
    + r"""
import cProfile

def tracer(frame, event, arg):  # a debugger's or coverage's trace function
    return None

def work():
    return len(str(calls))

inside = [True]
steps = holds(inside)
profiler = cProfile.Profile()
profiler.enable()
sys.settrace(tracer)
os.kill(os.getpid(), signal.SIGUSR1)
for _ in range(5):
    len(str(calls))  # C calls only inside the step: made pending again at each
held = list(calls)
inside[0] = False
work()
after = list(calls)
kept = sys.gettrace() is tracer
sys.settrace(None)
profiler.disable()
steps.end()
print(json.dumps([held, after, kept, len(written()) >= 1]))
"""
)


def test_under_cprofile_and_a_tracer_a_held_signal_still_comes_once() -> None:
    # Both slots taken: made pending again at every point of the step, as before
    # review 42 (a byte each; the one case left).
    held, after, kept, wrote = probe_outcome(_UNDER_CPROFILE_AND_A_TRACER)
    assert held == [] and after == [10]
    assert kept and wrote


_LANDING_AS_THE_HAND_ON_BEGINS = (
    _SETUP
    + r"""
def alarm(signum, frame):  # a time-out
    raise TimeoutError

signal.signal(signal.SIGALRM, alarm)

class Landing(list):
    # Emulates SIGALRM (outside any step: delivered at once) landing as the pending
    # call's hand-on takes its entry off the list, before the handler is called.
    def remove(self, item):
        super().remove(item)
        if sys._getframe(1).f_code.co_name == "__bool__" and not landed:
            landed.append(True)
            os.kill(os.getpid(), signal.SIGALRM)
            len(())

landed = []
interrupts._DUE = Landing()
inside = [True]
steps = holds(inside)
os.kill(os.getpid(), signal.SIGUSR1)  # held in the step
len(str(calls))
inside[0] = False
raised = []
try:
    len(str(calls))  # SIGUSR1 due here
except TimeoutError:
    raised.append("alarm")
for _ in range(3):
    len(())
after_the_step = list(calls)
steps.end()
for _ in range(3):
    len(())
print(json.dumps([raised, after_the_step, calls, steps.restored, interrupts._HANDING_ON[0]]))
"""
)


def test_a_signal_due_as_another_raises_where_its_pending_call_begins_is_not_lost() -> None:
    # Before (REVHOLD's finding in review 42's first pending call): taken off the
    # list outside the try block, SIGUSR1 was neither handed on nor made pending
    # again, its hold never ended, and the count of hand-ons under way stayed 1.
    raised, after_the_step, calls, restored, handing = probe_outcome(_LANDING_AS_THE_HAND_ON_BEGINS)
    assert raised == ["alarm"]  # the emulated landing happened
    assert after_the_step == [10] and calls == [10]
    assert restored and handing == 0
