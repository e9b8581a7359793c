"""A fork between ``with``'s binding of a compile count's two methods (review 39, REVB).

``with dispatcher._compiling_counter:`` (numba's ``Dispatcher.compile``) binds
``__enter__`` and then ``__exit__`` of ``navkit._shared.jit._CompileDepth``,
each through ``_LockMethod.__get__``, a Python function: a signal's handler may
run as the second is entered, with ``__enter__`` already bound to the count's
C lock. A handler that forks there (the compiling thread holds numba's
compiler lock, so the fork's hold goes through) ran the child hook
``_free_lost_compile_depths``, which replaced every lock the forking thread did
not own, this one too: the child's compile entered the old lock, counted 0
on the new one while compiling (numba's recursion check read it), and its
``with`` ended in ``RuntimeError: cannot release un-acquired lock``, raised
from the child's first call of the kernel. Only locks another thread holds
are replaced now.

Each case runs in a fresh interpreter with a timeout.
"""

from __future__ import annotations

import os
import sys
import textwrap

import pytest

from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(
    not hasattr(os, "fork") or sys.platform != "linux", reason="needs os.fork"
)

_FORK_BETWEEN_BINDINGS = textwrap.dedent(
    """
    import faulthandler, json, os, sys
    faulthandler.dump_traceback_later(60, exit=True)
    from navkit._shared import jit

    jit.load_numba()

    def add_three(x):
        return x + 3

    add_three.__qualname__ = "add_three"
    kernel = jit.typed_njit(cache=False)(add_three)
    counter = kernel._compiling_counter
    get_code = jit._LockMethod.__get__.__code__
    forked, seen = [], []

    def profile(frame, event, arg):
        if (
            event == "call"
            and not forked
            and frame.f_code is get_code
            and frame.f_locals["self"].name == "__exit__"
            and frame.f_locals["depth"] is counter
        ):
            sys.setprofile(None)
            forked.append(os.fork())  # as a signal handler run here would
            if forked == [0]:
                sys.setprofile(profile)
        elif event == "call" and forked == [0] and frame.f_code.co_name == "run_pass":
            seen.append(bool(counter))  # numba's passes read the count

    sys.setprofile(profile)
    try:
        result = repr(kernel(1))
    except BaseException as exc:
        result = repr(exc)
    sys.setprofile(None)
    if forked == [0]:
        ok = result == "4" and bool(seen) and all(seen) and not counter and kernel(2) == 5
        os._exit(0 if ok else 3)
    status = os.waitpid(forked[0], 0)[1] if forked else None
    print(json.dumps({"parent": result, "child_status": status}))
    """
)


def test_a_fork_between_with_binding_enter_and_exit_leaves_the_childs_compile_whole() -> None:
    out = probe_outcome(_FORK_BETWEEN_BINDINGS, timeout=120)
    # Before: the child's call raised "cannot release un-acquired lock" (status 3 << 8).
    assert out == {"parent": "4", "child_status": 0}
