"""Fixtures: the robot_localization regression bags' CSV dumps, read with numpy."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

FOLDER = "robot-localization-odom-imu-bags"


def read_csv(path: Path, columns: tuple[str, ...]) -> dict[str, FloatArray]:
    """Numeric ``columns`` of a CSV dump, by header name."""
    with path.open() as fh:
        header = fh.readline().strip().split(",")
    idx = [header.index(c) for c in columns]
    data = np.loadtxt(path, delimiter=",", skiprows=1, usecols=idx, ndmin=2)
    return {c: data[:, i] for i, c in enumerate(columns)}


def load_bag(shared_data: Path, name: str) -> dict[str, dict[str, FloatArray]]:
    """Wheel odometry and IMU (and GPS for test1) of ``name`` ("test1" or "test2")."""
    folder = shared_data / FOLDER / "csv_extract"
    out = {
        "odom": read_csv(
            folder / f"{name}_wheel_odom.csv",
            ("stamp", "x", "y", "qx", "qy", "qz", "qw", "vx", "wz", "twist_cov_vxvx"),
        ),
        "imu": read_csv(
            folder / f"{name}_imu.csv",
            ("stamp", "qx", "qy", "qz", "qw", "wx", "wy", "wz", "ori_cov_zz", "gyr_cov_zz"),
        ),
    }
    gps = folder / f"{name}_gps_fix.csv"
    if gps.exists():
        out["gps"] = read_csv(gps, ("stamp", "latitude", "longitude"))
    return out


@pytest.fixture(scope="session")
def bag_test1(shared_data: Path) -> dict[str, dict[str, FloatArray]]:
    """Husky parking-lot run: wheel odometry, rotated IMU and GPS."""
    return load_bag(shared_data, "test1")


@pytest.fixture(scope="session")
def bag_test2(shared_data: Path) -> dict[str, dict[str, FloatArray]]:
    """Jackal run: wheel odometry and IMU."""
    return load_bag(shared_data, "test2")
