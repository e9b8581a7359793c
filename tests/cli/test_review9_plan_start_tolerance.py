"""``navkit plan --start-tolerance METRES``: MapPlanner.plan's start escape on the command line."""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Literal

import numpy as np
import pytest

from navkit.cli import main
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map
from navkit.planning import MapPlanner

RADIUS = 0.3


def room_grid() -> OccupancyGrid:
    """A 3 x 2 m map: a wall at x = 1.4 to 1.6 m up to y = 1 m, unknown space top right."""
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:10, 14:16] = True
    unknown = np.zeros_like(occupied)
    unknown[15:, 25:] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown)


@pytest.fixture
def room(tmp_path: Path) -> Path:
    write_map(room_grid(), tmp_path / "room.yaml")
    return tmp_path / "room.yaml"


def plan_argv(map_yaml: Path, start: str, goal: str, *extra: str) -> list[str]:
    return ["plan", str(map_yaml), "--start", start, "--goal", goal, "--radius", str(RADIUS),
            "--quiet", *extra]  # fmt: skip


def row(out: str, name: str) -> str | None:
    match = re.search(rf"^{re.escape(name)}\s+(.+?)\s*$", out, flags=re.MULTILINE)
    return None if match is None else match.group(1)


def point(text: str | None) -> tuple[float, float]:
    assert text is not None
    match = re.fullmatch(r"\((\S+), (\S+)\)", text)
    assert match, text
    return float(match.group(1)), float(match.group(2))


def error_line(capsys: pytest.CaptureFixture[str]) -> str:
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("navkit: error: "), lines
    return lines[0]


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
@pytest.mark.parametrize(
    ("start", "goal"),
    [
        ((1.25, 0.35), (0.25, 0.35)),  # within --radius of the wall
        ((2.25, 1.85), (0.55, 1.55)),  # within --radius of unknown space
    ],
    ids=["near_wall", "near_unknown"],
)
def test_a_start_in_the_inflation_escapes(
    room: Path, capsys: pytest.CaptureFixture[str], planner: Literal["astar", "field_dstar"],
    start: tuple[float, float], goal: tuple[float, float],
) -> None:  # fmt: skip
    argv = plan_argv(room, f"{start[0]},{start[1]}", f"{goal[0]},{goal[1]}", "--planner", planner)
    # Refused without the option (the start's cell is impassable) ...
    assert main(argv) == 1
    assert "--start-tolerance > 0" in error_line(capsys)
    # ... planned with it, as the library plans on the map the command read.
    assert main([*argv, "--start-tolerance", "0.5"]) == 0
    out = capsys.readouterr().out
    library = MapPlanner(read_map(room), robot_radius=RADIUS, planner=planner)
    expected = library.plan(start, goal, start_tolerance=0.5)
    assert float(row(out, "length (m)") or "nan") == pytest.approx(expected.length, rel=1e-3)
    assert int(row(out, "path points") or "-1") == len(expected.points)
    assert float(row(out, "start tolerance (m)") or "nan") == 0.5
    escaped = point(row(out, "escaped to (m)"))
    assert escaped == pytest.approx(tuple(expected.points[1]), abs=1e-9)
    # The escape cell: passable, its centre within the tolerance of the start.
    assert math.dist(escaped, start) <= 0.5 + 1e-9
    cell = tuple(int(v) for v in np.asarray(library.grid.world_to_cell(escaped)).reshape(2))
    assert math.isfinite(library.costs[cell])


def test_a_passable_start_is_not_moved(room: Path, capsys: pytest.CaptureFixture[str]) -> None:
    argv = plan_argv(room, "0.55,0.35", "0.55,1.55")
    assert main(argv) == 0
    plain = capsys.readouterr().out
    assert main([*argv, "--start-tolerance", "0.5"]) == 0
    tolerant = capsys.readouterr().out
    assert row(tolerant, "escaped to (m)") is None
    assert row(plain, "start tolerance (m)") is None  # the default adds no row
    for name in ("length (m)", "path points", "cells expanded"):
        assert row(tolerant, name) == row(plain, name)


@pytest.mark.parametrize(
    "value", ["-1", "-0.5", "-1e-3", "nan", "inf", "-inf", "1e10", "1e9.5", "0.5m", "", "1,2"]
)
def test_bad_values_print_usage_naming_the_option(
    room: Path, capsys: pytest.CaptureFixture[str], value: str
) -> None:
    assert main([*plan_argv(room, "1.25,0.35", "0.25,0.35"), "--start-tolerance", value]) == 2
    err = capsys.readouterr().err
    assert "usage: navkit plan" in err and "argument --start-tolerance" in err, err
    assert "Traceback" not in err


@pytest.mark.parametrize(("value", "code"), [("0", 1), ("0.0", 1), ("-0", 1), ("1e9", 0)])
def test_the_range_ends_are_accepted(
    room: Path, capsys: pytest.CaptureFixture[str], value: str, code: int
) -> None:
    # 0 is the default (refused start); 1e9 m is MapPlanner.plan's largest tolerance.
    assert main([*plan_argv(room, "1.25,0.35", "0.25,0.35"), f"--start-tolerance={value}"]) == code
    out, err = capsys.readouterr()
    if code == 0:
        assert row(out, "escaped to (m)") is not None
    else:
        assert "usage" not in err and "--start-tolerance > 0" in err


@pytest.mark.parametrize(
    ("start", "tolerance", "words"),
    [
        ("1.25,0.35", None, "within --radius (0.3 m) of an obstacle; pass --start-tolerance > 0 "
                            "to escape to the nearest passable cell"),
        ("1.25,0.35", "0.05", "no passable cell centre within --start-tolerance (0.05 m)"),
        ("2.25,1.85", "0.05", "no passable cell centre within --start-tolerance (0.05 m)"),
        ("1.45,0.35", "0.5", "is in an obstacle"),  # never escaped, whatever the tolerance
    ],
)  # fmt: skip
def test_refusals_name_the_command_options(
    room: Path, capsys: pytest.CaptureFixture[str], start: str, tolerance: str | None, words: str
) -> None:
    extra = () if tolerance is None else ("--start-tolerance", tolerance)
    assert main(plan_argv(room, start, "0.25,0.35", *extra)) == 1
    line = error_line(capsys)
    assert line.startswith("navkit: error: --start (")
    assert words in line, line
    for internal in ("start_tolerance", "robot_radius", "unknown_cost", "inflate_unknown"):
        assert internal not in line


def test_the_library_keeps_its_keyword_names() -> None:
    # Only the command speaks of --start-tolerance: library callers pass the keyword.
    planner = MapPlanner(room_grid(), robot_radius=RADIUS)
    with pytest.raises(ValueError, match=r"pass start_tolerance > 0 to escape") as caught:
        planner.plan((1.25, 0.35), (0.25, 0.35))
    assert "--" not in str(caught.value)


def test_no_path_after_an_escape_names_the_options(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # A wall across the whole map: the start escapes from its band, then finds no way over.
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:, 14:16] = True
    write_map(OccupancyGrid.from_occupancy(occupied, resolution=0.1), tmp_path / "split.yaml")
    argv = plan_argv(tmp_path / "split.yaml", "1.25,0.55", "2.55,0.55", "--start-tolerance", "0.5")
    assert main(argv) == 1
    line = error_line(capsys)
    assert "from --start (1.25, 0.55)" in line and "escaped to cell" in line, line
    assert "to --goal (2.55, 0.55)" in line and "start_tolerance" not in line, line
