"""A child forked while another thread makes navkit kernels can make its own (review 37).

``navkit._shared.jit`` guards its table of kernels with a lock that every
kernel module takes as it decorates its kernels and binds numba's names. A fork
made while another thread held it (importing a navkit package after numba was
loaded: a ROS 2 node's callback importing ``navkit.planning`` as a ``fork``
worker pool starts) left the child's copy held by a thread the child does not
have: the child's next import of a navkit package with kernels, or its next
decorated function, waited for ever. The lock is made anew in the child now.

The other thread is held inside the lock (a trace function stops it there) for
at most a few seconds while the main thread forks; the child imports another
package and runs one of its kernels. In a fresh interpreter, with a timeout:
a hang is a failure that says so.
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
    import faulthandler, json, os, select, sys, threading
    faulthandler.dump_traceback_later(200, exit=True)
    import numpy as np
    import navkit.geometry, navkit.kinematics, navkit.mapping  # below both packages
    from navkit._shared import jit

    jit.load_numba()
    assert "navkit.planning" not in sys.modules and "navkit.estimation" not in sys.modules
    holding, forked = threading.Event(), threading.Event()
    source = open(jit.__file__).read().splitlines()

    def tracer(frame, event, arg):
        # Stops the thread inside jit's lock, at a kernel's decoration, once.
        def local(frame, event, arg):
            if event == "line" and "_NJIT is None" in source[frame.f_lineno - 1]:
                sys.settrace(None)
                holding.set()
                forked.wait(3.0)
            return local

        return local if frame.f_code.co_name == "decorate" else None

    def import_planning():
        sys.settrace(tracer)
        import navkit.planning  # noqa: F401

    thread = threading.Thread(target=import_planning)
    thread.start()
    assert holding.wait(60)
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read)
        from navkit.estimation import DiffOdometry
        from navkit.kinematics import DiffDrive

        odometry = DiffOdometry(DiffDrive(track=0.5, wheel_radius=0.1), ticks_per_rev=100)
        odometry.update(0, 0)
        pose = odometry.update(100, 100)  # a wheel turn each: 2 pi 0.1 m ahead
        os.write(write, repr(round(pose.x, 6)).encode())
        os._exit(0)
    forked.set()
    os.close(write)
    ready, _, _ = select.select([read], [], [], 60)
    answer = (os.read(read, 100).decode() if ready else "") or "the child hung"
    if not ready:
        os.kill(pid, 9)
    os.waitpid(pid, 0)
    thread.join(60)
    print(json.dumps(answer))
    """
)


def test_a_child_forked_while_another_thread_decorates_kernels_makes_its_own() -> None:
    assert probe_outcome(_SCRIPT, timeout=240) == "0.628319"
