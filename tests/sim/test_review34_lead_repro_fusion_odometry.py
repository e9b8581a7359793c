"""The simulator's wheel odometry for PlanarFusion is the same on every CPU (review 34).

``FusionEstimator`` turned wheel increments into a forward speed and yaw rate
with a matrix product, which OpenBLAS computes with a kernel chosen for the CPU:
on a recent Intel Xeon (AVX-512) a straight drive's yaw rate came out as
-7.4e-17 rad/s where older CPUs' kernel gives 0, so the same seed ran a
different estimate on each machine (and the digests pinned by
``test_review29_simmem_run_peak`` failed there). The products are now added
wheel by wheel, in order: the same bits everywhere.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from shapely.geometry import box

from navkit.estimation import PlanarFusion
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, WheelEncoders, World
from openblas_kernels import core_types
from subprocess_probe import probe_outcome


class _Recording(PlanarFusion):
    """A PlanarFusion that keeps the odometry it is given."""

    def __init__(self, *args: object, **kwargs: object) -> None:
        super().__init__(*args, **kwargs)  # type: ignore[arg-type]
        self.odometry: list[tuple[float, float]] = []

    def update_odometry(self, t: float, v: float, omega: float, **kwargs: float):  # type: ignore[no-untyped-def, override]
        self.odometry.append((v, omega))
        return super().update_odometry(t, v, omega, **kwargs)


def _straight(obs: Observation) -> Twist2D:
    return Twist2D(0.4, 0.0, 0.0)


@pytest.mark.parametrize("track", [0.3, 0.37, 0.1234567])
def test_a_straight_drive_reports_a_yaw_rate_of_exactly_zero(track: float) -> None:
    # Equal wheel increments: the two products cancel exactly when each is rounded
    # once and then added; a fused multiply-add (the AVX-512 kernel's) left -7.4e-17.
    robot = Robot(
        drive=DiffDrive(track=track, wheel_radius=0.05), footprint=0.1,
        encoders=WheelEncoders(ticks_per_rev=4096),
    )  # fmt: skip
    fusion = _Recording(pose=(0.0, 0.0, 0.0), t0=0.0)
    Simulation(
        World(box(-5.0, -5.0, 50.0, 5.0).exterior), robot, _straight, start=(0.0, 0.0, 0.0),
        duration=5.0, estimator=fusion,
    ).run()  # fmt: skip
    assert len(fusion.odometry) > 100
    speeds = np.array(fusion.odometry)
    assert np.all(speeds[1:, 0] > 0.3)  # it drove (the first reading latches the counters)
    assert np.all(speeds[:, 1] == 0.0), speeds[speeds[:, 1] != 0.0][:3]


_PROBE = """
import hashlib, json
from shapely.geometry import box
from navkit.estimation import PlanarFusion
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Robot, Simulation, World, WheelEncoders, Imu, Compass
import numpy as np
robot = Robot(
    drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.2, wheel_slip=0.01,
    encoders=WheelEncoders(latency=0.02), imu=Imu(gyro_noise=0.01), compass=Compass(noise=0.01),
)
trace = Simulation(
    World(box(-3.0, -3.0, 30.0, 3.0).exterior), robot,
    lambda obs: Twist2D(0.4, 0.0, 0.3 * np.sin(obs.t)), start=(0.0, 0.0, 0.0),
    duration=20.0, seed=3, estimator=PlanarFusion(pose=(0.0, 0.0, 0.0), t0=0.0),
).run()
print(json.dumps(hashlib.sha256(trace.estimates.tobytes()).hexdigest()))
"""


@pytest.mark.slow
def test_the_estimate_is_the_same_under_every_openblas_kernel(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    digests = {}
    for core in core_types():
        monkeypatch.setenv("OPENBLAS_CORETYPE", core)
        digests[core] = probe_outcome(_PROBE)
    assert len(set(digests.values())) == 1, json.dumps(digests)
