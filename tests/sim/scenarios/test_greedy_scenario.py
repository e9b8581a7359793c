"""The greedy scenario (issue 14): the Burger reaches its goals without collision."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from navkit.errors import DataNotFoundError
from navkit.mapping import LaserScan
from navkit.sim import Scenario, ScenarioResult, Scene, Trial, TrialResult
from navkit.sim.scenarios import Greedy, get_scenario
from navkit.sim.scenarios._greedy import MAP
from navkit.sim.scenarios._greedy_setup import GreedyController


def run(scenario: Scenario, trials: int | None = None, *, seed: int = 0) -> ScenarioResult:
    """What ``Scenario.run(workers=1)`` does: every trial in order, then summarize."""
    results = [scenario.run_trial(t) for t in scenario.trials(trials, seed=seed)]
    return scenario.summarize(results, seed=seed)


@pytest.fixture(scope="module")
def noise_free(shared_data: Path) -> ScenarioResult:
    return run(Greedy(noise=False, data_dir=str(shared_data)))


@pytest.fixture(scope="module")
def noisy(shared_data: Path) -> ScenarioResult:
    return run(Greedy(data_dir=str(shared_data)), 2, seed=5)


def test_registered_under_its_name() -> None:
    assert get_scenario("greedy") is Greedy


def test_reaches_every_goal_without_collision(noise_free: ScenarioResult) -> None:
    assert len(noise_free.trials) == 4
    for r in noise_free.trials:
        v = r.values
        assert v["reached"] == 1.0, r.trial.case
        assert v["collisions"] == 0.0 and v["min_clearance"] > 0.0, r.trial.case
        assert v["final_error"] <= 0.1
    assert noise_free.summary["success_rate"] == 1.0
    assert noise_free.summary["collisions"] == 0.0


def test_noisy_trials_reach_too(noisy: ScenarioResult) -> None:
    assert len(noisy.trials) == 8
    assert noisy.summary["success_rate"] == 1.0
    assert noisy.summary["collisions"] == 0.0
    lengths = {r.values["path_length"] for r in noisy.trials if r.trial.case_index == 0}
    assert len(lengths) == 2  # different noise seeds, different runs


def test_path_length_against_astar(noise_free: ScenarioResult) -> None:
    for r in noise_free.trials:
        v = r.values
        assert v["astar_length"] > 4.0  # the pairs are 4.1-4.5 m apart in a straight line
        assert v["length_ratio"] == pytest.approx(v["path_length"] / v["astar_length"])
        # A local planner drives farther than the global plan, but not wildly so.
        assert 0.95 < v["length_ratio"] < 1.6


def test_same_seed_same_summary(shared_data: Path) -> None:
    scenario = Greedy(data_dir=str(shared_data), pairs=[((-2.0, -0.5), (0.0, -0.55))])
    a = run(scenario, 1, seed=11)
    b = run(scenario, 1, seed=11)
    assert dict(a.summary) == dict(b.summary)
    assert a.summary["success_rate"] == 1.0


def test_the_plain_grid_grazes_the_pillars(shared_data: Path) -> None:
    # The paper's grid without growing the returns: lines of sight touch the pillars.
    scenario = Greedy(noise=False, inflation=0.0, data_dir=str(shared_data),
                      pairs=[((-1.5, -1.5), (1.5, 1.5))])  # fmt: skip
    result = run(scenario)
    assert result.summary["collisions"] >= 1.0
    assert result.summary["success_rate"] == 0.0


def test_result_is_json_ready_and_the_scene_has_the_map(noise_free: ScenarioResult) -> None:
    data = json.loads(json.dumps(noise_free.to_dict()))
    assert data["scenario"] == "greedy" and len(data["trials"]) == 4
    text = noise_free.table()
    assert "A* path (m)" in text and "paper" in text
    scene = noise_free.scene
    assert isinstance(scene, Scene)
    assert scene.grid is not None and scene.grid.resolution == pytest.approx(0.05)
    assert len(scene.paths) == 4 and len(scene.traces) == 4
    starts = dict(scene.points)["starts"]
    np.testing.assert_array_equal(starts[0], [-2.0, -0.5])


def test_missing_data_raises(tmp_path: Path) -> None:
    scenario = Greedy(data_dir=str(tmp_path))
    with pytest.raises(DataNotFoundError, match="turtlebot3_world"):
        scenario.run_trial(scenario.trials(1)[0])


def test_options() -> None:
    assert [n for _, n in Greedy(noise=False).cases(7)] == [1, 1, 1, 1]
    assert [n for _, n in Greedy().cases(7)] == [7, 7, 7, 7]
    with pytest.raises(ValueError, match="pairs"):
        Greedy(pairs=[((0.0, 0.0), (0.0, 0.05))])
    with pytest.raises(ValueError, match="pairs"):
        Greedy(pairs=[(0.0, 1.0)])  # type: ignore[list-item]
    with pytest.raises(ValueError, match="pairs"):
        Greedy(pairs=[((0.0, float("nan")), (1.0, 1.0))])
    free = np.array([[[-2.0, -0.5], [-1.0, -0.5]]])  # (0, 0) is a pillar: refused when built
    assert Greedy(pairs=free).pairs == (((-2.0, -0.5), (-1.0, -0.5)),)
    with pytest.raises(ValueError, match="inflation"):
        Greedy(inflation=2.0)
    with pytest.raises(TypeError, match="data_dir"):
        Greedy(data_dir=3)  # type: ignore[arg-type]


def _ring(radius: float) -> LaserScan:
    """A 1 m scan with a return at ``radius`` in every direction."""
    return LaserScan(np.full(360, radius), angle_min=-math.pi, angle_increment=math.tau / 360,
                     range_min=0.12, range_max=1.0)  # fmt: skip


@pytest.mark.parametrize(
    ("radius", "inflation", "waypoint", "fallbacks"),
    [
        (0.3, 0.25, True, 1),  # the grown grid is shut, the plain one is not: a fallback
        (0.15, 0.25, False, 0),  # both shut: no step was planned on the plain grid
        (0.15, 0.0, False, 0),  # no grown grid, so never a fallback
        (0.9, 0.25, True, 0),
    ],
)
def test_fallbacks_count_steps_planned_on_the_plain_grid(
    radius: float, inflation: float, waypoint: bool, fallbacks: int
) -> None:
    """``fallbacks`` used to count the grids that failed (2 for a step failing on both)."""
    controller = GreedyController((3.0, 0.0), inflation=inflation)
    out = controller._plan(_ring(radius), (3.0, 0.0), 0.0, 0.0, 1.0, 0.0)
    assert (out is not None) == waypoint
    assert controller.steps == 1 and controller.fallbacks == fallbacks


def test_summarize_names_missing_values(tmp_path: Path) -> None:
    result = TrialResult(Trial("case", 0, 0, 1), {"reached": 1.0})
    with pytest.raises(ValueError, match=r"results\[0\]\.values lack collisions"):
        Greedy(data_dir=str(tmp_path)).summarize([result], seed=0)


def test_the_map_is_found_once_when_built(
    shared_data: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # As Demo and DiffAStar: a sweep's workers, whose $NAVKIT_DATA and working
    # directory may differ, must run on the map the scenario was built with.
    import shutil

    copy = tmp_path / "data"
    folder = (copy / MAP).parent
    shutil.copytree((shared_data / MAP).parent, folder)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("NAVKIT_DATA", str(copy))
    scenario = Greedy(noise=False)
    monkeypatch.setenv("NAVKIT_DATA", str(tmp_path / "elsewhere"))
    found = Path(scenario._map_path())
    assert found.is_absolute() and found.samefile(copy / MAP)
