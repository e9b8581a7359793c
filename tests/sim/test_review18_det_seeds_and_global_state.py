"""Determinism of the simulator and the scenarios: seeds, global random state, threads.

* A run depends on its seed only: an int, a NumPy integer and a Generator made from
  that int give the same bits; a rerun in the same process gives them again.
* navkit never draws from, reseeds or advances the user's global random state
  (:mod:`random`, ``np.random``), even with ``seed=None`` (fresh entropy of its own).
* The demo's trial values are reproducible except ``plan_wall_time`` (its docstring);
  a sweep on a thread pool equals one in this process (``sweep``: "the same seeds
  give the same result on every executor").
"""

from __future__ import annotations

import concurrent.futures
import random
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest
from shapely.geometry import box

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Imu, Lidar, Observation, Robot, Simulation, World, sweep
from navkit.sim.scenarios import Demo, OmniApf
from scenario_results import comparable

_WORLD = World(box(-1.0, -1.0, 4.0, 2.0).exterior)
_ROBOT = Robot(
    drive=DiffDrive(track=0.3, wheel_radius=0.05),
    footprint=0.2,
    wheel_slip=0.1,
    wheel_radius_error=0.01,
    lidar=Lidar(n_beams=36),
    imu=Imu(),
)


def _curve(obs: Observation) -> Twist2D:
    return Twist2D(0.3, 0.0, 0.4)


def _run(seed: Any) -> bytes:
    sim = Simulation(
        _WORLD, _ROBOT, _curve, start=(0.0, 0.0, 0.0), duration=2.0, seed=seed, record_scans=True
    )
    trace = sim.run()
    scans = b"".join(np.asarray(s.scan.ranges).tobytes() for s in trace.scans)
    return trace.poses.tobytes() + trace.estimates.tobytes() + trace.commands.tobytes() + scans


@pytest.fixture
def global_state() -> Iterator[None]:
    """Seeds the global generators, then checks the test left them exactly as seeded."""
    random.seed(20261203)
    np.random.seed(20261203)  # noqa: NPY002 - the legacy global state is what is checked
    before_py = random.getstate()
    before_np = np.random.get_state()  # noqa: NPY002
    yield
    after_np = np.random.get_state()  # noqa: NPY002
    assert random.getstate() == before_py
    assert after_np[0] == before_np[0]
    assert np.array_equal(after_np[1], before_np[1])
    assert after_np[2:] == before_np[2:]


def test_a_seed_as_int_numpy_int_or_generator_gives_the_same_run(global_state: None) -> None:
    first = _run(5)
    assert _run(5) == first  # a rerun in the same process
    assert _run(np.int64(5)) == first
    assert _run(np.uint8(5)) == first
    assert _run(np.random.default_rng(5)) == first
    assert _run(6) != first  # the seed matters: the equalities above mean something


def test_fresh_entropy_leaves_the_global_state_alone(global_state: None) -> None:
    assert _run(None) != _run(None)
    lidar = Lidar(n_beams=36)
    lidar.scan(_WORLD, (1.0, 0.5, 0.0), seed=None)


def test_a_seed_sequence_is_refused_by_name() -> None:
    with pytest.raises(TypeError, match="seed"):
        _run(np.random.SeedSequence(5))


def test_scenario_trials_leave_the_global_state_alone(global_state: None) -> None:
    demo = Demo(map="office", duration=2.0)
    for trial in demo.trials(1, seed=3)[:2]:
        demo.run_trial(trial)
    omni = OmniApf()
    omni.run_trial(omni.trials(1, seed=3)[0])


def test_demo_values_repeat_except_the_planning_wall_time() -> None:
    demo = Demo(map="office", duration=4.0)
    trial = demo.trials(1, seed=11)[1]
    first, second = demo.run_trial(trial), demo.run_trial(trial)
    assert first.trace is not None and second.trace is not None
    assert set(first.values) == set(second.values)
    for name, value in first.values.items():
        if name != "plan_wall_time":
            assert second.values[name] == value, name
    assert first.trace.poses.tobytes() == second.trace.poses.tobytes()
    assert first.trace.estimates.tobytes() == second.trace.estimates.tobytes()
    other = demo.run_trial(demo.trials(1, seed=12)[1])
    assert other.values["estimate_error"] != first.values["estimate_error"]


def test_a_sweep_on_threads_equals_one_in_this_process() -> None:
    demo = Demo(map="office", duration=3.0)
    serial = comparable(sweep(demo, trials=2, seeds=9, workers=1))
    with concurrent.futures.ThreadPoolExecutor(3) as pool:
        threaded = comparable(sweep(demo, trials=2, seeds=9, executor=pool))
    assert threaded == serial
    assert comparable(sweep(demo, trials=2, seeds=9, workers=1)) == serial  # no leftovers
