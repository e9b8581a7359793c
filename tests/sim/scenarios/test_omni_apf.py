"""The omni-apf scenario (issue 14): noise-free error under 40 mm, every noisy trial reaches."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from navkit.sim import Scenario, ScenarioResult, Scene, Table, Trial, TrialResult
from navkit.sim.scenarios import OmniApf, get_scenario


def run(scenario: Scenario, trials: int | None = None, *, seed: int = 0) -> ScenarioResult:
    """What ``Scenario.run(workers=1)`` does: every trial in order, then summarize."""
    results = [scenario.run_trial(t) for t in scenario.trials(trials, seed=seed)]
    return scenario.summarize(results, seed=seed)


@pytest.fixture(scope="module")
def noise_free() -> ScenarioResult:
    # The paper's four targets, without and with the obstacle: 8 trials, one per case.
    return run(OmniApf(noise=False))


@pytest.fixture(scope="module")
def noisy() -> ScenarioResult:
    # Two noisy trials per case (the paper runs five) with the paper's latencies.
    return run(OmniApf(), 2, seed=3)


def test_registered_under_its_name() -> None:
    assert get_scenario("omni-apf") is OmniApf
    assert OmniApf.default_trials == 5


def test_noise_free_final_error_under_40_mm(noise_free: ScenarioResult) -> None:
    assert len(noise_free.trials) == 8  # 4 targets x {no obstacle, obstacle}, once each
    for r in noise_free.trials:
        v = r.values
        assert v["reached"] == 1.0 and v["collisions"] == 0.0, r.trial.case
        assert v["error"] < 0.040, (r.trial.case, v["error"])
        assert math.isclose(
            v["error"], math.hypot(v["final_x"] - v["target_x"], v["final_y"] - v["target_y"])
        )
    assert noise_free.summary["error_max"] < 0.040
    assert noise_free.summary["reached_rate"] == 1.0


def test_every_noisy_trial_reaches(noisy: ScenarioResult) -> None:
    assert len(noisy.trials) == 16
    for r in noisy.trials:
        v = r.values
        assert v["reached"] == 1.0 and v["collisions"] == 0.0, r.trial.case
        assert v["error"] < 0.040, (r.trial.case, v["error"])  # the paper's bound holds too
        assert math.isfinite(v["time"]) and v["time"] > 0.0
    assert noisy.summary["reached_rate"] == 1.0
    assert noisy.summary["collisions"] == 0.0


def test_noise_makes_the_odometry_drift(noise_free: ScenarioResult, noisy: ScenarioResult) -> None:
    # Wheel slip: the odometry's position differs from the truth more with noise.
    assert noisy.summary["drift_max"] > noise_free.summary["drift_max"]
    finals = {r.values["final_x"] for r in noisy.trials if r.trial.case_index == 2}
    assert len(finals) == 2  # the two trials' seeds differ, so do the runs


def test_the_obstacle_makes_the_robot_go_around(noise_free: ScenarioResult) -> None:
    for r in noise_free.trials:
        assert r.trace is not None
        tx, ty = r.values["target_x"], r.values["target_y"]
        pts = r.trace.poses[:, :2]
        # Distance from the straight route (the origin to the target).
        off = np.abs(pts[:, 0] * ty - pts[:, 1] * tx) / math.hypot(tx, ty)
        if "no obstacle" in r.trial.case:
            assert off.max() < 0.02
        else:
            assert off.max() > 0.2  # left the line to pass the box
            assert r.trace.metrics.min_clearance > 0.05


def test_same_seed_same_summary() -> None:
    scenario = OmniApf(obstacles=True, targets=[(0.0, 2.0)], duration=20.0)
    a = run(scenario, 2, seed=7)
    b = run(scenario, 2, seed=7)
    assert dict(a.summary) == dict(b.summary)
    assert [r.values for r in a.trials] == [r.values for r in b.trials]


def test_result_is_json_ready_with_the_paper_beside(noise_free: ScenarioResult) -> None:
    data = json.loads(json.dumps(noise_free.to_dict()))
    assert data["scenario"] == "omni-apf"
    assert len(data["trials"]) == 8
    text = noise_free.table()
    assert "< 40" in text and "11.2-12.9" in text
    assert all(isinstance(t, Table) for t in noise_free.tables)
    per_target = noise_free.tables[1]
    assert len(per_target.rows) == 8


def test_scene_shows_the_room_obstacles_and_traces(noise_free: ScenarioResult) -> None:
    scene = noise_free.scene
    assert isinstance(scene, Scene)
    assert scene.world is not None and scene.world.segments.shape[0] >= 4 + 16
    assert len(scene.traces) == 8
    labels = dict(scene.points)
    np.testing.assert_array_equal(labels["targets"], [[0, 3], [0, -3], [3, 0], [-3, 0]])


def test_cases_and_options() -> None:
    assert len(OmniApf(noise=False).cases(5)) == 8
    assert all(n == 1 for _, n in OmniApf(noise=False).cases(5))
    assert all(n == 5 for _, n in OmniApf().cases(5))
    assert [c for c, _ in OmniApf(obstacles=False, targets=[(1.0, 0.0)]).cases(1)] == [
        "target (1, 0) m, no obstacle"
    ]
    with pytest.raises(ValueError, match="targets"):
        OmniApf(targets=[(0.1, 0.0)])
    with pytest.raises(ValueError, match="targets"):
        OmniApf(targets=np.empty((0, 2)))
    with pytest.raises(ValueError, match="targets"):
        OmniApf(targets=[(float("inf"), 0.0)])
    assert OmniApf(targets=np.array([[0.0, 2.0]])).targets == ((0.0, 2.0),)
    with pytest.raises(TypeError, match="targets"):
        OmniApf(targets="0,3")
    with pytest.raises(ValueError, match="duration"):
        OmniApf(duration=-1.0)
    with pytest.raises(TypeError, match="noise"):
        OmniApf(noise="yes")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="trial"):
        OmniApf().run_trial("trial")  # type: ignore[arg-type]


def test_summarize_names_missing_values() -> None:
    # A result without the scenario's values used to fail with a bare KeyError.
    result = TrialResult(Trial("case", 0, 0, 1), {"error": 0.01})
    with pytest.raises(ValueError, match=r"results\[0\]\.values lack target_x"):
        OmniApf().summarize([result], seed=0)
