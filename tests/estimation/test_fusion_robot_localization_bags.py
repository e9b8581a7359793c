"""PlanarFusion on robot_localization's own regression recordings (real robots).

test2 (Jackal, 61 s, 50 Hz odometry and IMU)
    Fused: wheel-odometry forward speed, IMU yaw and gyro yaw rate. The wheel yaw
    rate is not fused: the Jackal is skid-steered and its odometry yaw rate
    averages 0.58 rad/s against the gyro's 0.078 rad/s. The robot climbs 0.74 m
    during the run (the z of robot_localization's 3-D result), so the speed is
    projected onto the ground plane with the IMU's pitch (v·cos pitch) before the
    2-D fusion; robot_localization's 3-D filter accounts for the slope itself.
    End position (1.0109, 3.4306) m, 0.010 m from robot_localization's accepted
    EKF result (1.0206, 3.4292) ± 0.1383 m. Without the projection it would be
    (1.0158, 3.6410), 0.212 m off: outside the tolerance.

test1 (Husky, 395 s parking-lot loop, IMU mounted rotated, GPS)
    The IMU orientation and gyro are rotated into base_link with the mounting
    transform of the upstream launch file (roll +π/2, yaw −π/2). Compared with the
    GPS track (latitude/longitude to local east/north metres, each trajectory
    rigidly aligned to it by least squares since the odometry frame's heading is
    arbitrary):

    ================================  =================  ==========  ==========  ==========
    estimate                          end − start (m)    |end −      RMS vs GPS  end vs GPS
                                      in its own frame   start|
    ================================  =================  ==========  ==========  ==========
    GPS (east, north)                 (13.36, -1.35)     13.43 m     —           —
    wheel odometry (Husky controller) (-24.04, -19.37)   30.87 m     6.98 m      12.52 m
    fused: odometry + gyro            (-8.44, 1.12)      8.52 m      3.04 m      7.94 m
    fused: odometry + gyro + IMU yaw  (-39.81, -77.04)   86.72 m     21.36 m     31.64 m
    ================================  =================  ==========  ==========  ==========

    GPS puts the end 13.4 m from the start. The "slightly broken" Microstrain's
    absolute yaw is badly wrong, so fusing it (what the upstream test does) is far
    worse than the gyro alone — but it reproduces robot_localization's accepted
    end position (-40.0454, -76.9988) ± 1.0452 m within 0.24 m.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from navkit.estimation import FusionResult, FusionStatus, MeasurementLog, PlanarFusion
from navkit.geometry import quaternion_to_matrix, quaternion_to_yaw, rpy_to_quaternion
from navkit.mapping.io import BagImu, BagOdometry, read_bag_imu, read_bag_odometry

pytest.importorskip("rosbags")

FOLDER = "robot-localization-odom-imu-bags"


class Bag:
    """Wheel odometry, IMU (and test1's GPS fixes, from the CSV dump) of one bag."""

    def __init__(self, shared_data: Path, name: str) -> None:
        path = shared_data / FOLDER / f"{name}.bag"
        self.odom: BagOdometry = read_bag_odometry(path)
        self.imu: BagImu = read_bag_imu(path, topic="/imu/data")
        gps = shared_data / FOLDER / "csv_extract" / f"{name}_gps_fix.csv"
        if gps.exists():  # sensor_msgs/NavSatFix has no navkit reader
            with gps.open() as fh:
                header = fh.readline().strip().split(",")
            cols = [header.index(c) for c in ("stamp", "latitude", "longitude")]
            table = np.loadtxt(gps, delimiter=",", skiprows=1, usecols=cols, ndmin=2)
            self.gps = dict(zip(("stamp", "latitude", "longitude"), table.T, strict=True))


@pytest.fixture(scope="module")
def bag_test1(shared_data: Path) -> Bag:
    """Husky parking-lot run: wheel odometry, rotated IMU and GPS."""
    return Bag(shared_data, "test1")


@pytest.fixture(scope="module")
def bag_test2(shared_data: Path) -> Bag:
    """Jackal run: wheel odometry and IMU."""
    return Bag(shared_data, "test2")


def imu_in_base(imu: BagImu, mount: np.ndarray) -> tuple[np.ndarray, ...]:
    """Yaw, pitch-projection factor and yaw rate of base_link from an IMU mounted as ``mount``."""
    base = imu.to_base(mount)
    yaw = np.asarray(quaternion_to_yaw(base.orientations))
    r_world_base = quaternion_to_matrix(base.orientations)
    horizontal = np.hypot(r_world_base[:, 0, 0], r_world_base[:, 1, 0])  # cos(pitch)
    return yaw, horizontal, base.angular_velocities[:, 2]


def fuse(
    bag: Bag, mount: np.ndarray, *, use_yaw: bool, use_wheel_rate: bool, project: bool
) -> FusionResult:
    odom, imu = bag.odom, bag.imu
    yaw, horizontal, rate = imu_in_base(imu, mount)
    speed = odom.twists[:, 0] * (np.interp(odom.times, imu.times, horizontal) if project else 1.0)
    if use_wheel_rate:
        odometry: tuple[np.ndarray, ...] = (odom.times, speed, odom.twists[:, 2])
    else:
        odometry = (odom.times, speed)
    streams: dict[str, object] = {
        "odometry": odometry,
        "odometry_variance": (odom.twist_covariances[:, 0, 0], 0.03),
        "yaw_rate": (imu.times, rate),
        "yaw_rate_variance": imu.angular_velocity_covariances[:, 2, 2],
    }
    if use_yaw:
        streams["yaw"] = (imu.times, yaw)
        streams["yaw_variance"] = imu.orientation_covariances[:, 2, 2]
    log = MeasurementLog.from_streams(**streams)  # type: ignore[arg-type]
    t0 = min(odom.times[0], imu.times[0])
    result = PlanarFusion([0.0, 0.0, yaw[0], 0.0, 0.0, 0.0], t0=t0).update_batch(log)
    assert np.all(result.status == FusionStatus.ACCEPTED)
    return result


def test_jackal_end_position_within_robot_localization_tolerance(bag_test2: Bag) -> None:
    level = np.array([0.0, 0.0, 0.0, 1.0])
    result = fuse(bag_test2, level, use_yaw=True, use_wheel_rate=False, project=True)
    end = result.final_pose
    miss = math.hypot(end.x - 1.0206, end.y - 3.4292)
    assert miss < 0.1383
    assert end.x == pytest.approx(1.0109, abs=1e-3)
    assert end.y == pytest.approx(3.4306, abs=1e-3)
    flat = fuse(bag_test2, level, use_yaw=True, use_wheel_rate=False, project=False)
    assert math.hypot(flat.final_pose.x - 1.0206, flat.final_pose.y - 3.4292) > 0.1383


HUSKY_MOUNT = rpy_to_quaternion(math.pi / 2, 0.0, -math.pi / 2)  # base_link -> imu_link


def gps_local(gps: dict[str, np.ndarray]) -> np.ndarray:
    """Latitude/longitude to east/north metres about the first fix (equirectangular)."""
    lat = np.radians(gps["latitude"])
    lon = np.radians(gps["longitude"])
    earth = 6378137.0
    return np.column_stack((earth * math.cos(lat[0]) * (lon - lon[0]), earth * (lat - lat[0])))


def drift_vs_gps(
    times: np.ndarray, xy: np.ndarray, gps: dict[str, np.ndarray]
) -> tuple[float, float]:
    """RMS and end-point distance to the GPS track after the best rigid 2-D alignment."""
    ref = gps_local(gps)
    est = np.column_stack(
        (np.interp(gps["stamp"], times, xy[:, 0]), np.interp(gps["stamp"], times, xy[:, 1]))
    )
    mu_e, mu_r = est.mean(axis=0), ref.mean(axis=0)
    u, _, vt = np.linalg.svd((ref - mu_r).T @ (est - mu_e))
    rot = u @ np.diag([1.0, np.sign(np.linalg.det(u @ vt))]) @ vt
    aligned = (est - mu_e) @ rot.T + mu_r
    err = np.hypot(*(aligned - ref).T)
    return float(np.sqrt(np.mean(err**2))), float(err[-1])


def test_husky_fusion_against_gps(bag_test1: Bag) -> None:
    odom, gps = bag_test1.odom, bag_test1.gps
    wheel_rms, wheel_end = drift_vs_gps(odom.times, odom.poses[:, :2], gps)
    gyro = fuse(bag_test1, HUSKY_MOUNT, use_yaw=False, use_wheel_rate=True, project=False)
    gyro_rms, gyro_end = drift_vs_gps(gyro.times, gyro.states[:, :2], gps)
    full = fuse(bag_test1, HUSKY_MOUNT, use_yaw=True, use_wheel_rate=True, project=False)
    full_rms, full_end = drift_vs_gps(full.times, full.states[:, :2], gps)
    # The figures in the module docstring.
    assert (wheel_rms, wheel_end) == pytest.approx((6.98, 12.52), abs=0.01)
    assert (gyro_rms, gyro_end) == pytest.approx((3.04, 7.94), abs=0.01)
    assert (full_rms, full_end) == pytest.approx((21.36, 31.64), abs=0.01)
    # Odometry + gyro halves the drift of wheel odometry alone.
    assert gyro_rms < 0.5 * wheel_rms
    assert gyro_end < wheel_end
    # Fusing the IMU's absolute yaw reproduces robot_localization's regression end point.
    end = full.final_pose
    assert math.hypot(end.x + 40.0454, end.y + 76.9988) < 1.0452
