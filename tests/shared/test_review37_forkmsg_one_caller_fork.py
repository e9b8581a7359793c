"""A call refused in a forked child because of a call under way in the parent says so (review 37).

A child forked while another thread of the parent was inside a method guarded
by ``one_caller`` keeps that call's token: the thread does not exist in the
child, and the object may be half-updated there, so every later call is
refused (rightly). The message named "another thread" of the child, which has
none: it now says the call was under way in the parent when the process was
forked, and to make a new object. Calls refused in the parent (another thread,
or the same thread's signal handler) keep their messages.
"""

from __future__ import annotations

import os
import sys
import textwrap

import pytest

from interrupt_points import interleaved
from navkit._shared.locks import one_caller
from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(
    not hasattr(os, "fork") or sys.platform != "linux", reason="needs os.fork"
)

_SCRIPT = textwrap.dedent(
    """
    import faulthandler, json, os, threading
    faulthandler.dump_traceback_later(60, exit=True)
    from navkit._shared.locks import one_caller

    class Box:
        __slots__ = ("_callers", "n")

        def __init__(self):
            self._callers, self.n = [], 0

        @one_caller
        def fill(self, inside=None, leave=None):
            self.n += 1
            if inside is not None:
                inside.set()
                leave.wait(30)

    def message(call):
        try:
            call()
        except RuntimeError as error:
            return str(error)
        return None

    box = Box()
    inside, leave = threading.Event(), threading.Event()
    worker = threading.Thread(target=box.fill, args=(inside, leave))
    worker.start()
    assert inside.wait(30)
    parent = message(box.fill)  # another thread's call under way, in this process
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        # Twice: the refusal leaves the object refusing, and names the fork each time.
        child = [message(box.fill), message(box.fill)]
        # A thread started in the child is refused the same way.
        out = []
        thread = threading.Thread(target=lambda: out.append(message(box.fill)))
        thread.start()
        thread.join(30)
        os.write(write, json.dumps(child + out).encode())
        os._exit(0)
    os.close(write)
    child = json.loads(os.read(read, 100000).decode())
    os.waitpid(pid, 0)
    leave.set()
    worker.join(30)
    after = message(box.fill)  # the parent's call is done: this one runs
    print(json.dumps({"parent": parent, "child": child, "after": after, "n": box.n}))
    """
)


def test_a_call_refused_in_a_forked_child_names_the_fork_not_another_thread() -> None:
    out = probe_outcome(_SCRIPT, timeout=120)
    assert "another thread was in this Box's fill" in out["parent"]
    assert len(out["child"]) == 3
    for text in out["child"]:
        assert text is not None  # refused: the parent's call may have left it half-updated
        assert "another thread" not in text, text
        assert "same thread" not in text, text
        assert "forked" in text and "make a new" in text, text
        assert text.startswith("Box.fill was called"), text
    assert out["after"] is None  # in the parent, the next call runs
    assert out["n"] == 2


def test_the_refusal_messages_in_one_process_are_unchanged() -> None:
    class Box:
        __slots__ = ("_callers", "n")

        def __init__(self) -> None:
            self._callers: list[object] = []
            self.n = 0

        @one_caller
        def fill(self) -> int:
            self.n += 1
            return self.n

    refused = 0
    for k in range(1, 20):
        box = Box()
        out = interleaved(k, box.fill, box.fill)
        if isinstance(out.get("h"), RuntimeError):
            refused += 1
            assert "in the same thread (from a signal handler?)" in str(out["h"]), out
            assert out["m"] == 1
        assert box._callers == []
    assert refused >= 1


# A class guarding its calls inline, as PlanarFusion does (its token in a local
# named ``token``, ``_in_use`` given the token alone).
_INLINE = textwrap.dedent(
    """
    import faulthandler, json, os, threading
    from _thread import get_ident
    faulthandler.dump_traceback_later(60, exit=True)
    from navkit._shared.locks import _in_use

    class Filter:
        def __init__(self):
            self._callers = []

        def step(self, inside=None, leave=None):
            callers = self._callers
            token = (get_ident(), "step", object())
            try:
                callers.append(token)
                if callers[0] is not token:
                    raise RuntimeError(_in_use("Filter", "step", callers[0]))
                if inside is not None:
                    inside.set()
                    leave.wait(30)
            finally:
                callers.remove(token)

    def message(call):
        try:
            call()
        except RuntimeError as error:
            return str(error)
        return None

    f = Filter()
    inside, leave = threading.Event(), threading.Event()
    worker = threading.Thread(target=f.step, args=(inside, leave))
    worker.start()
    assert inside.wait(30)
    parent = message(f.step)
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.write(write, json.dumps(message(f.step)).encode())
        os._exit(0)
    os.close(write)
    child = json.loads(os.read(read, 100000).decode())
    os.waitpid(pid, 0)
    leave.set()
    worker.join(30)
    print(json.dumps([parent, child]))
    """
)


def test_an_inline_guard_given_the_token_alone_tells_the_fork_too() -> None:
    parent, child = probe_outcome(_INLINE, timeout=120)
    assert "another thread was in this Filter's step" in parent
    assert "parent process when this process was forked" in child, child
