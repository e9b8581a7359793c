"""Bag readers on damaged copies of the real bags (review 46).

A bag cut anywhere, or with a flipped bit in a compressed chunk, is refused with
a ``ValueError`` naming it (or, for a flip rosbags cannot see, read as the
bag holds); a message declaring 2**31 ranges is refused naming the message,
without allocating them. ROS 1 bags carry no checksum: a flipped bit in an
uncompressed message's numbers (demo.bag) reads as another number, which no
reader can tell.
"""

from __future__ import annotations

import random
import struct
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from memory_peak import peak_bytes
from navkit.mapping.io import read_bag_imu, read_bag_odometry, read_bag_scans

pytest.importorskip("rosbags")

RL = "robot-localization-odom-imu-bags"
DEMO = "rosbag-hokuyo-laserscan-demo"


def _odometry(path: Path) -> tuple[bytes, ...]:
    odom = read_bag_odometry(path)
    return tuple(
        getattr(odom, name).tobytes()
        for name in ("times", "record_times", "poses", "twists", "twist_covariances")
    )


def _imu(path: Path) -> tuple[bytes, ...]:
    imu = read_bag_imu(path, topic="/imu/data")
    return tuple(
        getattr(imu, name).tobytes()
        for name in ("times", "record_times", "orientations", "angular_velocities")
    )


def _scans(path: Path) -> tuple[bytes, ...]:
    scans = read_bag_scans(path)
    return (scans.times.tobytes(), np.array([s.ranges for s in scans.scans]).tobytes())


def _damage(
    shared_data: Path, tmp_path: Path, name: str, read: Callable[[Path], Any], count: int
) -> dict[str, int]:
    """Read ``count`` cut and ``count`` bit-flipped copies of bag ``name``; how each came out."""
    data = (shared_data / name).read_bytes()
    path = tmp_path / "damaged.bag"
    path.write_bytes(data)
    whole = read(path)
    rng = random.Random(f"46{name}")
    outcomes = {"refused": 0, "same": 0, "other numbers": 0}
    for kind in ("cut", "flip"):
        for _ in range(count):
            offset = rng.randrange(len(data))
            if kind == "cut":
                damaged = data[:offset]
            else:
                flipped = bytearray(data)
                flipped[offset] ^= 1 << rng.randrange(8)
                damaged = bytes(flipped)
            path.write_bytes(damaged)
            try:
                got = read(path)
            except ValueError as exc:
                assert str(path) in str(exc), exc
                outcomes["refused"] += 1
                continue
            assert kind == "flip", f"a bag cut at byte {offset} of {len(data)} was read"
            outcomes["same" if got == whole else "other numbers"] += 1
    return outcomes


@pytest.mark.parametrize(
    ("name", "read", "count"),
    [(f"{RL}/test2.bag", _odometry, 12), (f"{DEMO}/demo.bag", _scans, 12)],
)
def test_damaged_bags_are_refused_naming_them(
    shared_data: Path, tmp_path: Path, name: str, read: Callable[[Path], Any], count: int
) -> None:
    outcomes = _damage(shared_data, tmp_path, name, read, count)
    if name.endswith("test2.bag"):  # compressed chunks: their damage is seen
        assert outcomes["other numbers"] == 0, outcomes


@pytest.mark.slow
@pytest.mark.parametrize(
    ("name", "read", "count"),
    [
        (f"{RL}/test2.bag", _odometry, 150),
        (f"{RL}/test1.bag", _imu, 50),
        (f"{DEMO}/demo.bag", _scans, 100),
    ],
)
def test_many_damaged_bags_are_refused_naming_them(
    shared_data: Path, tmp_path: Path, name: str, read: Callable[[Path], Any], count: int
) -> None:
    outcomes = _damage(shared_data, tmp_path, name, read, count)
    if "/test" in name:
        assert outcomes["other numbers"] == 0, outcomes


@pytest.mark.parametrize("count", [2**31, 2**32 - 1, 682])
def test_a_scan_declaring_too_many_ranges_is_refused_without_allocating_them(
    shared_data: Path, tmp_path: Path, count: int
) -> None:
    data = bytearray((shared_data / DEMO / "demo.bag").read_bytes())
    # The first message's range count (681), after its five float32 angles and ranges.
    at = data.index(struct.pack("<I", 681))
    data[at : at + 4] = struct.pack("<I", count)
    path = tmp_path / "huge.bag"
    path.write_bytes(bytes(data))

    def read() -> str:
        with pytest.raises(ValueError, match="message 0 of /scan cannot be decoded") as info:
            read_bag_scans(path)
        return str(info.value)

    peak, message = peak_bytes(read)
    assert message.startswith(str(path))
    assert peak < 8 * len(data)  # the bag read whole, not 4 bytes x 2**31
