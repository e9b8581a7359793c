"""The demo scenario (issue 14, ``navkit demo``): plan, track and localise on a real map.

On the Willow Garage map and on the synthetic office used when the data is
absent, every leg of the tour is planned, driven on the fused estimate without
touching a wall, stays near its plan, and the estimate stays near the truth.
"""

from __future__ import annotations

import json
import pickle
from pathlib import Path

import numpy as np
import pytest

from navkit.errors import DataNotFoundError
from navkit.sim import ScenarioResult, Scene, Trial, TrialResult
from navkit.sim.scenarios import Demo, find_data, get_scenario


def run(demo: Demo, trials: int | None = None, *, seed: int = 0) -> ScenarioResult:
    """What ``Scenario.run(workers=1)`` does: every trial in order, then summarize."""
    results = [demo.run_trial(t) for t in demo.trials(trials, seed=seed)]
    return demo.summarize(results, seed=seed)


def without_wall_times(result: ScenarioResult) -> dict[str, float]:
    return {k: v for k, v in result.summary.items() if not k.endswith("_wall_time")}


@pytest.fixture(scope="module")
def willow(shared_data: Path) -> ScenarioResult:
    return run(Demo(data_dir=shared_data, map="willow"))


@pytest.fixture(scope="module")
def office(tmp_path_factory: pytest.TempPathFactory) -> ScenarioResult:
    # An empty data folder: "auto" falls back to the synthetic office.
    return run(Demo(data_dir=tmp_path_factory.mktemp("no-data")))


def check_tour(result: ScenarioResult) -> None:
    assert [r.trial.case_index for r in result.trials] == [0, 1, 2]
    for r in result.trials:
        v = r.values
        assert v["reached"] == 1.0 and v["collisions"] == 0.0, (r.trial.case, v)
        assert v["min_clearance"] > 0.1, (r.trial.case, v)
        assert v["cross_track_max"] < 0.15, (r.trial.case, v)  # 1.5 cells of 0.1 m
        assert v["estimate_error_max"] < 0.1, (r.trial.case, v)
        assert 0.0 <= v["plan_wall_time"] < 1.0
        # The robot drives about the planned length (corners cut, the goal radius).
        assert 0.85 * v["plan_length"] < v["distance"] < 1.05 * v["plan_length"], v
        assert r.trace is not None and r.trace.scans  # the LiDAR's scans are kept
    s = result.summary
    assert s["reached"] == 1.0 and s["collisions"] == 0.0 and s["legs"] == 3.0
    assert s["plan_length"] == pytest.approx(sum(r.values["plan_length"] for r in result.trials))


def test_registered_under_its_name() -> None:
    assert get_scenario("demo") is Demo
    assert Demo.default_trials == 1


def test_tour_of_the_willow_garage_map(willow: ScenarioResult) -> None:
    check_tour(willow)
    assert willow.summary["willow"] == 1.0
    assert 35.0 < willow.summary["plan_length"] < 50.0
    text = willow.table()
    assert "Willow Garage office map" in text and "willow-2010-02-18-0.10.yaml" in text
    assert "No paper to compare with" in text


def test_tour_of_the_synthetic_office_without_data(office: ScenarioResult) -> None:
    check_tour(office)
    assert office.summary["willow"] == 0.0
    assert "synthetic office" in office.table()


def test_willow_needs_its_data(tmp_path: Path) -> None:
    with pytest.raises(DataNotFoundError, match="willow"):
        Demo(data_dir=tmp_path, map="willow")
    assert Demo(map="office").map_path is None


def test_same_seed_same_result_other_seed_other_noise() -> None:
    demo = Demo(map="office", duration=5.0)
    a, b, c = run(demo, 2, seed=1), run(demo, 2, seed=1), run(demo, 2, seed=2)
    assert without_wall_times(a) == without_wall_times(b)
    for x, y in zip(a.trials, b.trials, strict=True):
        assert x.trial == y.trial
        assert np.array_equal(x.trace.poses, y.trace.poses)  # type: ignore[union-attr]
    assert [r.values["estimate_error"] for r in a.trials] != [
        r.values["estimate_error"] for r in c.trials
    ]


def test_result_is_json_ready_and_has_a_scene(office: ScenarioResult) -> None:
    data = json.loads(json.dumps(office.to_dict()))
    assert data["scenario"] == "demo" and len(data["trials"]) == 3
    assert data["tables"][0]["columns"][0] == "leg"
    scene = office.scene
    assert isinstance(scene, Scene)
    assert scene.grid is not None and len(scene.paths) == 3 and len(scene.traces) == 3
    start = scene.paths[0][1][0]
    assert np.allclose(start, scene.points[0][1][0])  # the first plan starts at waypoint 1


def test_pickles_for_worker_processes() -> None:
    demo = Demo(map="office", duration=3.0)
    copy = pickle.loads(pickle.dumps(demo))
    assert repr(copy) == repr(demo) and copy.map_path is None


@pytest.mark.parametrize(
    ("kwargs", "error"),
    [
        ({"map": "mars"}, ValueError),
        ({"map": 1}, TypeError),
        ({"duration": 0.0}, ValueError),
        ({"duration": 1e5}, ValueError),
        ({"duration": "1"}, TypeError),
        ({"data_dir": 3}, TypeError),
    ],
)
def test_bad_options(kwargs: dict[str, object], error: type[Exception]) -> None:
    with pytest.raises(error):
        Demo(**kwargs)  # type: ignore[arg-type]


def test_summarize_names_missing_values() -> None:
    # A result without the demo's values used to fail with a bare KeyError.
    result = TrialResult(Trial("leg 1", 0, 0, 1), {"plan_length": 20.0})
    with pytest.raises(ValueError, match=r"results\[0\]\.values lack plan_wall_time"):
        Demo(map="office").summarize([result], seed=0)


def test_an_empty_data_dir_is_refused(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # data_dir="" used to mean the working directory: run from a folder holding the
    # maps, it found them there (as a relative path) instead of refusing the option.
    (tmp_path / "ros-map-server-maps").mkdir()
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match="data_dir must not be empty"):
        find_data("ros-map-server-maps", data_dir="")
    with pytest.raises(ValueError, match="data_dir must not be empty"):
        Demo(data_dir="", map="willow")
