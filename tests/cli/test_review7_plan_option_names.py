"""``navkit plan``: a blocked or off-map start or goal is reported by the options given."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.cli import main
from navkit.mapping import OccupancyGrid


@pytest.fixture
def room(tmp_path: Path) -> Path:
    """A 3 x 2 m map: a wall at x = 1.4 to 1.6 m, unknown space in its top-right corner."""
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:10, 14:16] = True
    unknown = np.zeros_like(occupied)
    unknown[15:, 25:] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown)
    grid.save(tmp_path / "room.yaml")
    return tmp_path / "room.yaml"


def error_line(capsys: pytest.CaptureFixture[str]) -> str:
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("navkit: error: "), lines
    return lines[0]


@pytest.mark.parametrize(
    ("start", "goal", "radius", "option", "words"),
    [
        ("1.25,0.35", "0.25,0.35", "0.3", "--start", "within --radius (0.3 m) of an obstacle"),
        ("0.55,0.35", "1.95,0.35", "0.5", "--goal", "within --radius (0.5 m) of an obstacle"),
        ("0.55,1.55", "2.85,1.85", "0", "--goal", "is in unknown space"),
        ("0.55,1.55", "2.25,1.85", "0.3", "--goal", "within --radius (0.3 m) of unknown space"),
        ("0.55,1.55", "9,9", "0", "--goal", "is outside the map"),
        ("-9,1.55", "0.55,1.55", "0", "--start", "is outside the map"),
    ],
)
def test_errors_name_the_command_options(
    room: Path, capsys: pytest.CaptureFixture[str], start: str, goal: str, radius: str,
    option: str, words: str,
) -> None:  # fmt: skip
    # They named the planner's arguments: "start ... is within robot_radius (0.3 m) of an
    # obstacle", "(unknown_cost is inf)", "(inflate_unknown is True)", none of which the
    # command takes.
    argv = ["plan", str(room), "--start", start, "--goal", goal, "--radius", radius, "--quiet"]
    assert main(argv) == 1
    line = error_line(capsys)
    assert line.startswith(f"navkit: error: {option} (")
    assert words in line
    for internal in ("robot_radius", "unknown_cost", "inflate_unknown"):
        assert internal not in line


def test_no_path_is_reported_by_the_options_given(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # A wall across the whole map: start and goal lie on either side of it.
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:, 14:16] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    grid.save(tmp_path / "split.yaml")
    code = main(["plan", str(tmp_path / "split.yaml"), "--start", "0.55,0.55",
                 "--goal", "2.55,0.55", "--radius", "0", "--quiet"])
    assert code == 1
    line = error_line(capsys)
    assert "from --start (0.55, 0.55)" in line and "to --goal (2.55, 0.55)" in line, line
