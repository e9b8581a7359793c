"""A signal handler copying a grid while the main thread makes a grid's lock (review 25).

``OccupancyGrid._writer_lock`` makes a missing or stale lock (a grid built by
``__new__``; every grid's first use in a forked child) under one module lock.
A signal handler runs in the main thread at a Python call, here ``_new_lock``'s,
while that thread holds the module lock: a handler saving a map (``copy()``)
of a grid whose lock must be made too waited for ever on the plain module lock.
It is re-entrant now, and a lock the handler made for the same grid is the one
kept (another thread may have taken it meanwhile). The probes run in a child
process (a hang ends there, by its alarm, not in the test session), as in a
forked child: every lock stale.
"""

from __future__ import annotations

import textwrap

import pytest

from subprocess_probe import probe_outcome

_PROBE = textwrap.dedent(
    """
    import json, os, signal, sys
    import numpy as np
    import navkit.mapping._grid as G
    from navkit.mapping import OccupancyGrid

    same = sys.argv[1] == "same"
    a = OccupancyGrid(np.zeros((4, 4), np.float32), resolution=0.1)
    b = a if same else OccupancyGrid(np.zeros((4, 4), np.float32), resolution=0.1)
    seen = []

    def handler(signum, frame):  # saving the map, as on Ctrl-C
        seen.append(b.copy())
        seen.append(b._lock)

    signal.signal(signal.SIGUSR1, handler)
    made = G._new_lock
    fired = []

    def new_lock():
        # The handler runs where a pending signal is delivered: this call's entry.
        if not fired:
            fired.append(1)
            signal.raise_signal(signal.SIGUSR1)
        return made()

    G._new_lock = new_lock
    G._FORKS[0] += 1  # as in a forked child: every grid's lock is made anew
    signal.signal(signal.SIGALRM, lambda *_: os._exit(3))  # a hang ends the probe
    signal.alarm(20)
    copied = a.copy()
    signal.alarm(0)
    print(json.dumps({
        "handled": len(seen) == 2,
        "kept": a._lock is seen[1] if same else a._lock[1] == G._FORKS[0],
        "equal": bool((copied.logodds == seen[0].logodds).all()),
    }))
    """
)


@pytest.mark.parametrize("which", ["same", "other"])
def test_a_handler_copying_a_grid_while_a_lock_is_made_does_not_hang(which: str) -> None:
    outcome = probe_outcome(_PROBE, which, timeout=120)
    assert outcome == {"handled": True, "kept": True, "equal": True}
