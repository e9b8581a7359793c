"""MapPlanner's ``NoPathError`` says how far the search got, as ``astar``'s does.

``astar`` said "no path from start_cell (0, 0) to goal_cell (0, 4) (expanded 10
cells)"; ``MapPlanner.plan``, ``plan_path`` and ``navkit plan`` said only "no
collision-free path from start ... to goal ...": the count (a handful when the
start itself is boxed in, the whole reachable map when the goal is walled off)
was on ``exc.expanded`` but not in the message a user reads.
"""

from __future__ import annotations

import re
from functools import partial
from pathlib import Path

import numpy as np
import pytest

from navkit._shared.counts import counted
from navkit.cli import main
from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner, astar, plan_path


def _walled() -> OccupancyGrid:
    """A 2 x 2 m map, a wall across it at x = 1.0 to 1.1 m."""
    occupied = np.zeros((20, 20), dtype=bool)
    occupied[:, 10] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1)


@pytest.mark.parametrize(
    ("planner", "unit"),
    [("astar", "cell"), ("field_dstar", "node"), (partial(astar, method="jps"), "jump point")],
)
def test_no_path_message_gives_the_expansions(planner: object, unit: str) -> None:
    with pytest.raises(NoPathError) as info:
        plan_path(_walled(), (0.25, 0.25), (1.75, 0.25), planner=planner)  # type: ignore[arg-type]
    message = str(info.value)
    assert info.value.expanded > 0
    assert re.search(r"\(cell \(2, 17\)\) \(expanded (\d+) ([\w ]+)\)$", message), message
    assert message.endswith(f" (expanded {counted(info.value.expanded, unit)})"), message


def test_the_count_is_the_cell_planners_own() -> None:
    planner = MapPlanner(_walled())
    with pytest.raises(NoPathError) as direct:
        astar(planner.costs, (2, 2), (2, 17))
    with pytest.raises(NoPathError) as mapped:
        planner.plan((0.25, 0.25), (1.75, 0.25))
    # The start's side of the wall: 20 rows x 10 columns, every cell expanded.
    assert direct.value.expanded == mapped.value.expanded == 200
    assert f"(expanded {direct.value.expanded} cells)" in str(direct.value)
    assert f"(expanded {mapped.value.expanded} cells)" in str(mapped.value)


def test_the_count_comes_before_the_hint() -> None:
    with pytest.raises(NoPathError) as info:
        plan_path(_walled(), (0.25, 0.25), (1.75, 0.25), robot_radius=0.1)
    message = str(info.value)
    assert re.search(
        r"\(expanded \d+ cells\): obstacles grown by robot_radius=0\.1 m may close every way",
        message,
    ), message


def test_navkit_plan_prints_the_count(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    _walled().save(tmp_path / "walled.yaml")
    code = main(["plan", str(tmp_path / "walled.yaml"), "--start", "0.25,0.25",
                 "--goal", "1.75,0.25", "--quiet"])  # fmt: skip
    assert code == 1
    line = capsys.readouterr().err.strip()
    assert line.startswith("navkit: error: no collision-free path from --start"), line
    assert re.search(r"to --goal \(1\.75, 0\.25\) \(cell \(2, 17\)\) \(expanded 200 cells\)$",
                     line), line  # fmt: skip


@pytest.mark.parametrize(("planner", "label"), [("astar", "cells"), ("field_dstar", "nodes")])
def test_navkit_plan_names_what_its_planner_expands(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], planner: str, label: str
) -> None:
    # Field D* expands grid corners: its count was printed as "cells expanded".
    OccupancyGrid.from_occupancy(np.zeros((20, 20), dtype=bool), resolution=0.1).save(
        tmp_path / "open.yaml"
    )
    assert main(["plan", str(tmp_path / "open.yaml"), "--start", "0.25,0.25",
                 "--goal", "1.75,1.5", "--planner", planner, "--quiet"]) == 0  # fmt: skip
    out = capsys.readouterr().out
    rows = re.findall(r"^(cells|nodes) expanded +(\d+)$", out, flags=re.MULTILINE)
    want = MapPlanner(OccupancyGrid.load(tmp_path / "open.yaml"), planner=planner).plan(
        (0.25, 0.25), (1.75, 1.5)
    )
    assert rows == [(label, str(want.expanded))], out
