"""``navkit plan MAP.yaml --start X,Y --goal X,Y`` on real and broken maps (issue 14)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from navkit.cli import main
from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner

TURTLEBOT3 = Path("ros-map-server-maps") / "turtlebot3_world" / "map.yaml"
WILLOW = Path("ros-map-server-maps") / "willow_garage_2010" / "willow-2010-02-18-0.10.yaml"


def figure(out: str, name: str) -> float:
    match = re.search(rf"^{re.escape(name)}\s+(\S+)$", out, flags=re.MULTILINE)
    assert match, out
    return float(match.group(1))


def one_error_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("navkit: error: "), err
    return lines[0]


@pytest.mark.parametrize(
    ("relative", "start", "goal", "radius"),
    [
        (TURTLEBOT3, (-1.5, -0.5), (1.5, 0.5), 0.105),
        (WILLOW, (23.65, 28.15), (18.05, 23.75), 0.3),
    ],
    ids=["turtlebot3_world", "willow_garage"],
)
@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
def test_plan_on_real_maps(
    shared_data: Path,
    capsys: pytest.CaptureFixture[str],
    relative: Path,
    start: tuple[float, float],
    goal: tuple[float, float],
    radius: float,
    planner: str,
) -> None:
    path = shared_data / relative
    points = ["--start", f"{start[0]},{start[1]}", "--goal", f"{goal[0]},{goal[1]}"]
    argv = ["plan", str(path), *points, "--planner", planner, "--radius", str(radius)]
    assert main(argv) == 0
    out = capsys.readouterr().out
    expected = MapPlanner(OccupancyGrid.load(path), robot_radius=radius, planner=planner).plan(
        start, goal
    )
    assert figure(out, "length (m)") == pytest.approx(expected.length, rel=1e-3)
    # Field D* expands grid corners: its row says nodes.
    label = "cells expanded" if planner == "astar" else "nodes expanded"
    assert figure(out, label) == expected.expanded
    assert 0.0 < figure(out, "plan time (ms)") < 10_000.0
    assert planner in out and path.name in out


def test_plan_plot_writes_a_png(
    shared_data: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    picture = tmp_path / "plan.png"
    argv = ["plan", str(shared_data / TURTLEBOT3), "--start", "-1.5,-0.5", "--goal", "1.5,0.5",
            "--radius", "0.105", "--plot", str(picture), "--quiet"]  # fmt: skip
    assert main(argv) == 0
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f"wrote {picture}" in capsys.readouterr().out


def test_missing_map_is_one_line_and_exit_1(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["plan", "missing.yaml", "--start", "0,0", "--goal", "1,1"]) == 1
    assert "missing.yaml" in one_error_line(capsys.readouterr().err)


@pytest.mark.parametrize(
    "text",
    ["image: nothing.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n", "{{{ not yaml", "[1, 2]\n"],
)
def test_malformed_map_is_one_line_and_exit_1(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], text: str
) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text(text)
    assert main(["plan", str(bad), "--start", "0,0", "--goal", "1,1"]) == 1
    one_error_line(capsys.readouterr().err)


@pytest.fixture
def walled(tmp_path: Path) -> Path:
    """A 3 x 2 m map cut in two by a wall."""
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:, 14:16] = True
    OccupancyGrid.from_occupancy(occupied, resolution=0.1).save(tmp_path / "walled.yaml")
    return tmp_path / "walled.yaml"


@pytest.mark.parametrize(
    ("start", "goal", "words"),
    [
        ("0.55,0.55", "2.55,0.55", "path"),  # across the wall: NoPathError
        ("1.45,0.55", "0.55,0.55", "start"),  # in the wall
        ("9,9", "0.55,0.55", "start"),  # off the map
    ],
)
def test_no_path_and_bad_points_are_one_line(
    walled: Path, capsys: pytest.CaptureFixture[str], start: str, goal: str, words: str
) -> None:
    assert main(["plan", str(walled), "--start", start, "--goal", goal, "--quiet"]) == 1
    assert words in one_error_line(capsys.readouterr().err).lower()


def test_plot_over_the_maps_image_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # A map whose image is a PNG: `--plot` naming that image replaced the map
    # with the picture of the plan.
    image_module = pytest.importorskip("PIL.Image")
    grid = OccupancyGrid.from_occupancy(np.zeros((20, 40), dtype=bool), resolution=0.1)
    yaml_path = tmp_path / "map.yaml"
    pgm = grid.save(yaml_path)
    image = tmp_path / "map.png"
    image_module.open(pgm).save(image)
    yaml_path.write_text(yaml_path.read_text().replace(pgm.name, image.name))
    before = image.read_bytes()
    argv = ["plan", str(yaml_path), "--start", "0.5,0.5", "--goal", "3.5,1.5",
            "--plot", str(image), "--quiet"]  # fmt: skip
    assert main(argv) == 1
    line = one_error_line(capsys.readouterr().err)
    assert "--plot" in line and "map's image" in line
    assert image.read_bytes() == before
    # Another file is still written.
    assert main([*argv[:-2], str(tmp_path / "plan.png"), "--quiet"]) == 0
    assert OccupancyGrid.load(yaml_path).shape == grid.shape
