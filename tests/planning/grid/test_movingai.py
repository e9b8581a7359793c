"""A* against the published optimal lengths of the MovingAI grid benchmarks.

Data: ``../shared/data/movingai-grid-benchmarks`` (N. Sturtevant, "Benchmarks for
Grid-Based Pathfinding", IEEE TCIAIG 4(2), 2012). Optimal lengths are 8-connected
octile lengths (diagonals sqrt(2)) without corner cutting, printed with 8
decimals, so costs must agree to 1e-6 relative. CI checks a fixed random sample
of every scenario file with A* and with jump point search (``method="jps"``),
path by path too; the slow-marked tests check a larger such sample, and every
scenario's cost.
"""

from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import numpy as np
import pytest
from grid_oracle import assert_valid_path

from navkit.planning import AStarPlanner, distance_field

FOLDER = "movingai-grid-benchmarks"
MAPS = [
    "dao/arena",
    "dao/arena2",
    "dao/den011d",
    "maze/maze512-1-0",
    "maze/maze512-32-9",
    "random/random512-10-0",
    "room/8room_000",
    "street/Berlin_0_256",
    "street/Boston_0_256",
    "street/Berlin_0_512",
    "street/Berlin_0_1024",
]
# Scenarios per map in the default (CI) run, the longest among them; the slow run
# checks SAMPLE_SLOW, also path by path (the check, in Python, costs about as much
# as the search).
SAMPLE = 100
SAMPLE_SLOW = 300
SAMPLES = [SAMPLE, pytest.param(SAMPLE_SLOW, marks=pytest.mark.slow)]
PASSABLE = frozenset(".GS")


class Scenario(NamedTuple):
    start: tuple[int, int]
    goal: tuple[int, int]
    optimal: float


def read_map(path: Path) -> np.ndarray:
    """MovingAI ``.map`` as a cost grid: 1 where passable, inf elsewhere."""
    lines = path.read_text(encoding="ascii").splitlines()
    header = {}
    for i, line in enumerate(lines):
        if line.strip() == "map":
            body = lines[i + 1 :]
            break
        key, value = line.split()
        header[key] = value
    height, width = int(header["height"]), int(header["width"])
    assert header["type"] == "octile"
    rows = [row for row in body if row]
    assert len(rows) == height and all(len(row) == width for row in rows)
    passable = np.array([[ch in PASSABLE for ch in row] for row in rows])
    return np.where(passable, 1.0, np.inf)


def read_scenarios(path: Path) -> list[Scenario]:
    """MovingAI ``.scen`` version 1: x is the column and y the row."""
    lines = path.read_text(encoding="ascii").splitlines()
    assert lines[0].strip() == "version 1"
    out = []
    for line in lines[1:]:
        if not line.strip():
            continue
        fields = line.split("\t")
        sx, sy, gx, gy = (int(v) for v in fields[4:8])
        out.append(Scenario((sy, sx), (gy, gx), float(fields[8])))
    return out


def load(shared_data: Path, name: str) -> tuple[np.ndarray, list[Scenario]]:
    base = shared_data / FOLDER / name
    return read_map(base.with_name(base.name + ".map")), read_scenarios(
        base.with_name(base.name + ".map.scen")
    )


def check(
    costs: np.ndarray,
    scenarios: list[Scenario],
    validate: bool,
    method: str = "astar",
    validate_every: int = 1,
) -> None:
    planner = AStarPlanner(costs, method=method)
    assert planner.method == method
    for i, sc in enumerate(scenarios):
        path = planner.plan(sc.start, sc.goal)
        assert path.cost == pytest.approx(sc.optimal, rel=1e-6, abs=1e-6), sc
        if validate and i % validate_every == 0:
            cost, _ = assert_valid_path(costs, path.cells, sc.start, sc.goal)
            assert cost == pytest.approx(path.cost, rel=1e-9)
            assert path.length == pytest.approx(path.cost, rel=1e-12)


def sample(scenarios: list[Scenario], size: int) -> list[Scenario]:
    """A fixed random sample of ``size`` problems that includes the longest one."""
    rng = np.random.default_rng(20121)
    # Always include the longest problem, the hardest one for the search.
    longest = max(range(len(scenarios)), key=lambda i: scenarios[i].optimal)
    size = min(size - 1, len(scenarios))
    picks = {longest, *rng.choice(len(scenarios), size=size, replace=False).tolist()}
    return [scenarios[i] for i in sorted(picks)]


@pytest.mark.parametrize("size", SAMPLES)
@pytest.mark.parametrize("name", MAPS)
def test_random_sample_matches_published_optimum(shared_data: Path, name: str, size: int) -> None:
    costs, scenarios = load(shared_data, name)
    check(costs, sample(scenarios, size), validate=True)


@pytest.mark.parametrize("size", SAMPLES)
@pytest.mark.parametrize("name", MAPS)
def test_jump_point_search_matches_published_optimum(
    shared_data: Path, name: str, size: int
) -> None:
    # JPS paths are filled in between jump points: check every 4th cell by cell
    # (the check, in Python, costs more than the search).
    costs, scenarios = load(shared_data, name)
    check(costs, sample(scenarios, size), validate=True, method="jps", validate_every=4)


def test_distance_field_matches_published_optimum(shared_data: Path) -> None:
    costs, scenarios = load(shared_data, "dao/arena2")
    goal = scenarios[-1].goal
    field = distance_field(costs, goal)
    same_goal = [sc for sc in scenarios if sc.goal == goal]
    assert same_goal
    for sc in same_goal:
        assert field[sc.start] == pytest.approx(sc.optimal, rel=1e-6)
    # The field is symmetric in start and goal.
    for sc in scenarios[:50]:
        assert distance_field(costs, sc.start)[sc.goal] == pytest.approx(sc.optimal, rel=1e-6)


@pytest.mark.slow
@pytest.mark.parametrize("method", ["astar", "jps"])
@pytest.mark.parametrize("name", MAPS)
def test_every_scenario_matches_published_optimum(
    shared_data: Path, name: str, method: str
) -> None:
    costs, scenarios = load(shared_data, name)
    check(costs, scenarios, validate=False, method=method)
