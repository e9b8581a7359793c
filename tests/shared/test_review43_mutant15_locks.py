"""A call refused in a forked child because of the child's own call keeps its message (MUTANT15).

Review 37 made a refusal in a forked child name the fork when the call under
way was a parent's thread's (that call never ends in the child). A call under
way in the child itself -- in the same thread (a signal handler's, here a
re-entrant call) or in a thread the child started -- is an ordinary refusal and
must say so: the object is not half-updated, and making a new one is the wrong
advice. Mutants that skipped the child's frame search (or searched only the
threads' innermost frames) named the fork for these calls too, unseen by the
tests, which refused calls in a child only because of the parent's thread; so
did one that named the fork for a call that ended while the refusal was being
worded (no longer in the object's list).
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

_SCRIPT = textwrap.dedent(
    """
    import faulthandler, json, os, threading
    faulthandler.dump_traceback_later(60, exit=True)
    from navkit._shared.locks import _in_use, one_caller

    class Box:
        __slots__ = ("_callers", "n")

        def __init__(self):
            self._callers, self.n = [], 0

        @one_caller
        def fill(self, inner=False, inside=None, leave=None):
            self.n += 1
            if inner:
                return message(self.fill)  # as a signal handler's call would
            if inside is not None:
                inside.set()
                leave.wait(30)
            return None

    def message(call):
        try:
            call()
        except RuntimeError as error:
            return str(error)
        return None

    box = Box()  # at rest when the process forks
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        same = box.fill(inner=True)
        inside, leave = threading.Event(), threading.Event()
        worker = threading.Thread(target=box.fill, kwargs={"inside": inside, "leave": leave})
        worker.start()
        assert inside.wait(30)
        other = message(box.fill)
        leave.set()
        worker.join(30)
        after = message(box.fill)  # both calls are done: this one runs
        # A call that ended between the refusal's read of the list and the message
        # (its token no longer listed, no frame holds it) was this process's own.
        ended = _in_use("Box", "fill", (0, "fill", object()), [])
        os.write(write, json.dumps([same, other, after, ended, box.n, box._callers]).encode())
        os._exit(0)
    os.close(write)
    out = json.loads(os.read(read, 100000).decode())
    os.waitpid(pid, 0)
    print(json.dumps(out))
    """
)


def test_a_childs_own_call_under_way_gets_the_ordinary_messages() -> None:
    same, other, after, ended, n, callers = probe_outcome(_SCRIPT, timeout=120)
    assert same is not None and other is not None
    for text in (same, other, ended):
        assert text.startswith("Box.fill was called"), text
        assert "forked" not in text and "make a new" not in text, text
    assert "during this Box's own fill, in the same thread" in same, same
    assert "another thread was in this Box's fill" in other, other
    assert "another thread was in this Box's fill" in ended, ended
    assert after is None
    assert n == 3  # the outer call, the worker's, the last; the two refused did not run
    assert callers == []
