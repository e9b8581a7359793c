"""The sim conventions the guides now state, checked on the code.

* Bias signs: a bias is added to the quantity measured, in the reading's own
  sense. ``Compass(bias=b)`` reads ``b`` clockwise of the truth, so the yaw
  recovered with ``compass_to_yaw`` is the true yaw minus ``b``; ``Imu``'s
  ``gyro_bias`` adds to the yaw rate.
* ``trials`` (the argument) is trials per case in ``Scenario.run``,
  ``Scenario.trials`` and ``sweep``; ``ScenarioResult.trials`` holds them all.
* ``workers=None`` is one count of usable cores for ``sweep`` and ``warmup``.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.estimation import compass_to_yaw
from navkit.geometry import Twist2D, angle_diff
from navkit.kinematics import DiffDrive
from navkit.sim import (
    Compass,
    Imu,
    Observation,
    Robot,
    Scenario,
    ScenarioResult,
    Simulation,
    Table,
    Trial,
    TrialResult,
    World,
    sweep,
)


@settings(max_examples=200, deadline=None)
@given(
    yaw=st.floats(-math.pi, math.pi),
    bias=st.floats(-0.5, 0.5),
    north=st.floats(-2 * math.pi, 2 * math.pi),
)
def test_compass_bias_is_clockwise_so_the_yaw_reads_bias_less(
    yaw: float, bias: float, north: float
) -> None:
    reading = Compass(bias=bias, north=north).heading_deg(yaw)
    recovered = north + float(compass_to_yaw(reading))
    assert abs(angle_diff(recovered, yaw - bias)) < 1e-9


def test_gyro_bias_adds_to_the_yaw_rate() -> None:
    robot = Robot(
        drive=DiffDrive(track=0.3, wheel_radius=0.05),
        footprint=0.15,
        encoders=None,
        imu=Imu(gyro_bias=0.25, rate=100.0),
    )
    rates: list[float] = []

    def still(obs: Observation) -> Twist2D:
        if obs.imu is not None:
            rates.append(obs.imu.yaw_rate)
        return Twist2D(0.0, 0.0, 0.0)

    Simulation(World(), robot, still, start=(0.0, 0.0, 0.0), duration=0.1).run()
    assert rates and np.allclose(rates, 0.25)


class _TwoCases(Scenario):
    """Two cases, a coin each trial: the cheapest scenario with more than one case."""

    name, title, paper, default_trials = "two-cases", "two coins", "none", 2

    def __init__(self) -> None:
        self.asked: list[int] = []

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        self.asked.append(trials)
        return (("first", trials), ("second", trials))

    def run_trial(self, trial: Trial) -> TrialResult:
        heads = float(np.random.default_rng(trial.seed).random() < 0.5)
        return TrialResult(trial, {"heads": heads})

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        table = Table("coins", ("trials",), ((len(results),),))
        return ScenarioResult(self.name, seed, tuple(results), (table,), {"n": float(len(results))})


def test_trials_is_per_case_and_the_result_holds_every_trial() -> None:
    scenario = _TwoCases()
    assert len(scenario.trials(3)) == 6
    result = scenario.run(3, seed=1)
    assert len(result.trials) == 6 and set(scenario.asked) == {3}
    assert [r.trial.case_index for r in result.trials] == [0, 0, 0, 1, 1, 1]
    swept = sweep(_TwoCases(), trials=3, seeds=1, workers=1)
    assert len(swept.trials) == 6
    assert [r.trial for r in swept.trials] == [r.trial for r in result.trials]
    assert len(_TwoCases().run(seed=1).trials) == 2 * _TwoCases.default_trials


def test_workers_none_is_one_count_of_usable_cores() -> None:
    from navkit._shared import cores
    from navkit.cli import _scenarios
    from navkit.sim import _sweep, _warmup

    assert _sweep.usable_cores is _warmup.usable_cores is cores.usable_cores
    expected = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    assert cores.usable_cores() == expected
    # the command line's "N local processes" counts the same cores as sweep
    assert _scenarios._processes(None, 10**6) == expected
