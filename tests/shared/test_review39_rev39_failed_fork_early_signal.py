"""A signal before navkit's fork hold, and a fork that fails (review 39, REV39).

A signal whose handler raises, landing in navkit's before-fork hook before its
hold is in place, has its exception kept and raised as ``os.fork`` returns, by
a profile function set for that one event (review 38). Python calls the after
hooks even when ``fork()`` fails (``EAGAIN`` under ``RLIMIT_NPROC``), and
``os.fork`` then raises ``OSError``. Pinned as it is: the handler's exception
reaches the caller once, in place of the ``OSError`` or in the caller's
handler of it, and no profile function is left behind to raise it again later.

The fork is made to fail as an unprivileged user with ``RLIMIT_NPROC`` 1, so
the probe needs root to change user (skipped otherwise).
"""

from __future__ import annotations

import os
import sys
import textwrap

import pytest

from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(
    not hasattr(os, "fork") or sys.platform != "linux" or os.geteuid() != 0,
    reason="needs os.fork and root (to fork as a user out of processes)",
)

_FAILED_FORK = textwrap.dedent(
    """
    import json, os, resource, signal, sys
    from navkit._shared.jit import load_numba

    load_numba()
    calls = []

    def on_term(signum, frame):
        calls.append(signum)
        raise SystemExit("terminated")

    signal.signal(signal.SIGTERM, on_term)
    os.setgid(65534)
    os.setuid(65534)
    resource.setrlimit(resource.RLIMIT_NPROC, (1, 1))  # this user has one already

    def tracer(frame, event, arg):
        if event == "call" and frame.f_code.co_name == "_forks":
            sys.settrace(None)
            signal.raise_signal(signal.SIGTERM)  # before the hold
        return None

    def fork(catch):
        sys.settrace(tracer)
        try:
            os.fork()
        except OSError:
            if not catch:
                raise
            return "returned"  # the exception comes as the frame returns
        os._exit(0)

    out = []
    for catch in (False, True):
        calls.clear()
        try:
            result = fork(catch)
        except SystemExit:
            result = "SystemExit"
        except OSError:
            result = "OSError"
        sys.settrace(None)
        left = sys.getprofile() is not None
        later = (lambda: "ok")()  # a call: a profile left behind would raise here
        out.append([result, len(calls), left, later])
    print(json.dumps(out))
    """
)


def test_an_early_signal_reaches_the_caller_of_a_fork_that_fails_once() -> None:
    out = probe_outcome(_FAILED_FORK, timeout=120)
    assert out == [
        ["SystemExit", 1, False, "ok"],  # in place of the OSError
        ["SystemExit", 1, False, "ok"],  # in the caller's handler of it
    ]
