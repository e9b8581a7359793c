"""Review 9: read_carmen's documented scan geometry and line checks (found by mutation testing).

FLASER lines carry no geometry: read_carmen's docstring gives CARMEN's guesses
(first beam at -90°, 1° for 180/181 beams, 0.5° for 360/361, 0.25° for 400/401,
else 180° over n - 1 gaps); the tests had only tried the last rule. Also: which
triple of a FLASER line is the laser pose, ROBOTLASER1 lines without
remissions, and fields of view beyond a full turn.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from navkit.mapping.io import read_carmen


def _flaser(n: int, pose: str = "0 0 0", odom: str = "0 0 0") -> str:
    ranges = " ".join(["1.5"] * n)
    return f"FLASER {n} {ranges} {pose} {odom} 10.0 host 10.1\n"


@pytest.mark.parametrize(
    ("n", "degrees"),
    [
        (180, 1.0),
        (181, 1.0),
        (360, 0.5),
        (361, 0.5),
        (400, 0.25),
        (401, 0.25),
        (91, 2.0),  # otherwise 180° over n - 1 gaps
        (7, 30.0),
    ],
)
def test_flaser_geometry_is_carmens_guess(tmp_path: Path, n: int, degrees: float) -> None:
    path = tmp_path / "log.txt"
    path.write_text(_flaser(n))
    scan = read_carmen(path, range_max=5.0).scans[0]
    assert scan.angle_min == pytest.approx(-math.pi / 2, abs=1e-15)
    assert scan.angle_increment == pytest.approx(math.radians(degrees), rel=1e-14)


def test_flaser_laser_pose_comes_before_the_odometry_pose(tmp_path: Path) -> None:
    # "FLASER n r_1 .. r_n x y theta odom_x odom_y odom_theta timestamp": the
    # first triple is the laser's world pose, the second the robot's odometry.
    path = tmp_path / "log.txt"
    path.write_text(_flaser(3, pose="1.5 -2.0 0.25", odom="7.0 8.0 -1.0"))
    log = read_carmen(path, range_max=5.0)
    assert log.laser_poses[0].as_array().tolist() == [1.5, -2.0, 0.25]
    assert log.robot_poses[0].as_array().tolist() == [7.0, 8.0, -1.0]


def _robotlaser1(fov: float, remissions: list[float]) -> str:
    ranges = [1.0, 2.0, 3.0]
    fields = [0, -0.5, fov, 0.5, 8.0, 0.01, 0, len(ranges), *ranges]
    fields += [len(remissions), *remissions]
    fields += [1.0, 2.0, 0.1, 0.9, 1.9, 0.1, 0, 0, 0.5, 0.5, 0.0, 20.0]
    return "ROBOTLASER1 " + " ".join(str(f) for f in fields) + " host 20.1\n"


def test_robotlaser1_without_one_remission_per_beam_has_no_intensities(tmp_path: Path) -> None:
    # Remissions become intensities only when there is one per beam; a line
    # with none (remission_mode 0, the common case) or with another count (its
    # fields still match its counts: a well-formed line) reads as a scan without.
    path = tmp_path / "log.txt"
    path.write_text(
        _robotlaser1(1.0, []) + _robotlaser1(1.0, [0.3, 0.2]) + _robotlaser1(1.0, [0.3, 0.2, 0.1])
    )
    none, other, per_beam = read_carmen(path).scans
    for scan in (none, other):
        assert scan.intensities is None
        assert scan.ranges.tolist() == [1.0, 2.0, 3.0]
    assert per_beam.intensities is not None
    assert per_beam.intensities.tolist() == [0.3, 0.2, 0.1]


def test_a_field_of_view_beyond_a_full_turn_is_refused(tmp_path: Path) -> None:
    # "angles in degrees (a field of view ... spanning more than 2π)" raise.
    path = tmp_path / "log.txt"
    path.write_text(_robotlaser1(2 * math.pi + 1e-3, []))
    with pytest.raises(ValueError, match=r"log\.txt:1:.*field of view"):
        read_carmen(path)
    path.write_text(_robotlaser1(2 * math.pi, []))
    assert len(read_carmen(path)) == 1


def test_an_out_of_range_flaser_maximum_names_its_first_line(tmp_path: Path) -> None:
    # Without range_max the largest FLASER reading is the maximum range; beyond
    # 1e9 m it is refused, naming the line holding it (the first of equals).
    path = tmp_path / "log.txt"
    big = "FLASER 2 1.0 2e9 0 0 0 0 0 0 {t} host {t}\n"
    path.write_text(_flaser(2) + big.format(t=11.0) + big.format(t=12.0))
    with pytest.raises(ValueError, match=r"log\.txt:2: FLASER reading 2000000000\.0 m"):
        read_carmen(path)
