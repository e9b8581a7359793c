"""CARMEN log reader and maps built from the real Radish logs in ../shared/data."""

from __future__ import annotations

import dataclasses
import gzip
import math
from pathlib import Path

import numpy as np
import pytest

import navkit.mapping
from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid, integrate_scan
from navkit.mapping.io import CarmenLog, read_carmen

LOGS = "carmen-logs"


@pytest.fixture(scope="module")
def intel(shared_data: Path) -> CarmenLog:
    return read_carmen(shared_data / LOGS / "intel-corrected.log.gz")


@pytest.mark.parametrize(
    ("name", "scans", "beams", "odom", "first", "last", "range_max"),
    [
        ("intel", 910, 180, 14541, 32.9, 2683.8, 81.83),
        ("aces", 440, 180, 7814, 21.0, 1339.1, 50.0),
        ("csail", 406, 361, 2394, None, None, 81.91),
    ],
)
def test_logs_match_their_readme(
    shared_data: Path,
    name: str,
    scans: int,
    beams: int,
    odom: int,
    first: float | None,
    last: float | None,
    range_max: float,
) -> None:
    log = read_carmen(shared_data / LOGS / f"{name}-corrected.log.gz")
    assert len(log) == scans == len(log.laser_poses) == len(log.robot_poses)
    assert {len(s) for s in log.scans} == {beams}
    assert log.odometry.shape == (odom, 4)
    if first is not None and last is not None:
        assert log.times.min() == pytest.approx(first, abs=0.05)
        assert log.times.max() == pytest.approx(last, abs=0.05)
    scan = log.scans[0]
    # CARMEN's guessed geometry: first beam at -90°, 1° (180 beams) or 0.5° (361).
    assert scan.angle_min == pytest.approx(-math.pi / 2)
    assert scan.angle_increment == pytest.approx(math.pi / (180 if beams == 180 else 360))
    assert scan.range_max == range_max
    # Readings equal to the maximum are "no return", never points.
    for s in log.scans[::20]:
        assert np.array_equal(s.valid_mask(), s.ranges < range_max)


def test_odometry_headings_are_wrapped(tmp_path: Path) -> None:
    path = tmp_path / "log.txt"
    path.write_text(
        "FLASER 2 1.0 2.0 0 0 3.5 0 0 3.5 1.0 h 1.0\n"
        "ODOM 1 2 3.5 0 0 0 2.0 h 2.0\nODOM 1 2 -3.141592653589793 0 0 0 3.0 h 3.0\n"
    )
    log = read_carmen(path)
    assert log.laser_poses[0].theta == pytest.approx(3.5 - 2.0 * math.pi)
    np.testing.assert_allclose(log.odometry[:, 2], [3.5 - 2.0 * math.pi, math.pi], atol=1e-12)
    assert log.odometry[1, 2] > 0.0  # (-π, π]: -π becomes +π
    assert log.odometry[:, [0, 1, 3]].tolist() == [[1.0, 2.0, 2.0], [1.0, 2.0, 3.0]]
    made = CarmenLog(log.scans, log.laser_poses, log.robot_poses, [1.0], [[0.0, 0.0, -7.0, 1.0]])
    assert made.odometry[0, 2] == pytest.approx(-7.0 + 2.0 * math.pi)


def test_real_odometry_headings_are_wrapped(shared_data: Path) -> None:
    # csail's ODOM headings run up to 11.06 rad, intel's to 3.247 rad.
    for name in ("csail", "intel"):
        log = read_carmen(shared_data / LOGS / f"{name}-corrected.log.gz")
        theta = log.odometry[:, 2]
        assert np.all((theta > -math.pi) & (theta <= math.pi))
        if name == "csail":  # the line "ODOM 21.44 4.5 11.058 0 0 0 1.13486e+09 ..."
            row = np.flatnonzero((log.odometry[:, 0] == 21.44) & (log.odometry[:, 1] == 4.5))
            assert theta[row].tolist() == pytest.approx([11.058 - 4.0 * math.pi])


def test_odometry_agrees_with_corrected_poses(shared_data: Path) -> None:
    # README: the ODOM poses of intel and aces agree with the corrected FLASER
    # poses to a few cm. ODOM lines with timestamp 0 are copies written after
    # each FLASER line, so only timed records are compared.
    for name in ("intel", "aces"):
        log = read_carmen(shared_data / LOGS / f"{name}-corrected.log.gz")
        odom = log.odometry[log.odometry[:, 3] > 0]
        nearest = np.abs(odom[None, :, 3] - log.times[:, None]).argmin(axis=1)
        laser = np.array([[p.x, p.y] for p in log.laser_poses])
        gap = np.hypot(*(odom[nearest, :2] - laser).T)
        assert np.median(gap) < 0.1


def test_intel_builds_a_recognisable_map(shared_data: Path, intel: CarmenLog) -> None:
    points = [s.to_points(p) for s, p in zip(intel.scans, intel.laser_poses, strict=True)]
    hits = np.vstack(points)
    lo = hits.min(axis=0) - 1.0
    hi = hits.max(axis=0) + 1.0
    width, height = hi - lo
    grid = OccupancyGrid.empty(
        width=width, height=height, resolution=0.1, origin=Pose2D(lo[0], lo[1], 0.0)
    )
    for scan, pose in zip(intel.scans, intel.laser_poses, strict=True):
        integrate_scan(grid, scan, pose)
    rows, cols = grid.shape

    # Most returns fall on cells that many scans hit: the SLAM-corrected poses
    # put the same walls in the same cells.
    cells = grid.world_to_cell(hits)
    flat = cells[:, 0] * cols + cells[:, 1]
    counts = np.bincount(flat, minlength=rows * cols)
    assert np.mean(counts[flat] >= 3) > 0.95
    # The log-odds map agrees: most returns land on occupied cells, and every
    # robot pose is in free space.
    assert np.mean(grid.occupied().ravel()[flat]) > 0.8
    robot = grid.world_to_cell([[p.x, p.y] for p in intel.laser_poses])
    assert grid.free()[robot[:, 0], robot[:, 1]].all()

    # Extent of the walls: the Intel lab is a square building (about 29 m on a
    # side); its map preview in the dataset is 200 x 199 px, the same shape.
    occ = grid.cell_to_world(np.argwhere(grid.occupied()))
    extent = np.ptp(np.percentile(occ, [1, 99], axis=0), axis=0)
    assert np.all((extent > 27.0) & (extent < 31.0))
    image = pytest.importorskip("PIL.Image")
    with image.open(shared_data / LOGS / "intel-corrected.png") as preview:
        width_px, height_px = preview.size
    assert extent[0] / extent[1] == pytest.approx(width_px / height_px, rel=0.05)


def test_robotlaser1_lines(tmp_path: Path) -> None:
    ranges = " ".join(["1.5"] * 5)
    line = (
        f"ROBOTLASER1 0 -0.5 1.0 0.25 8.0 0.01 0 5 {ranges} 5 1 2 3 4 5 "
        "1.0 2.0 0.1 0.9 2.0 0.1 0 0 0 0 0 123.5 host 123.6\n"
    )
    path = tmp_path / "log.gz"
    with gzip.open(path, "wt") as fh:
        fh.write("# comment\nPARAM a b\n" + line + "ODOM 1 2 0.5 0 0 0 99.0 host 99.1\n")
    log = read_carmen(path)
    scan = log.scans[0]
    assert (scan.angle_min, scan.angle_increment, scan.range_max) == (-0.5, 0.25, 8.0)
    assert scan.intensities is not None and scan.intensities.tolist() == [1, 2, 3, 4, 5]
    assert log.laser_poses[0] == Pose2D(1.0, 2.0, 0.1)
    assert log.robot_poses[0] == Pose2D(0.9, 2.0, 0.1)
    assert log.times.tolist() == [123.5]
    assert log.odometry.tolist() == [[1.0, 2.0, 0.5, 99.0]]


def test_flaser_range_max_override(tmp_path: Path) -> None:
    path = tmp_path / "log.txt"
    path.write_text("FLASER 3 1.0 2.0 5.0 0 0 0 0 0 0 1.0 host 1.0\n")
    assert read_carmen(path).scans[0].valid_mask().tolist() == [True, True, False]
    scan = read_carmen(path, range_max=10.0).scans[0]
    assert scan.valid_mask().tolist() == [True, True, True]
    # CARMEN's fallback geometry for unusual beam counts: 180° over n - 1 gaps.
    assert scan.angle_increment == pytest.approx(math.pi / 2)


@pytest.mark.parametrize(
    ("text", "error", "match"),
    [
        ("FLASER 3 1.0 2.0 0 0 0 0 0 0 1.0 host 1.0\n", ValueError, "log.txt:1: malformed FLASER"),
        ("ODOM 1 2\n", ValueError, ":1: malformed ODOM"),
        ("ODOM 1 2 3 0 0 0 1.0 h 1.0\n", ValueError, "no FLASER or ROBOTLASER1 lines"),
        ("FLASER x 1.0\n", ValueError, "malformed FLASER"),
    ],
)
def test_bad_logs(tmp_path: Path, text: str, error: type[Exception], match: str) -> None:
    path = tmp_path / "log.txt"
    path.write_text(text)
    with pytest.raises(error, match=match):
        read_carmen(path)


def test_missing_log() -> None:
    with pytest.raises(FileNotFoundError, match="does not exist"):
        read_carmen("/nonexistent/log.gz")


def test_one_public_path() -> None:
    # The reader lives in navkit.mapping.io only.
    assert not hasattr(navkit.mapping, "read_carmen")
    assert not hasattr(navkit.mapping, "CarmenLog")
    assert "read_carmen" not in navkit.mapping.__all__


def test_carmen_log_is_a_frozen_record(tmp_path: Path) -> None:
    path = tmp_path / "log.txt"
    path.write_text("FLASER 2 1.0 2.0 0.5 0 0 0 0 0 3.0 host 3.1\nODOM 1 2 0.5 0 0 0 9.0 h 9.1\n")
    log = read_carmen(path)
    with pytest.raises(dataclasses.FrozenInstanceError):
        log.scans = ()  # type: ignore[misc]
    with pytest.raises(ValueError, match="read-only"):
        log.times[0] = 0.0
    with pytest.raises(ValueError, match="read-only"):
        log.odometry[0, 0] = 0.0
    stamps = np.array([1.0])
    copy = CarmenLog(log.scans, log.laser_poses, log.robot_poses, stamps, np.zeros((0, 4)))
    stamps[0] = 5.0
    assert copy.times.tolist() == [1.0]
    with pytest.raises(ValueError, match="same length"):
        CarmenLog(log.scans, (), log.robot_poses, log.times, log.odometry)
    with pytest.raises(ValueError, match="odometry must have length 4"):
        CarmenLog(log.scans, log.laser_poses, log.robot_poses, log.times, np.zeros((1, 3)))


# ------------------------------------------------------------ issue 12: bad input
GOOD_RL1 = (
    "ROBOTLASER1 0 -0.5 1.0 0.25 8.0 0.01 0 5 1.5 1.5 1.5 1.5 1.5 0 "
    "1.0 2.0 0.1 0.9 2.0 0.1 0 0 0 0 0 123.5 host 123.6\n"
)


@pytest.mark.parametrize(
    ("text", "match"),
    [
        (
            "FLASER 3 1.0 2.0 5.0 0 0 0 0 0 0 nan host 1.0\n",
            r":1: malformed FLASER .*finite, got 'nan'",
        ),
        (
            "FLASER 3 1.0 inf 5.0 0 0 0 0 0 0 1.0 host 1.0\n",
            r":1: malformed FLASER .*finite, got 'inf'",
        ),
        ("FLASER 3 1.0 2.0 5.0 nan 0 0 0 0 0 1.0 host 1.0\n", r"finite, got 'nan'"),
        ("FLASER 3 1.0 2.0 5.0 1e999 0 0 0 0 0 1.0 host 1.0\n", r"finite, got '1e999'"),
        (
            "FLASER -2 1.0 2.0 0 0 0 0 0 0 1.0 host 1.0\n",
            r"beam count must be a non-negative integer, got '-2'",
        ),
        (
            "FLASER 1.5 1.0 2.0 0 0 0 0 0 0 1.0 host 1.0\n",
            r"beam count must be a non-negative integer",
        ),
        ("FLASER 0 0 0 0 0 0 0 1.0 host 1.0\n", r"beam count must be at least 1"),
        (
            "FLASER " + "1" * 27 + " 1.0 0 0 0 0 0 0 1.0 h 1.0\n",
            r"beam count 1{20}\.\.\. is out of range",
        ),
        ("FLASER 1000000000 1.0 0 0 0 0 0 0 1.0 h 1.0\n", r"fields where the counts give"),
        # A count one too small: the pose would be read from the ranges.
        ("FLASER 2 1.0 2.0 5.0 0 0 0 0 0 0 1.0 host 1.0\n", r"fields where the counts give 10"),
        ("ODOM 1 2 nan 0 0 0 1.0 h 1.0\n", r":1: malformed ODOM .*finite"),
        # The n_rem = -2, which shifted fields into the pose.
        (
            GOOD_RL1.replace(" 1.5 0 1.0", " 1.5 -2 1.0"),
            r"remission count must be a non-negative integer, got '-2'",
        ),
        (GOOD_RL1.replace(" 1.5 0 1.0", " 1.5 2 1.0"), r"are the beam and remission counts right"),
        # Degrees given as radians: start -90, field of view 180, increment 1.
        (
            GOOD_RL1.replace("-0.5 1.0 0.25", "-90 180 1"),
            r"field of view 180 rad exceeds a full turn .*degrees",
        ),
        (
            GOOD_RL1.replace("-0.5 1.0 0.25", "-90 3.0 0.25"),
            r"log.txt:1: angle_min \(-90 rad\) .*degrees",
        ),
        (GOOD_RL1.replace("123.5 host", "inf host"), r"finite, got 'inf'"),
        (
            GOOD_RL1.replace("0.25 8.0", "0.25 2e9"),
            r"log.txt:1: range_max must be > 0 and <= 1e9 m",
        ),
        # A maximum range of 0 was reported as "cannot determine a maximum range".
        (GOOD_RL1.replace("0.25 8.0", "0.25 0"), r"log.txt:1: range_max must be > 0"),
        # Python reads "1_0" as 10; CARMEN's strtod does not.
        ("FLASER 3 1_0 2.0 5.0 0 0 0 0 0 0 1.0 host 1.0\n", r":1: malformed FLASER .*numbers"),
        ("ODOM 1 2 0.5 0 0 0 1_000.0 h 1.0\n" + GOOD_RL1, r":1: malformed ODOM .*numbers"),
    ],
)
def test_malformed_lines_name_the_file_and_line(tmp_path: Path, text: str, match: str) -> None:
    path = tmp_path / "log.txt"
    path.write_text(text)
    with pytest.raises(ValueError, match=match) as info:
        read_carmen(path)
    assert str(path) in str(info.value)


def test_robotlaser1_range_below_range_min_names_the_line(tmp_path: Path) -> None:
    path = tmp_path / "log.txt"
    path.write_text("FLASER 3 1.0 2.0 20.0 0 0 0 0 0 0 1.0 host 1.0\n" + GOOD_RL1)
    assert [s.range_max for s in read_carmen(path, range_min=1.0).scans] == [20.0, 8.0]
    with pytest.raises(ValueError, match=r"log.txt:2: range_max \(8.0\) must be greater than"):
        read_carmen(path, range_min=10.0)  # the FLASER max is 20 m, the ROBOTLASER1's 8 m


def test_corrupt_gzip_is_a_value_error(tmp_path: Path) -> None:
    good = gzip.compress(("FLASER 3 1.0 2.0 5.0 0 0 0 0 0 0 1.0 host 1.0\n" * 200).encode())
    for name, data in [
        ("garbage.gz", b"\x1f\x8b\x08\x00garbage"),  # EOFError / BadGzipFile in the issue
        ("truncated.gz", good[: len(good) // 2]),
        ("bad-crc.gz", good[:-8] + b"\x00" * 8),
    ]:
        path = tmp_path / name
        path.write_bytes(data)
        with pytest.raises(ValueError, match=r"corrupt or truncated gzip file") as info:
            read_carmen(path)
        assert str(path) in str(info.value)


def test_reader_arguments(tmp_path: Path) -> None:
    path = tmp_path / "log.txt"
    path.write_text("FLASER 3 1.0 2.0 5.0 0 0 0 0 0 0 1.0 host 1.0\n")
    with pytest.raises(TypeError, match=r"path must be a str or an os\.PathLike"):
        read_carmen(3)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="is not a regular file"):
        read_carmen(tmp_path)
    with pytest.raises(ValueError, match="path must not be empty"):  # was "CARMEN log ."
        read_carmen("")
    with pytest.raises(ValueError, match=r"range_max must be > 0 and <= 1e9 m"):
        read_carmen(path, range_max=1e12)
    with pytest.raises(TypeError, match="range_max must be a real number"):
        read_carmen(path, range_max="5")  # type: ignore[arg-type]
    # Host name and logger timestamp are optional; a valid ROBOTLASER1 line reads.
    path.write_text("FLASER 3 1.0 2.0 5.0 0 0 0 0 0 0 1.0\n" + GOOD_RL1)
    log = read_carmen(path)
    assert len(log) == 2 and log.laser_poses[1] == Pose2D(1.0, 2.0, 0.1)


def test_carmen_log_from_lists_copies_and_checks() -> None:
    scan = read_scan()
    stamps = [1.0]
    odometry: list[list[float]] = []
    log = CarmenLog([scan], [(0.0, 1.0, 0.5)], [[0.0, 1.0, 0.5]], stamps, odometry)  # type: ignore[arg-type]
    assert log.laser_poses == (Pose2D(0.0, 1.0, 0.5),) and log.odometry.shape == (0, 4)
    mine = np.array([2.0])
    odo = np.zeros((1, 4))
    log = CarmenLog((scan,), (Pose2D(0, 0, 0),), (Pose2D(0, 0, 0),), mine, odo)
    assert mine.flags.writeable and odo.flags.writeable
    mine[0] = 5.0
    assert log.times.tolist() == [2.0]
    with pytest.raises(TypeError, match=r"scans\[0\] must be a LaserScan"):
        CarmenLog(([1.0],), (Pose2D(0, 0, 0),), (Pose2D(0, 0, 0),), [1.0], odo)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match=r"laser_poses\[0\]"):
        CarmenLog((scan,), ("pose",), (Pose2D(0, 0, 0),), [1.0], odo)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="times must contain only finite values"):
        CarmenLog((scan,), (Pose2D(0, 0, 0),), (Pose2D(0, 0, 0),), [math.nan], odo)
    with pytest.raises(ValueError, match="odometry must contain only finite values"):
        CarmenLog((scan,), (Pose2D(0, 0, 0),), (Pose2D(0, 0, 0),), [1.0], [[0, 0, math.inf, 1]])


def read_scan() -> navkit.mapping.LaserScan:
    return navkit.mapping.LaserScan(
        [1.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0
    )
