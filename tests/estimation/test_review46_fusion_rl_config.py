"""PlanarFusion configured as robot_localization's own bag tests (review 46).

robot_localization's regression tests (``test/test_ekf_localization_node_bag1.test``
and ``..._bag2.test`` / ``.yaml`` upstream) run its EKF on these bags with:

=====================  ===============================  ==================================
setting                test1 (Husky, 395 s)             test2 (Jackal, 61 s)
=====================  ===============================  ==================================
``odom0_config``       vx, vy, vz                       vx, vy, vz, vyaw
``imu0_config``        roll, pitch, yaw, vroll,         roll, pitch, yaw, vroll, vpitch,
                       vpitch, ax, ay, az (no vyaw)     vyaw, ax, ay, az
``*_differential``     false (absolute yaw)             false
``two_d_mode``         false (3-D)                      false
``frequency``          30 Hz                            50 Hz
process noise          x, y 0.05; yaw 0.06; vx 0.025;   x, y 0.03; yaw 0.06; vx 0.025;
                       vyaw 0.02; ax 0.01               vyaw 0.004; ax 0.01
initial covariance     1e-9 on every state              1e-9 on every state
gravity removed        yes                              yes
accepted end (m)       (-40.0454, -76.9988) ± 1.0452    (1.0206, 3.4292) ± 0.1383
=====================  ===============================  ==================================

The planar equivalent fuses the same inputs that have a planar state: the wheel
speed (and, for test2, the wheel yaw rate), the IMU's absolute yaw (and, for
test2, the gyro's yaw rate) and the IMU's forward acceleration with gravity
removed (through the IMU orientation, as ``imu0_remove_gravitational_acceleration``
does), with the launch files' process noise and initial covariance
(``frequency`` has no counterpart: PlanarFusion predicts to every
measurement's stamp, as robot_localization does inside its cycle). vy = vz = 0
and roll / pitch have no planar state: the wheel speed is projected on the
ground with the IMU pitch instead of RL's 3-D integration. End point against
robot_localization's accepted one (no ground truth exists):

=======================================  ==============  ==============
configuration                            test1 (m)       test2 (m)
=======================================  ==============  ==============
as robot_localization (above)            0.201           0.013
  speed not projected on the ground      0.189           **0.210**
  navkit's default Q and P0              0.215           0.013
  without the forward acceleration       0.229           0.013
  gyro yaw rate flipped (on 1, off 2)    0.210           0.079
  gyro instead of the IMU's yaw          **84.4**        **0.872**
=======================================  ==============  ==============

(bold: outside robot_localization's tolerance). The path lengths are 359 m
and 84 m, so the ends are 0.056 % and 0.016 % of the distance driven from
RL's. Only two settings matter beyond the tolerances: the absolute yaw (on
test1 the "slightly broken" IMU's yaw carries RL's result: navkit with the
gyro ends near the GPS track instead, see test_fusion_robot_localization_bags)
and, on test2, the 0.74 m climb that RL's 3-D filter integrates. test1's
remaining 0.2 m (19 % of RL's tolerance) is explained by no single planar
setting; what a planar filter lacks (RL's lateral and vertical velocity
states pinned by the odometry's vy = vz = 0, its roll and pitch dynamics)
remains. Not a navkit defect.

Gating: robot_localization gates nothing unless ``*_rejection_threshold``
is set (these tests do not). Gated at 0.997 (``gate_probability``), the
test2 configuration above rejects 6,581 of its 12,243 readings (2,678 of the
3,060 wheel speeds, 2,155 of the 3,061 accelerations, no yaw) and ends 34 m
off: the Jackal's wheel speed changes at up to 8 m/s² (99th percentile of
its steps) where the process noise allows far less, and the IMU's stated
acceleration deviation (0.005 m/s²) is far below its scatter (0.03 m/s² at
rest, 0.4 m/s² from step to step while driving), so once
the speed lags, every later one is further off (one run of 2,086 rejected
speeds, 41.7 s). Each rejected row keeps the prediction, as documented.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.estimation import FusionResult, FusionStatus, MeasurementLog, PlanarFusion
from navkit.geometry import quaternion_to_matrix, quaternion_to_yaw

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from rl_bags import read_bag

pytest.importorskip("rosbags")

GRAVITY = 9.80665


@dataclass(frozen=True)
class Upstream:
    """robot_localization's settings and accepted end point for one bag (see the docstring)."""

    wheel_rate: bool
    gyro: bool
    process_noise: tuple[float, ...]
    end: tuple[float, float]
    tolerance: float


UPSTREAM = {
    "test1": Upstream(
        False, False,
        (0.05, 0.05, 0.06, 0.025, 0.02, 0.01), (-40.0454, -76.9988), 1.0452,
    ),
    "test2": Upstream(
        True, True, (0.03, 0.03, 0.06, 0.025, 0.004, 0.01), (1.0206, 3.4292), 0.1383,
    ),
}  # fmt: skip


@dataclass
class Bag:
    t0: float
    odom_times: np.ndarray
    speed: np.ndarray  # wheel forward speed, m/s
    ground: np.ndarray  # cos(pitch) at the odometry stamps
    wheel_rate: np.ndarray
    odom_var: np.ndarray  # (T, 2): speed, yaw rate variances
    imu_times: np.ndarray
    yaw: np.ndarray
    yaw_var: np.ndarray
    rate: np.ndarray
    rate_var: np.ndarray
    accel: np.ndarray  # forward, gravity removed, m/s²
    accel_var: np.ndarray
    path_length: float


def _load(shared_data: Path, name: str) -> Bag:
    odom, imu, base = read_bag(shared_data, name)
    rot = quaternion_to_matrix(base.orientations)  # base_link in the world
    cos_pitch = np.hypot(rot[:, 0, 0], rot[:, 1, 0])
    # a - Rᵀ g: the specific force less gravity, in base_link; its x is the forward one.
    accel = base.linear_accelerations[:, 0] - GRAVITY * rot[:, 2, 0]
    return Bag(
        t0=float(min(odom.times[0], imu.times[0])),
        odom_times=odom.times,
        speed=odom.twists[:, 0],
        ground=np.interp(odom.times, imu.times, cos_pitch),
        wheel_rate=odom.twists[:, 2],
        odom_var=np.column_stack(
            (odom.twist_covariances[:, 0, 0], odom.twist_covariances[:, 5, 5])
        ),
        imu_times=imu.times,
        yaw=np.asarray(quaternion_to_yaw(base.orientations), dtype=np.float64),
        yaw_var=base.orientation_covariances[:, 2, 2],
        rate=base.angular_velocities[:, 2],
        rate_var=base.angular_velocity_covariances[:, 2, 2],
        accel=accel,
        accel_var=base.linear_acceleration_covariances[:, 0, 0],
        path_length=float(np.sum(np.abs(odom.twists[:-1, 0]) * np.diff(odom.times))),
    )


@pytest.fixture(scope="module")
def bags(shared_data: Path) -> dict[str, Bag]:
    return {name: _load(shared_data, name) for name in UPSTREAM}


def fuse(
    bag: Bag,
    up: Upstream,
    *,
    project: bool = True,
    upstream_noise: bool = True,
    accel: bool = True,
    gyro: bool | None = None,
    yaw: bool = True,
    gate_probability: float | None = None,
) -> tuple[FusionResult, MeasurementLog]:
    speed = bag.speed * bag.ground if project else bag.speed
    streams: dict[str, Any] = {}
    if up.wheel_rate:
        streams["odometry"] = (bag.odom_times, speed, bag.wheel_rate)
        streams["odometry_variance"] = (bag.odom_var[:, 0], bag.odom_var[:, 1])
    else:
        streams["odometry"] = (bag.odom_times, speed)
        streams["odometry_variance"] = (bag.odom_var[:, 0], 1.0)
    if yaw:
        streams["yaw"] = (bag.imu_times, bag.yaw)
        streams["yaw_variance"] = bag.yaw_var
    if (up.gyro if gyro is None else gyro) or not yaw:
        streams["yaw_rate"] = (bag.imu_times, bag.rate)
        streams["yaw_rate_variance"] = bag.rate_var
    if accel:
        streams["acceleration"] = (bag.imu_times, bag.accel)
        streams["acceleration_variance"] = bag.accel_var
    log = MeasurementLog.from_streams(**streams)
    x0 = [0.0, 0.0, float(bag.yaw[0]), 0.0, 0.0, 0.0]
    if upstream_noise:
        fusion = PlanarFusion(
            x0, np.full(6, 1e-9), process_noise=up.process_noise, t0=bag.t0,
            gate_probability=gate_probability,
        )  # fmt: skip
    else:
        fusion = PlanarFusion(x0, t0=bag.t0, gate_probability=gate_probability)
    return fusion.update_batch(log), log


def miss(result: FusionResult, up: Upstream) -> float:
    end = result.final_pose
    return math.hypot(end.x - up.end[0], end.y - up.end[1])


@pytest.mark.parametrize(
    ("name", "expected"),
    [
        ("test1", (0.201, 0.189, 0.215, 0.229, 0.210, 84.385)),
        ("test2", (0.013, 0.210, 0.013, 0.013, 0.079, 0.872)),
    ],
)
def test_robot_localization_configuration(
    bags: dict[str, Bag], name: str, expected: tuple[float, ...]
) -> None:
    bag, up = bags[name], UPSTREAM[name]
    as_rl, _ = fuse(bag, up)
    assert np.all(as_rl.status == FusionStatus.ACCEPTED)
    assert np.all(np.isfinite(as_rl.states))
    variants = [
        as_rl,
        fuse(bag, up, project=False)[0],
        fuse(bag, up, upstream_noise=False)[0],
        fuse(bag, up, accel=False)[0],
        fuse(bag, up, gyro=not up.gyro)[0],
        fuse(bag, up, yaw=False)[0],
    ]
    misses = [miss(r, up) for r in variants]
    # The figures of the module docstring.
    assert misses == pytest.approx(expected, abs=0.0015)
    within = [m < up.tolerance for m in misses]
    # As robot_localization configures it: within its tolerance, a small fraction of the path.
    assert within[0] and misses[0] < 1e-3 * bag.path_length
    # Settings that each stay within the tolerance: the defaults, the acceleration.
    assert within[2] and within[3] and within[4]
    # Settings that do not: the absolute yaw (both), the ground projection (test2's climb).
    assert not within[5]
    assert within[1] == (name == "test1")


def test_gated_rows_keep_the_prediction(bags: dict[str, Bag]) -> None:
    """With a gate, the Jackal's fast accelerations are gated: each gated row is the prediction."""
    bag, up = bags["test2"], UPSTREAM["test2"]
    result, log = fuse(bag, up, gate_probability=0.997)
    gated = np.flatnonzero(result.status == FusionStatus.GATED)
    speeds = gated[log.observed[gated, 1]]
    assert speeds.size > 100
    assert np.all(np.isfinite(result.states))
    for k in (int(speeds[0]), int(speeds[speeds.size // 2]), int(speeds[-1])):
        head = MeasurementLog(log.times[:k], log.values[:k], log.variances[:k], log.observed[:k])
        fusion = PlanarFusion(
            [0.0, 0.0, float(bag.yaw[0]), 0.0, 0.0, 0.0], np.full(6, 1e-9),
            process_noise=up.process_noise, t0=bag.t0, gate_probability=0.997,
        )  # fmt: skip
        fusion.update_batch(head)
        fusion.predict(float(log.times[k]))
        np.testing.assert_array_equal(result.states[k], fusion.x)
        np.testing.assert_array_equal(result.covariances[k], fusion.P)
        assert result.nis[k] > 8.807  # the 0.997 chi-square quantile of one component


def test_gate_on_robot_localization_configuration(bags: dict[str, Bag]) -> None:
    """The figures of ``PlanarFusion(gate_probability=)``: a gate rejects much of test2's data."""
    bag, up = bags["test2"], UPSTREAM["test2"]
    plain, log = fuse(bag, up)
    gated, _ = fuse(bag, up, gate_probability=0.997)
    assert len(log) == 12243
    assert int(np.sum(plain.status == FusionStatus.GATED)) == 0
    assert int(np.sum(gated.status == FusionStatus.GATED)) == 6581
    assert miss(plain, up) == pytest.approx(0.013, abs=5e-4)
    assert miss(gated, up) == pytest.approx(34.1, abs=0.1)
    # Rejections run on: some run of consecutive rejected wheel speeds lasts seconds.
    speed = log.observed[:, 1]
    rejected = gated.status[speed] == FusionStatus.GATED
    times = log.times[speed]
    edges = np.flatnonzero(np.diff(np.concatenate(([0], rejected.astype(np.int8), [0]))))
    longest = max(
        float(times[b - 1] - times[a]) for a, b in zip(edges[::2], edges[1::2], strict=True)
    )
    assert longest > 2.0
