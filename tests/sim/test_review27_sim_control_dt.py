"""The controller is told how long its command is held, counted in physics steps (review 27).

``TrackerController`` stepped its tracker with ``1 / control_rate`` at every
control step. A control rate that does not divide the physics rate runs the
controller on whole steps only: at 30 Hz of 100 Hz every 3 or 4 steps (0.03 or
0.04 s, never 1/30 s), at 20 Hz of 50 Hz every 3 or 2. A tracker that
rate-limits or integrates by ``dt`` then saw a period up to a physics step off
the time its command was held. ``Observation.dt`` now carries that time,
``(j - i) / rate`` for the control step ``i`` and the next one ``j`` (the
trackers' ``dt``: the command to hold for the next ``dt`` seconds), and
``TrackerController`` passes it on.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from shapely.geometry import box

from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, TrackerController, World

ROOM = World(box(-1.0, -1.0, 1.0, 1.0).exterior)
ROBOT = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2, encoders=None)


def _observed(rate: float, control_rate: float, duration: float) -> list[Observation]:
    seen: list[Observation] = []

    def spin(obs: Observation) -> Twist2D:
        seen.append(obs)
        return Twist2D(0.0, 0.0, 0.2)

    Simulation(ROOM, ROBOT, spin, start=(0.0, 0.0, 0.0), rate=rate, control_rate=control_rate,
               duration=duration).run()  # fmt: skip
    return seen


@pytest.mark.parametrize(
    ("rate", "control_rate", "periods"),
    [(100.0, 30.0, {3, 4}), (50.0, 20.0, {2, 3}), (100.0, 20.0, {5}), (7.0, 3.0, {2, 3})],
)
def test_observation_dt_is_the_steps_to_the_next_control_step(
    rate: float, control_rate: float, periods: set[int]
) -> None:
    seen = _observed(rate, control_rate, 10.0)
    steps = [round(obs.t * rate) for obs in seen]
    gaps = [b - a for a, b in itertools.pairwise(steps)]
    assert set(gaps) == periods
    # Exactly the step count over the rate, not a difference of rounded times.
    assert [obs.dt for obs in seen[:-1]] == [g / rate for g in gaps]
    # The last command too is held until the control step after it, had the run
    # gone on: the schedule k / control_rate, on whole steps.
    last = seen[-1].dt
    assert last is not None and round(last * rate) in periods


def test_a_dividing_control_rate_gets_exactly_its_period() -> None:
    seen = _observed(100.0, 20.0, 30.0)
    assert {obs.dt for obs in seen} == {1.0 / 20.0}
    # A difference of the times would not be: 0.15 - 0.1 is 0.04999999999999999.
    assert any(b.t - a.t != 0.05 for a, b in itertools.pairwise(seen))


class _Spy:
    """A path tracker that records the dt it is stepped with."""

    done = False

    def __init__(self) -> None:
        self.dts: list[float] = []

    def step(self, pose: Pose2D, dt: float) -> Twist2D:
        self.dts.append(dt)
        return Twist2D(0.0, 0.0, 0.2)


@pytest.mark.parametrize(("rate", "control_rate"), [(100.0, 30.0), (50.0, 20.0), (100.0, 20.0)])
def test_tracker_controller_steps_its_tracker_by_the_time_held(
    rate: float, control_rate: float
) -> None:
    spy = _Spy()
    follow = TrackerController(spy, control_rate=control_rate, use_estimate=False)
    times: list[float] = []

    def control(obs: Observation) -> Twist2D:
        times.append(obs.t)
        return follow(obs)

    Simulation(ROOM, ROBOT, control, start=(0.0, 0.0, 0.0), rate=rate, control_rate=control_rate,
               duration=10.0).run()  # fmt: skip
    steps = [round(t * rate) for t in times]
    assert spy.dts[:-1] == [(b - a) / rate for a, b in itertools.pairwise(steps)]
    # What a tracker integrating by dt adds up is the simulated time.
    assert math.isclose(math.fsum(spy.dts[:-1]), times[-1], rel_tol=0.0, abs_tol=1e-12)


def test_an_observation_without_dt_steps_the_tracker_by_the_nominal_period() -> None:
    spy = _Spy()
    follow = TrackerController(spy, control_rate=30.0, use_estimate=False)
    pose = Pose2D(0.0, 0.0, 0.0)
    follow(Observation(0.0, None, None, None, None, (), None, pose))
    follow(Observation(0.04, None, None, None, None, (), None, pose, dt=0.04))
    follow(Observation(0.07, None, None, None, None, (), None, pose))
    assert spy.dts == [1.0 / 30.0, 0.04, 1.0 / 30.0]


@pytest.mark.parametrize(
    ("dt", "error"),
    [(0.0, ValueError), (-0.01, ValueError), (math.nan, ValueError), (math.inf, ValueError),
     (5e-324, ValueError), ("0.05", TypeError)],
)  # fmt: skip
def test_a_bad_dt_is_refused_by_name(dt: object, error: type[Exception]) -> None:
    with pytest.raises(error, match="dt"):
        Observation(0.1, None, None, None, None, (), None, Pose2D(0.0, 0.0, 0.0), dt=dt)  # type: ignore[arg-type]


def test_dt_is_taken_as_a_float() -> None:
    obs = Observation(0.1, None, None, None, None, (), None, Pose2D(0.0, 0.0, 0.0),
                      dt=np.float32(0.25))  # type: ignore[arg-type]  # fmt: skip
    assert type(obs.dt) is float and obs.dt == 0.25
