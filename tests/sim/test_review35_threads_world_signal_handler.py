"""A signal handler may query a world while the main thread's query is under way.

``World`` serializes its queries of shared shapely geometries with one lock
(GEOS's prepared geometries are not thread-safe, and shapely releases the GIL
while it tests a point). Python runs a signal handler in the main thread
between two bytecodes, and a signal arriving during that test is handled as
soon as it returns, while the lock is still held: a handler that asked
``collides`` (a ``signal.setitimer`` tick of a simulation loop, a ``SIGINT``
handler reporting where the robot is) waited for the lock its own thread
held, for ever. The interleaving is forced: shapely's ``contains_xy`` is
wrapped so that a signal is raised as it returns. Each case runs in a fresh
interpreter with a time limit, as the failure is a hang.
"""

from __future__ import annotations

import ast
import signal
import subprocess
import sys
import textwrap

import pytest

pytestmark = pytest.mark.skipif(
    sys.platform == "win32" or not hasattr(signal, "SIGUSR1"), reason="needs SIGUSR1"
)

_SCRIPT = textwrap.dedent(
    """
    import signal, sys
    import shapely
    from shapely.geometry import box
    from navkit.sim import MovingObstacle, World

    moving = MovingObstacle.constant_velocity(
        box(-0.5, -0.5, 0.5, 0.5), start_xy=(6.0, 6.0), velocity_xy=(0.0, 0.0)
    )
    world = World([box(2, 2, 3, 3)], moving=[moving])
    queries = [(0.1, (2.5, 2.5, 0.0)), (0.1, (6.0, 6.0, 0.0)), (0.1, (0.0, 0.0, 0.0))]
    alone = [world.collides(f, p) for f, p in queries]

    real = shapely.contains_xy
    inside = [False]

    def signalled(*args, **kwargs):
        out = real(*args, **kwargs)
        if not inside[0]:  # the handler's own queries run as they would
            inside[0] = True
            try:
                signal.raise_signal(signal.SIGUSR1)
            finally:
                inside[0] = False
        return out

    shapely.contains_xy = signalled
    handled = []
    signal.signal(
        signal.SIGUSR1, lambda s, f: handled.append([world.collides(g, p) for g, p in queries])
    )
    interrupted = [world.collides(f, p) for f, p in queries]
    print(repr((alone, interrupted, handled)))
    """
)


def test_a_handlers_collision_query_inside_the_main_threads_answers() -> None:
    try:
        done = subprocess.run(
            [sys.executable, "-c", _SCRIPT],
            capture_output=True,
            text=True,
            timeout=60,
            check=False,
        )
    except subprocess.TimeoutExpired:
        pytest.fail("the handler's query waited for the lock its own thread held")
    assert done.returncode == 0, done.stderr
    alone, interrupted, handled = ast.literal_eval(done.stdout.strip().splitlines()[-1])
    assert alone == [True, True, False]
    assert interrupted == alone
    # One handler run per point test of a solid shape (the static ones, then the
    # moving one), each answering as the queries alone.
    assert len(handled) >= 3
    assert handled == [alone] * len(handled)
