"""The experiment framework: trial seeds, records, tables, the registry and data lookup."""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.errors import DataNotFoundError
from navkit.sim import (
    Scenario,
    ScenarioResult,
    Scene,
    Table,
    Trial,
    TrialResult,
    trial_seed,
)
from navkit.sim.scenarios import SCENARIOS, find_data, get_scenario


class Coin(Scenario):
    """A two-case scenario whose trials draw one number from their seed."""

    name = "coin"
    title = "draws"
    paper = "none"
    default_trials = 3

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        return (("heads", trials), ("once", 1))

    def run_trial(self, trial: Trial) -> TrialResult:
        return TrialResult(trial, {"draw": float(np.random.default_rng(trial.seed).random())})

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        draws = [r.values["draw"] for r in results]
        table = Table("draws", ("case", "draw"), tuple((r.trial.case, r.values["draw"])
                                                       for r in results))  # fmt: skip
        return ScenarioResult(self.name, seed, tuple(results), (table,), {"mean": np.mean(draws)})


@given(st.integers(0, 2**64 - 1), st.integers(0, 50), st.integers(0, 50))
def test_trial_seeds_depend_only_on_their_place(base: int, case: int, index: int) -> None:
    seed = trial_seed(base, case, index)
    assert seed == trial_seed(base, case, index)
    assert 0 <= seed < 2**63
    assert seed != trial_seed(base, case, index + 1)
    assert seed != trial_seed(base, case + 1, index)


def test_trials_cover_every_case_in_order_with_their_own_seeds() -> None:
    trials = Coin().trials(2, seed=5)
    assert [(t.case, t.index) for t in trials] == [("heads", 0), ("heads", 1), ("once", 0)]
    assert [t.seed for t in trials] == [trial_seed(5, 0, 0), trial_seed(5, 0, 1),
                                        trial_seed(5, 1, 0)]  # fmt: skip
    assert len(Coin().trials()) == Coin.default_trials + 1


@pytest.mark.parametrize(("trials", "error"), [(0, ValueError), (2.0, TypeError),
                                                (True, TypeError), (10**6, ValueError)])
def test_bad_trial_counts_are_refused(trials: object, error: type) -> None:
    with pytest.raises(error, match="trials"):
        Coin().trials(trials)  # type: ignore[arg-type]


def test_run_is_deterministic_and_json_ready() -> None:
    first, second = Coin().run(4, seed=1), Coin().run(4, seed=1)
    assert first.to_dict()["summary"] == second.to_dict()["summary"]
    assert Coin().run(4, seed=2).summary["mean"] != first.summary["mean"]
    data = json.loads(json.dumps(first.to_dict()))
    assert [t["case"] for t in data["trials"]] == ["heads"] * 4 + ["once"]
    assert data["tables"][0]["columns"] == ["case", "draw"]


def test_tables_render_aligned_with_nan_as_dash() -> None:
    table = Table("t", ("name", "value"), (("a", 1.23456), ("bb", math.nan), ("c", None)),
                  notes=("n",))  # fmt: skip
    lines = table.render(digits=2).splitlines()
    assert lines[0] == "t" and lines[-1] == "n"
    assert lines[3].endswith("1.2") and lines[4].endswith("-")
    assert len({len(line) for line in lines[1:3]}) == 1  # header and rule line up
    assert table.to_dict()["rows"][1] == ["bb", None]


def test_records_are_checked_and_copied() -> None:
    values = {"a": 1.0}
    result = TrialResult(Trial("c", 0, 0, 1), values)
    values["a"] = 2.0
    assert result.values["a"] == 1.0
    with pytest.raises(ValueError, match="values"):
        TrialResult(Trial("c", 0, 0, 1), {"a": math.inf})
    with pytest.raises(TypeError, match="trial"):
        TrialResult("c", {})  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"rows\[0\]"):
        Table("t", ("a", "b"), (("x",),))
    with pytest.raises(ValueError, match="seed"):
        Trial("c", 0, 0, -1)
    scene = Scene("s", points=(("goal", [1.0, 2.0]),))
    assert scene.points[0][1].shape == (1, 2) and not scene.points[0][1].flags.writeable


def test_copied_and_unpickled_scenes_keep_read_only_arrays(
    duplicate: Callable[[Any], Any],
) -> None:
    scene = Scene("s", paths=(("plan", [[0.0, 0.0], [1.0, 1.0]]),), points=(("goal", [1.0, 2.0]),))
    copy = duplicate(scene)
    for (_, xy), (_, original) in zip((*copy.paths, *copy.points),
                                      (*scene.paths, *scene.points), strict=True):  # fmt: skip
        assert not xy.flags.writeable and np.array_equal(xy, original)


def test_numpy_booleans_are_figures_like_python_booleans() -> None:
    """``values`` and ``summary`` store booleans as 0.0/1.0, NumPy's as well as Python's."""
    result = TrialResult(Trial("c", 0, 0, 1), {"ok": np.bool_(True), "also": True})
    assert result.values == {"ok": 1.0, "also": 1.0}
    summary = ScenarioResult("x", 0, (result,), (), {"all": np.all([True, False])})
    assert json.loads(json.dumps(summary.to_dict()))["summary"] == {"all": 0.0}


def test_registry_names_every_scenario() -> None:
    assert sorted(SCENARIOS) == ["demo", "diff-astar", "greedy", "indoor-nav", "omni-apf",
                                 "soccer"]  # fmt: skip
    for name, cls in SCENARIOS.items():
        assert get_scenario(name) is cls and cls.name == name and cls.title and cls.paper
    with pytest.raises(ValueError, match="omni-apf"):
        get_scenario("nosuch")


def test_find_data_looks_in_data_dir_then_the_environment(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "set").mkdir()
    (tmp_path / "set" / "x.yaml").write_text("x")
    assert find_data("set/x.yaml", data_dir=tmp_path) == tmp_path / "set" / "x.yaml"
    monkeypatch.setenv("NAVKIT_DATA", str(tmp_path))
    assert find_data("set/x.yaml") == tmp_path / "set" / "x.yaml"
    with pytest.raises(DataNotFoundError, match="NAVKIT_DATA"):
        find_data("set/missing.yaml", data_dir=tmp_path)


def test_a_misspelt_data_folder_is_not_replaced_by_the_synthetic_map(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # The "auto" maps fall back to the synthetic office when the data set is missing
    # from a real folder (DataNotFoundError), not when the folder named is wrong.
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("NAVKIT_DATA", str(tmp_path / "misspelt"))
    with pytest.raises(ValueError, match=r"\$NAVKIT_DATA names the data folder"):
        get_scenario("demo")()
    with pytest.raises(ValueError, match="data_dir names the data folder"):
        get_scenario("demo")(data_dir=tmp_path / "misspelt")
    # A real folder without the data set: the synthetic office.
    assert get_scenario("demo")(data_dir=tmp_path).map_path is None


def test_find_data_refuses_a_named_folder_that_does_not_exist(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # $NAVKIT_DATA naming no folder used to be skipped silently: the lookup went on
    # to a shared/data nearby, data the user had not chosen.
    import re  # (only this test needs it)

    nearby = tmp_path / "shared" / "data"
    (nearby / "set").mkdir(parents=True)
    (nearby / "set" / "x.yaml").write_text("x")
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("NAVKIT_DATA", raising=False)
    assert find_data("set/x.yaml").samefile(nearby / "set" / "x.yaml")
    missing = tmp_path / "misspelt"
    monkeypatch.setenv("NAVKIT_DATA", str(missing))
    pattern = rf"\$NAVKIT_DATA names the data folder {re.escape(str(missing))}, which does not"
    with pytest.raises(ValueError, match=pattern):
        find_data("set/x.yaml")
    # A relative value is shown resolved against the working directory too.
    monkeypatch.setenv("NAVKIT_DATA", "misspelt")
    with pytest.raises(ValueError, match=re.escape(f"misspelt ({missing})")):
        find_data("set/x.yaml")
    # A file is not a data folder either.
    monkeypatch.setenv("NAVKIT_DATA", str(nearby / "set" / "x.yaml"))
    with pytest.raises(ValueError, match=r"NAVKIT_DATA .* is not a folder"):
        find_data("set/x.yaml")
    # data_dir= is the only place looked in, and the variable is not read then.
    assert find_data("set/x.yaml", data_dir=nearby) == nearby / "set" / "x.yaml"
    # data_dir= naming no folder says so (it used to report the file as missing).
    with pytest.raises(ValueError, match=r"data_dir names the data folder .*does not exist"):
        find_data("set/x.yaml", data_dir=missing)
    # Set but empty is unset.
    monkeypatch.setenv("NAVKIT_DATA", "")
    assert find_data("set/x.yaml").samefile(nearby / "set" / "x.yaml")
