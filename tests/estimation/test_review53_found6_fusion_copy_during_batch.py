"""A PlanarFusion copied or pickled while another thread fuses a log (review 53, FOUND6).

``update_batch`` runs its kernel without the GIL, and it wrote the filter's own
buffer row by row (x and P every row, the time at the end): a copy or pickle
taken by another thread meanwhile held x and P of some row, often half a step
(the prediction written, not the update), at the time before the log; 15,056
of 15,727 copies taken during a 200,000-row log were so, with or without
``history``. A copy stepped on from there predicts from the wrong time. The
kernel now runs on a copy put in place by one C call: a copy taken during the
call is the filter as before the log, as the class notes promise ("the filter
as before or after one of that call's steps").
"""

from __future__ import annotations

import copy
import pickle
import threading

import numpy as np
import pytest

from navkit.estimation import MeasurementLog, PlanarFusion


def _log(n: int) -> MeasurementLog:
    rng = np.random.default_rng(7)
    times = np.arange(1, n + 1) * 0.01
    speeds = 1.0 + 0.01 * rng.normal(size=n)
    return MeasurementLog.from_streams(
        odometry=(times, speeds, 0.1 * np.sin(times)),
        yaw=(times + 0.005, 0.01 * rng.normal(size=n)),
    )


@pytest.mark.parametrize("history", [0.0, 0.5])
def test_copies_taken_during_another_threads_batch_are_the_filter_before_the_log(
    history: float,
) -> None:
    log = _log(60_000)
    fusion = PlanarFusion(t0=0.0, history=history)
    fusion.update_odometry(0.001, 1.0, 0.0, v_variance=0.01, omega_variance=0.01)
    before = (fusion.t, fusion.x.copy(), fusion.P.copy())
    copiers = (copy.copy, copy.deepcopy, lambda f: pickle.loads(pickle.dumps(f)))
    copies: list[PlanarFusion] = []
    running = threading.Event()
    done = threading.Event()
    results = []

    def fuse() -> None:
        running.set()
        results.append(fusion.update_batch(log))
        done.set()

    thread = threading.Thread(target=fuse)
    thread.start()
    running.wait()
    while not done.is_set():
        copies.append(copiers[len(copies) % 3](fusion))
    thread.join()
    (result,) = results
    after = (float(log.times[-1]), result.states[-1], result.covariances[-1])
    assert (fusion.t, fusion.x.tolist(), fusion.P.tolist()) == (
        after[0],
        after[1].tolist(),
        after[2].tolist(),
    )
    # The copier had the GIL to itself while the kernel ran: many copies in that time.
    assert len(copies) >= 20
    kinds = {"before": 0, "after": 0}
    for index, twin in enumerate(copies):
        state = (twin.t, twin.x.tolist(), twin.P.tolist())
        for name, (t, x, p) in (("before", before), ("after", after)):
            if state == (t, x.tolist(), p.tolist()):
                kinds[name] += 1
                break
        else:
            pytest.fail(
                f"copy {index} of {len(copies)} is neither the filter before nor after the "
                f"log: t={twin.t}, x={twin.x.tolist()}"
            )
    assert kinds["before"] >= 1


def test_a_copy_taken_during_a_batch_steps_on_as_the_filter_before_it() -> None:
    log = _log(60_000)
    fusion = PlanarFusion(t0=0.0)
    fusion.update_odometry(0.001, 1.0, 0.0, v_variance=0.01, omega_variance=0.01)
    twin = copy.deepcopy(fusion)
    taken: list[PlanarFusion] = []
    thread = threading.Thread(target=fusion.update_batch, args=(log,))
    thread.start()
    while thread.is_alive() and len(taken) < 50:
        taken.append(copy.copy(fusion))
    thread.join()
    expected = twin.update_odometry(0.5, 1.0, 0.0, v_variance=0.01, omega_variance=0.01)
    for copied in taken:
        if copied.t == 0.001:  # taken during the call (or before it started)
            got = copied.update_odometry(0.5, 1.0, 0.0, v_variance=0.01, omega_variance=0.01)
            assert got.accepted == expected.accepted
            assert copied.x.tolist() == twin.x.tolist()
            assert copied.P.tolist() == twin.P.tolist()
