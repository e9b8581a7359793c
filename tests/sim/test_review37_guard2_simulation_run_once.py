"""A Simulation runs once, also when a second run() starts while the first is starting.

``run`` checked that the Simulation had not run, then looked at its estimator
(an ``isinstance``, a PlanarFusion's start check), and only then marked it run.
A second ``run()`` started in between (a signal handler's, or another
thread's) passed the same check: it ran the whole loop, and the first run went
on after it with the controller, the estimator and the random generator that
run had left, returning a second, wrong trace without an error. The mark is now
set right after the check, with no call between (where Python could switch
threads or run a handler): the second run is refused as a second run is
(``RuntimeError``), and the first gives the trace it gives alone. A run refused
by the estimator's start check still leaves the Simulation unrun (review 37,
GUARD2).

The interleavings are forced: a profile hook starts the second run at every
point where CPython runs a signal handler (``interrupt_points.DELIVERY``)
within the first run's start.
"""

from __future__ import annotations

import threading
from typing import Any

import pytest
from shapely.geometry import box

from interrupt_points import interleaved
from navkit.estimation import PlanarFusion
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Compass, Observation, Robot, Simulation, World


class _Turning:
    """A controller with state: each call turns a little faster."""

    def __init__(self) -> None:
        self.calls = 0

    def __call__(self, obs: Observation) -> Twist2D:
        self.calls += 1
        return Twist2D(0.2, 0.0, 0.01 * self.calls)


ROBOT = Robot(
    drive=DiffDrive(track=0.3, wheel_radius=0.05),
    footprint=0.1,
    compass=Compass(rate=10.0, noise=0.01),
)
WORLD = World(box(-5.0, -5.0, 5.0, 5.0).exterior)


def _sim(estimator: Any = None) -> Simulation:
    return Simulation(WORLD, ROBOT, _Turning(), start=(0.0, 0.0, 0.0), duration=0.3, seed=1,
                      estimator=estimator)  # fmt: skip


@pytest.mark.parametrize("with_fusion", [False, True], ids=["no estimator", "PlanarFusion"])
def test_a_run_started_while_a_run_starts_is_refused_and_the_first_runs_alone(
    with_fusion: bool,
) -> None:
    def make() -> Simulation:
        return _sim(PlanarFusion(t0=0.0) if with_fusion else None)

    want = make().run()
    # The run's start: the first points of the whole run (a run has thousands).
    window = 60
    assert interleaved(0, make().run, lambda: None)["points"] > window
    refused = 0
    for k in range(1, window + 1):
        sim = make()
        out = interleaved(k, sim.run, sim.run)
        traces = [out[w] for w in ("m", "h") if w in out and not isinstance(out[w], RuntimeError)]
        errors = [out[w] for w in ("m", "h") if isinstance(out.get(w), RuntimeError)]
        # Exactly one run, the one a fresh Simulation gives; the other refused.
        assert len(traces) == 1, (k, out)
        assert traces[0].poses.tobytes() == want.poses.tobytes(), k
        assert traces[0].estimates.tobytes() == want.estimates.tobytes(), k
        assert len(errors) == 1
        assert "a Simulation runs once" in str(errors[0])
        refused += isinstance(out.get("h"), RuntimeError)
    assert refused > window // 2


def test_a_run_refused_by_the_estimators_start_check_leaves_the_simulation_unrun() -> None:
    fusion = PlanarFusion(t0=0.0)
    sim = _sim(fusion)
    fusion.predict(1.0)  # past the run's start
    with pytest.raises(ValueError, match="after the run's start"):
        sim.run()
    fusion.reset(t0=0.0)
    assert sim.run().metrics.reason == "timeout"
    with pytest.raises(RuntimeError, match="runs once"):
        sim.run()


def test_two_threads_running_one_simulation_get_one_run_and_one_refusal() -> None:
    for _ in range(20):
        sim = _sim()
        start = threading.Barrier(2)
        outcomes: list[str] = []

        def run(
            sim: Simulation = sim,
            start: threading.Barrier = start,
            outcomes: list[str] = outcomes,
        ) -> None:
            start.wait(60)
            try:
                sim.run()
            except RuntimeError as error:
                outcomes.append("refused" if "runs once" in str(error) else repr(error))
                return
            outcomes.append("ran")

        threads = [threading.Thread(target=run) for _ in range(2)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join(120)
        assert sorted(outcomes) == ["ran", "refused"]
