"""Pause Python's cyclic garbage collector while numba compiles navkit's kernels (private).

numba's compiler allocates many objects (IR nodes, types, LLVM wrappers) that
live until the compile ends, so during a first use the cyclic collector runs
hundreds of times, each oldest-generation pass scanning everything the process
holds, and frees nothing useful: on Field D*'s first use (plan, update, replan)
about 600 collections and 0.3 s of 3.9 s of CPU (issue 17; 0.08 s of the
0.48 s of a use that loads the kernels from numba's cache, most of it numba's
own initialisation).

* :func:`paused` disables the collector for a block and restores its previous
  state; :func:`navkit._shared.jit.load_numba` imports numba and initialises
  its compiler inside it.
* :func:`install` registers two listeners with numba's event API
  (``numba.core.event``): at the start of the compile of a navkit kernel the
  collector is disabled, and it is restored to its previous state when the
  compiling thread releases numba's compiler lock (after the kernel, its
  callees and its cache file are done, or the compile failed). Compiles of
  other code (the user's own kernels) are left alone, and loading a kernel
  from numba's cache changes nothing. The same two listeners switch
  :mod:`navkit._shared.compile_shortcuts` on and off (cheaper numba internals
  for the compile: error-message markup, compile-flag comparisons).
* The compiler lock's listener also puts a
  :class:`navkit._shared.interrupts.StepHold` in front of the ``SIGINT``
  handler while the main thread holds numba's compiler lock (any compile or
  cache load, the user's too), so that a Ctrl-C does not cut short the steps of
  :func:`_lock_steps`: a ``KeyboardInterrupt`` there left numba's compiler
  lock or llvmlite's LLVM lock held for good (every later compile or cache load
  in another thread waited for ever), or crashed the process during a cache
  load (review 39). Elsewhere a Ctrl-C is delivered at once. So does one in
  front of every other signal's Python handler
  (:class:`navkit._shared.interrupts.StepHolds`): a ``signal.alarm``
  time-out's or a ``SIGTERM`` handler's exception left the lock held the same
  way (review 40); its steps include numba's registry refresh and the
  collector's pause at a compile's start, where navkit defers Ctrl-C alone. The hold is begun
  as numba reports an acquire, before the wait for the lock, so numba's global
  lock's ``acquire`` is wrapped (:func:`_wrap_acquire`, the one attribute navkit
  sets on a numba object) to end it when the wait ends in another signal's
  handler's exception, and a compile in such a handler does not end it.

The collector's switch is one for the whole process while compiles and
pauses are per thread (threads of a ROS 2 executor using navkit for the first
time at once), so the pauses are counted process-wide: the first to start
records whether the collector was running and the last to end restores that.
With a record per thread, a thread that took numba's compiler lock before the
previous holder's pause had ended compiled with the collector switched back
on, having recorded it as off.

A ``gc.disable()`` made (in another thread) while a pause is under way is
undone when the last pause ends: the collector is already off, so the call
leaves no trace to tell it from the pause, and only hooking ``gc.disable``
could see it. ``gc.enable()`` meanwhile is kept (the state restored is "on"
either way, or left on). docs/compilation.md ("Threads and processes") tells
users.

A child forked while other threads pause (a ``multiprocessing`` "fork"
worker started during a first use elsewhere) has only the forking thread: the
count keeps that thread's pauses, and with none left the collector is
restored there (``os.register_at_fork``). A fork waits for numba's compiler
lock (review 35): numba holds it for every compile and every load of a kernel
from its cache, and a child forked while another thread held it inherited it
held by a thread that does not exist there, so its first kernel call waited
for ever (a ``sweep`` over a ``fork`` process pool started while a ROS 2
callback made a first call never ended). The fork now happens between
compiles, as CPython's own fork waits for its import lock. It waits for
navkit's import of numba in another thread too (:data:`NUMBA_IMPORT`,
review 36): a child forked during the import (the first half second of a
process's first kernel call) inherited Python's locks of the modules under
way, held by a thread it does not have, and hung at its first kernel call.
A Ctrl-C during a fork's hooks is held and raised in the parent after the
fork (:func:`navkit._shared.interrupts.held_for_fork`): Python ignores an
exception in a fork hook and forks anyway, so one during a wait was lost, and
the fork made without the lock; and one between a lock's acquire and its
record, or in the after hook before its releases, left the lock held for good
(review 37).

Garbage made meanwhile is collected as usual afterwards; the peak memory of a
compile rises by a few tens of MB (25 MB measured on Field D*'s).
"""

from __future__ import annotations

import contextlib
import gc
import importlib

# Before this module registers its fork hooks (and numba's import, which uses
# logging): a hook registered later runs its ``before`` part earlier, so
# logging's would hold logging's lock while this module's waits for a numba
# import that needs it (numba's modules call logging.getLogger). And one
# registered while a fork waits has its ``after`` parts run without its
# ``before`` ("cannot release un-acquired lock").
import logging  # noqa: F401
import os
import re
import sys
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from types import CodeType, FrameType, MethodType
from typing import Any

from navkit._shared import compile_shortcuts
from navkit._shared.interrupts import (
    StepHolds,
    held_for_fork,
    interrupts_deferred,
    release_in_child,
    release_in_parent,
    release_others_in_child,
    rewatch,
)

__all__ = ["install", "paused"]

_INSTALLED: list[Any] = []

#: Guards the two below (re-entrant: a collection run inside could end a pause).
_PAUSE_LOCK = threading.RLock()
#: Pauses under way in every thread.
_PAUSES = 0
#: Whether the collector ran when the first of them began.
_RESUME = False
#: This thread's share of them (``pauses``): all that survives a fork.
_THREAD = threading.local()
#: The main thread's (the forking thread's in a forked child).
_MAIN = threading.main_thread().ident


def _begin_pause() -> None:
    global _PAUSES, _RESUME
    with _PAUSE_LOCK:
        if _PAUSES == 0:
            _RESUME = gc.isenabled()
            gc.disable()
        _PAUSES += 1
        _THREAD.pauses = getattr(_THREAD, "pauses", 0) + 1


def _end_pause() -> None:
    global _PAUSES
    with _PAUSE_LOCK:
        _PAUSES -= 1
        _THREAD.pauses = getattr(_THREAD, "pauses", 0) - 1
        if _PAUSES == 0 and _RESUME:
            gc.enable()


#: The main thread's hold of Ctrl-C (and of every other signal with a Python handler)
#: in the steps of numba's and llvmlite's locks (see
#: :func:`_lock_steps`), in place from numba's report of an acquire (before the wait
#: for the lock) to the outermost release, or to an exception ending the wait (see
#: :func:`_wrap_acquire`); None before, and once it has ended (as long as a held
#: signal is still to come, it is kept).
_LOCK_HOLD: list[StepHolds | None] = [None]

#: Held while navkit imports numba (jit.load_numba, jit.jit_disabled): a fork waits for it.
NUMBA_IMPORT = threading.RLock()


def _forks() -> list[list[Any]]:
    """This thread's forks under way, innermost last: each the Ctrl-C hold and locks it took.

    Per thread: two threads may fork at once (one waiting in its ``before``
    hook for the locks the other's fork holds), and each after-fork hook must
    let go of its own thread's only. A stack: a signal handler may fork while
    this thread's own fork waits, and its hooks must not let go of the outer
    fork's hold or locks.
    """
    forks: list[list[Any]] | None = getattr(_THREAD, "forks", None)
    if forks is None:
        forks = _THREAD.forks = []
    return forks


def _held_for_fork() -> list[Any]:
    """The locks the innermost fork under way in this thread has taken, else empty."""
    forks = _forks()
    return list(forks[-1][1:]) if forks else []


def _numba_compiler_lock() -> Any:
    """The re-entrant lock in numba's ``global_compiler_lock``; None before numba is imported."""
    module = sys.modules.get("numba.core.compiler_lock")
    lock = getattr(getattr(module, "global_compiler_lock", None), "_lock", None)
    return lock if callable(getattr(lock, "release", None)) else None


def _take_locks_for_fork(record: list[Any]) -> None:
    """Take numba's compiler lock, then navkit's import lock, each recorded in ``record``."""
    # The compiler lock first: a thread compiling a user's kernel that calls a
    # navkit one takes it, then NUMBA_IMPORT (load_numba); a thread importing
    # numba takes NUMBA_IMPORT alone (numba's import never takes the compiler
    # lock), and the compiler lock after letting it go. Before numba's import
    # there is no compiler lock to take: if it appears while this waits for the
    # import, the import lock is let go and both are taken in order.
    nested = _inside_navkit_lock()
    while True:
        lock = _numba_compiler_lock()
        if lock is not None:
            _take_for_fork(lock, record, nested=nested)
        _take_for_fork(NUMBA_IMPORT, record, nested=nested)
        if lock is not None or _numba_compiler_lock() is None:
            return
        _release_locks(record)


class _NotTaken:
    """A lock a fork was made without (see :func:`_take_for_fork`): made anew in the child."""

    __slots__ = ("lock",)

    def __init__(self, lock: Any) -> None:
        self.lock = lock

    def release(self) -> None:
        """Nothing to let go: it was not taken."""


def _inside_navkit_lock() -> bool:
    """Whether this thread holds a navkit lock that a compiling thread takes under numba's.

    Then this fork is made from inside navkit's own code (a signal handler
    that forks, run where the main thread was), and the thread holding numba's
    compiler lock or navkit's import lock may be waiting for that lock (the
    lock order is numba's compiler lock, navkit's import lock, then the others).
    """
    jit = sys.modules.get("navkit._shared.jit")
    jit_lock = getattr(getattr(jit, "_LOCK", None), "_lock", None)
    for lock in (NUMBA_IMPORT, jit_lock, _PAUSE_LOCK, compile_shortcuts._LOCK):
        owned = getattr(lock, "_is_owned", None)
        if owned is not None and owned():
            return True
    return False


#: navkit's modules whose functions take the locks of :func:`_inside_navkit_lock`.
_LOCKING_FILES = frozenset(
    os.path.join(os.path.dirname(os.path.abspath(__file__)), name)
    for name in ("compile_gc.py", "compile_shortcuts.py", "jit.py", "locks.py")
)


def _take_for_fork(lock: Any, record: list[Any], *, nested: bool) -> None:
    """Take ``lock`` for a fork and record it; nested (see below), perhaps go without it.

    A fork made while this thread holds one of navkit's locks that come after
    ``lock`` in the lock order (:func:`_inside_navkit_lock`: a signal handler
    forking where the main thread was in navkit's code) waited for ever when the
    thread holding ``lock`` was waiting for that one (review 38: a thread
    compiling holds numba's compiler lock and takes the collector's pause lock
    at its compile's start and end, navkit's kernel table lock at a first
    kernel call). Such a fork waits only while that thread is elsewhere than
    in navkit's own locking code; found waiting there (the same frame and
    instruction for 10 ms), it forks without ``lock``, recorded as
    :class:`_NotTaken`, and the child makes the lock anew.
    """
    if not nested or lock.acquire(blocking=False):
        if not nested:
            lock.acquire()
        record.append(lock)
        return
    seen: tuple[int, int] | None = None
    still = 0
    while not lock.acquire(timeout=0.002):
        where = _where_holder_waits(lock)
        still = still + 1 if where is not None and where == seen else 0
        seen = where
        if still >= 5:
            record.append(_NotTaken(lock))
            return
    record.append(lock)


def _where_holder_waits(lock: Any) -> tuple[int, int] | None:
    """Where ``lock``'s holder is (frame, instruction) if in navkit's locking code, else None."""
    match = re.search(r"owner=(\d+)", repr(lock))
    frame = sys._current_frames().get(int(match.group(1))) if match else None
    if frame is None or os.path.abspath(frame.f_code.co_filename) not in _LOCKING_FILES:
        return None
    return id(frame), frame.f_lasti


def _renew_not_taken(record: list[Any]) -> None:
    """In a forked child, make anew the locks its fork was made without (held by a lost thread)."""
    global NUMBA_IMPORT
    for item in record:
        if not isinstance(item, _NotTaken):
            continue
        if item.lock is NUMBA_IMPORT:
            NUMBA_IMPORT = threading.RLock()
        module = sys.modules.get("numba.core.compiler_lock")
        compiler = getattr(module, "global_compiler_lock", None)
        if compiler is not None and getattr(compiler, "_lock", None) is item.lock:
            compiler._lock = threading.RLock()


def _before_fork() -> None:
    # A fork waits for numba's compiler lock and for navkit's import of numba
    # under way in another thread: numba holds the one for every compile and
    # load of a kernel from its cache, and a child forked meanwhile inherited it
    # held by a thread that does not exist there, so its first kernel call
    # waited for ever; a child forked during the import (Python's locks of the
    # modules being imported held) hung at its first use of numba. Taken
    # without numba's events (its lock object's own acquire reports one),
    # before _PAUSE_LOCK, as a compiling thread takes them (this handler runs
    # before compile_shortcuts', registered earlier, which takes that module's
    # lock). A Ctrl-C from the hook's start to os.fork's return is held and
    # raised in the parent after os.fork returns: raised here, Python would
    # report it as ignored in this hook and fork without the lock; and raised
    # between a lock's acquire and its record, or in the after hook before its
    # releases, it left the lock held for good (review 37: numba's compiler
    # lock held by the main thread, every other thread's compile waiting for
    # ever). So is every other signal with a Python handler (a SIGTERM handler
    # raising SystemExit left them held the same way). Only a signal before
    # the hold is in place reaches the hook (its handler runs there: the hold
    # is recorded before it starts, undone by the after hook however far it
    # got, and the hook goes on; a handler's exception is kept and raised as
    # os.fork returns, see held_for_fork). The hold costs about 10 µs a fork
    # from the main thread, but a whole fork takes longer than without it
    # (review 37: 1.06 -> 1.47 ms at os.fork's return): page copies after the
    # fork, as the handlers are put back in pages the child now shares. Put back
    # without signal.signal's enum conversions and ctypes' buffer making, the
    # hold adds about half what it did (review 38: 0.61 -> 0.34 ms on a loaded
    # 2-core machine, 300 alternating forks with and without it, medians).
    # A fork from a signal handler run inside navkit's own locking code does not
    # wait for ever for a thread waiting for the lock it interrupted
    # (_take_for_fork).
    record: list[Any] = []
    early: BaseException | None = None
    while True:
        # A signal's handler raising before the hold is in place: kept by the
        # hold and raised as os.fork returns (review 38), and the hook goes on
        # (held_for_fork's own start keeps the ones landing in it).
        try:
            if not record:
                forks = _forks()
                if not forks or forks[-1] is not record:
                    forks.append(record)
                held_for_fork(sys._getframe(1), record)  # os.fork's caller; record[0]
            else:
                record[0].start()  # goes on from where it was cut short
            break
        except BaseException as error:
            if early is None:
                early = error
    if early is not None and record[0].early is None:
        record[0].early = early
    _take_locks_for_fork(record)
    # Held across the fork, so the child copies a count and a state that agree;
    # compile_shortcuts' lock too, taken here under the hold: its own hooks,
    # which ran outside it, left it held when a second Ctrl-C came in its after
    # hook (review 37: the first before the hold, cutting this hook short).
    nested = _inside_navkit_lock()
    _take_for_fork(_PAUSE_LOCK, record, nested=nested)
    _take_for_fork(compile_shortcuts._LOCK, record, nested=nested)


def _release_locks(record: list[Any]) -> None:
    """Let go of the locks ``record`` holds (after its first item, the hold), last first."""
    while len(record) > 1:
        record[-1].release()
        record.pop()


def _end_fork() -> Any:
    """This thread's innermost fork's Ctrl-C hold, its locks let go; None if there is none."""
    forks = _forks()
    if not forks:  # the before hook was cut short before it recorded its fork
        return None
    record = forks[-1]
    _release_locks(record)
    forks.pop()
    return record[0] if record else None  # the hold, if the hook got that far


def _after_fork_in_parent() -> None:
    release_in_parent(_end_fork())


def _after_fork_in_child() -> None:
    """Keep only the forking thread's pauses: the other threads do not exist here.

    Their pauses would never end, and the child would run with the collector
    off for good (a worker forked while another thread compiled a kernel).
    numba's compiler lock and navkit's import lock, held by this thread across
    the fork, are let go; a Ctrl-C held meanwhile was the parent's. Forked by
    another thread than the main one, the main thread's holds of Ctrl-C (its
    own fork waiting for this one's locks) are ended too: nothing here would.
    """
    global _PAUSE_LOCK, _PAUSES, _MAIN
    _PAUSE_LOCK = threading.RLock()  # the parent's is held, by this thread's twin
    others = _PAUSES > 0  # or none at all: then the collector's state is the user's
    _PAUSES = getattr(_THREAD, "pauses", 0)
    if others and _PAUSES == 0 and _RESUME:
        gc.enable()
    forks = _forks()
    if forks:
        _renew_not_taken(forks[-1])
    release_in_child(_end_fork())
    if threading.get_ident() != _MAIN:
        _MAIN = threading.get_ident()
        release_others_in_child()


if hasattr(os, "register_at_fork"):  # not on Windows, which cannot fork
    os.register_at_fork(
        before=_before_fork,
        after_in_parent=_after_fork_in_parent,
        after_in_child=_after_fork_in_child,
    )


def _is_navkit(dispatcher: Any) -> bool:
    module = getattr(getattr(dispatcher, "py_func", None), "__module__", None) or ""
    return module == "navkit" or module.startswith("navkit.")


#: The qualified name of :func:`navkit._shared.jit._hold_refreshes`' wrapper of numba's
#: registry refresh (a step of :func:`_lock_steps`), and its file.
_REFRESH_HOLD = (
    "_hold_refreshes.<locals>.held",
    os.path.join(os.path.dirname(os.path.abspath(__file__)), "jit.py"),
)


def _lock_steps(
    compiler_lock: Any, also: tuple[CodeType, ...] = ()
) -> Callable[[FrameType | None], bool]:
    """A test of the main thread's stack: is it inside a step a Ctrl-C must not cut short?

    The steps: Python code run while numba's compiler lock is taken or let go,
    between the ``acquire`` and the frame that will release it (the ``with``
    block, an ``ExitStack``'s callback), or between the ``with`` block's end and
    the ``release`` (its ``acquire``, ``__enter__``, ``release`` and ``__exit__``;
    ``ExitStack.enter_context`` and ``__exit__`` with it, as numba's dispatcher
    takes it: the whole ``__exit__`` of a dispatcher's own ExitStack while the lock
    is held, since between the pop of the lock's exit callback and its call the
    callback is nowhere to be seen); and any of llvmlite's Python code (``llvmlite.binding``), which
    keeps the ownership of LLVM's objects across its C calls: its LLVM lock's
    ``__enter__`` after the acquire (numba's callbacks report the event there)
    and ``__exit__`` (callbacks before the release), its object-cache callbacks
    (called by LLVM through ctypes: an exception inside was reported as ignored,
    and LLVM read the cached object code it was not given, SIGSEGV), a string's
    ``close`` (between LLVM's free and forgetting the pointer: a double free at
    its ``__del__``, found by review 39's sampled interrupts of a cache load), its
    objects' finalizers (a ``KeyboardInterrupt`` there is reported as ignored, and
    the Ctrl-C lost). A wait for the LLVM lock held by another thread (for one
    LLVM call, or a finalizer's) is held through too. The LLVM calls themselves
    are C code, which a Ctrl-C does not cut short anyway: one arriving during a
    long optimisation is raised as llvmlite returns to numba, microseconds after
    the C call. Steps of a name missing from the installed numba are left out.

    Two more hold other signals than Ctrl-C (review 40: navkit's deferrals of
    Ctrl-C, :func:`navkit._shared.interrupts.interrupts_deferred`, hold ``SIGINT``
    only, and another signal's handler raising in them did what a Ctrl-C did
    before them): numba's registry refresh with navkit's wrapper of it
    (:func:`navkit._shared.jit._hold_refreshes`: cut short, every later compile
    failed, "generator raised StopIteration"), and the code objects ``also``
    (the compile-start listener's pause: cut short, the collector stayed off).
    Both run only while the compiling thread holds numba's compiler lock.
    """

    # Each test: True (a step), None (not this frame; look further out).

    def always(frame: FrameType) -> bool | None:
        return True

    def compiler_lock_held(frame: FrameType) -> bool | None:
        return True if compiler_lock.is_locked() else None

    def entering_compiler_lock(frame: FrameType) -> bool | None:
        taking = compiler_lock.is_locked() and frame.f_locals.get("cm") is compiler_lock
        return True if taking else None

    dispatcher: Any = importlib.import_module("numba.core.dispatcher")
    dispatcher_file = os.path.abspath(dispatcher.__file__)

    def exiting_compiler_lock(frame: FrameType) -> bool | None:
        if not compiler_lock.is_locked():
            return None
        # numba's dispatchers' ExitStacks (their compile) hold the lock: between the
        # pop of its exit callback and the call the callback is in neither the
        # stack nor ``cb`` (review 40: a Ctrl-C there left the lock held for good).
        caller = frame.f_back
        if caller is not None and os.path.abspath(caller.f_code.co_filename) == dispatcher_file:
            return True
        stack = frame.f_locals.get("self")
        exits = [frame.f_locals.get("cb"), *getattr(stack, "_exit_callbacks", ())]
        letting_go = any(
            getattr(item[-1] if isinstance(item, tuple) else item, "__self__", None)
            is compiler_lock
            for item in exits
        )
        return True if letting_go else None

    lock_class = type(compiler_lock)
    ffi: Any = importlib.import_module("llvmlite.binding.ffi")
    llvmlite_code = os.path.dirname(os.path.abspath(ffi.__file__)) + os.sep
    named = (
        (lock_class, "__exit__", always),
        (lock_class, "release", always),
        (lock_class, "__enter__", compiler_lock_held),
        (lock_class, "acquire", compiler_lock_held),
        (contextlib.ExitStack, "enter_context", entering_compiler_lock),
        (contextlib.ExitStack, "__exit__", exiting_compiler_lock),
    )
    steps: dict[Any, Callable[[FrameType], bool | None]] = {}
    for owner, name, test in named:
        code = getattr(getattr(owner, name, None), "__code__", None)
        if code is not None:
            steps[code] = test
    #: Whether a file is llvmlite's, by name (each looked at once).
    files: dict[str, bool] = {}

    own = getattr(vars(compiler_lock).get("acquire"), "__code__", None)
    if own is not None:  # navkit's wrapper (see _wrap_acquire): a step as numba's acquire
        steps[own] = compiler_lock_held
    for code in also:
        steps[code] = always
    refresh_name, refresh_file = _REFRESH_HOLD

    def in_step(frame: FrameType | None) -> bool:
        while frame is not None:
            code = frame.f_code
            test = steps.get(code)
            if test is None:
                name = code.co_filename
                ours = files.get(name)
                if ours is None:
                    ours = files[name] = os.path.abspath(name).startswith(llvmlite_code)
                if not ours and code.co_qualname == refresh_name:
                    ours = os.path.abspath(name) == refresh_file
                test = always if ours else None
            step = test(frame) if test is not None else None
            if step is not None:
                return step
            frame = frame.f_back
        return False

    return in_step


def _acquire_under_way(acquire: CodeType, frame: FrameType | None) -> bool:
    """Whether ``frame`` or one further out runs ``acquire`` (numba's, waiting for the lock)."""
    while frame is not None:
        if frame.f_code is acquire:
            return True
        frame = frame.f_back
    return False


def _end_lock_hold(compiler_lock: Any, acquire: CodeType, frame: FrameType | None) -> None:
    """End the main thread's hold (:data:`_LOCK_HOLD`) if nothing of the lock is under way.

    Nothing is: the main thread does not hold numba's compiler lock, and no
    ``acquire`` (code ``acquire``) is waiting for it in ``frame`` or further out.
    One is when a signal's handler, run in the main thread's wait for the lock,
    compiles (review 39, REVC): the handler's compile takes and lets go of the
    lock inside the wait, and ending the hold at that release left the waiting
    compile without it (a Ctrl-C as it let go of the lock left the lock held for
    good). About 4 µs an outermost release in the main thread (a walk of its
    stack, some 15 frames; 54 releases in a cold ``warmup(workers=1)``).
    """
    hold = _LOCK_HOLD[0]
    if hold is None or threading.get_ident() != _MAIN or compiler_lock.is_locked():
        return
    if not _acquire_under_way(acquire, frame):
        hold.end()
        if hold.restored and _LOCK_HOLD[0] is hold:
            # Ended: not kept, nor the program's handlers it refers to, until the
            # next compile (a node's bound method, and the node; review 41, REVSIG).
            _LOCK_HOLD[0] = None


def _wrap_acquire(compiler_lock: Any) -> None:
    """Make ``compiler_lock.acquire`` end the main thread's hold when its wait ends in an exception.

    numba reports an acquire (and the hold is begun) before it waits for the
    lock held by another thread; the main thread's wait runs other signals'
    handlers, and one that raises (a ``signal.alarm`` time-out) ended the wait
    with no release to follow: navkit's ``SIGINT`` handler stayed in place
    after the call had failed (review 39, REVC). An instance attribute, a
    method bound to numba's one global lock: numba's ``__enter__`` calls
    ``self.acquire()``, and nothing of numba reads the attribute otherwise (nor
    the lock's ``__dict__``); its behaviour is numba's ``acquire`` (looked up
    on the class at each call, or the lock's own ``acquire`` set before this),
    one Python frame more, a step of :func:`_lock_steps` like numba's. Kept
    across a fork (it holds no state).
    """
    numba_acquire = type(compiler_lock).acquire
    before = vars(compiler_lock).get("acquire")  # another's, set before navkit's
    waiting: CodeType = numba_acquire.__code__

    def acquire(self: Any) -> None:
        try:
            if before is None:
                type(self).acquire(self)
            else:
                before()
        except BaseException:  # the wait cut short: no release will end the hold
            _end_lock_hold(self, waiting, sys._getframe())
            raise

    compiler_lock.acquire = MethodType(acquire, compiler_lock)


def _make_listeners() -> tuple[Any, Any]:
    """The listeners of numba's compile events and of its compiler lock."""
    # Any: numba's event module is not typed in every supported numba version.
    event: Any = importlib.import_module("numba.core.event")
    compiler_lock: Any = importlib.import_module("numba.core.compiler_lock").global_compiler_lock
    state = threading.local()
    waiting: CodeType = type(compiler_lock).acquire.__code__
    _wrap_acquire(compiler_lock)

    def begin_hold() -> None:
        rewatch()  # signals held for a profile function another took away: pending again
        hold = _LOCK_HOLD[0]
        if hold is not None and not hold.restored:
            # A handler installed since (by a handler run in the compile): held too.
            hold.extend()
            return
        hold = _LOCK_HOLD[0] = StepHolds(critical=in_lock_step, under_way=compiler_lock.is_locked)
        hold.begin()  # nothing put in place (SIG_IGN...): restored, the next acquire looks again

    class CompileStart(event.Listener):  # type: ignore[misc]  # (a class of Any)
        """Pause the collector, shortcuts on, when a navkit kernel's compile starts."""

        def on_start(self, ev: Any) -> None:
            data = ev.data if isinstance(ev.data, dict) else {}
            if getattr(state, "paused", False) or not _is_navkit(data.get("dispatcher")):
                return
            # A Ctrl-C held back (see LockRelease): all three, or none.
            with interrupts_deferred():
                _begin_pause()
                compile_shortcuts.begin()
                state.paused = True

        def on_end(self, ev: Any) -> None:
            """Nothing here: the collector resumes when the compiler lock is released."""

    in_lock_step = _lock_steps(compiler_lock, (CompileStart.on_start.__code__,))

    class LockRelease(event.Listener):  # type: ignore[misc]
        """Resume it (shortcuts off) when the compiling thread releases numba's compiler lock."""

        def on_start(self, ev: Any) -> None:
            # numba reports the start before it waits for the lock: nothing of the
            # pause here. In the main thread, Ctrl-C is held in the lock's own steps
            # until the outermost release (see _LOCK_HOLD).
            if threading.get_ident() == _MAIN:
                begin_hold()

        def on_end(self, ev: Any) -> None:
            # The lock itself tells whether this was the outermost release (it
            # is re-entrant), not a count of the events: numba reports an
            # acquire before it waits for the lock, so a wait that ends in an
            # exception (Ctrl-C while another thread compiles) counted an
            # acquire that never happened, and every later pause in the thread
            # outlived its compile for good (the collector off, the shortcuts
            # on); and a release whose acquire came before install() (numba
            # loaded from inside a compile, e.g. a user's kernel typing a navkit
            # one) would end a pause at an inner release, mid-compile.
            if getattr(state, "paused", False) and not compiler_lock.is_locked():
                # A Ctrl-C held back until the three are done: Python delivers
                # one on entering a function or after a C call returns, and
                # one landing between them left the pause (the collector off)
                # or the shortcuts on for the rest of the process. (Landing
                # before, it leaves the pause to the thread's next release.)
                with interrupts_deferred():
                    _end_pause()
                    compile_shortcuts.end()
                    state.paused = False
            # Not while an acquire further out waits for the lock (this was the
            # compile of a signal handler run in that wait): its own release ends it.
            _end_lock_hold(compiler_lock, waiting, sys._getframe())

    return CompileStart(), LockRelease()


@contextmanager
def paused() -> Iterator[None]:
    """Disable the collector for the block, then restore its previous state.

    The state restored is the one from before the first of the pauses under
    way in any thread (this block's, or a compile's), once the last ends.

    For navkit's own one-off work in the library's many allocations: importing
    numba and initialising its compiler (:func:`navkit._shared.jit.load_numba`).

    Examples
    --------
    >>> import gc
    >>> with paused():
    ...     gc.isenabled()
    False
    >>> gc.isenabled()
    True
    """
    _begin_pause()
    try:
        yield
    finally:
        _end_pause()


def install() -> None:
    """Register the listener once (call after numba is imported).

    Examples
    --------
    >>> from navkit._shared import compile_gc
    >>> compile_gc.install()
    >>> compile_gc.install()  # idempotent
    >>> len(compile_gc._INSTALLED)
    2
    """
    if _INSTALLED:
        return
    event: Any = importlib.import_module("numba.core.event")
    on_compile, on_lock = _make_listeners()
    event.register("numba:compile", on_compile)
    event.register("numba:compiler_lock", on_lock)
    _INSTALLED.extend((on_compile, on_lock))
