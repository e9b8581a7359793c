"""TrialResult.values and ScenarioResult.summary are read-only, in copies and pickles too.

They were plain dicts inside frozen records: ``r.summary["x"] = 1`` changed a
"frozen" result, and ``copy.copy`` shared the dict, so editing a copy's
summary edited the original's. They are now ``FrozenDict`` s (equal to the
dicts they were, printed and pickled as those were); the JSON a run writes is
unchanged byte for byte.
"""

from __future__ import annotations

import copy
import json
import math
import pickle
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pytest

from navkit._shared.frozendict import FrozenDict
from navkit.cli import main
from navkit.cli._outputs import save_json
from navkit.sim import Scenario, ScenarioResult, Table, Trial, TrialResult, sweep
from scenario_results import comparable_dict


def _result() -> ScenarioResult:
    values = {"error": 0.02, "ok": np.bool_(True), "nan": math.nan, "n": np.int64(3)}
    t1 = TrialResult(Trial("a", 0, 0, 7), values, wall_time=0.5)
    t2 = TrialResult(Trial("b", 1, 0, 2**63 + 5), {"error": 1e-300, "z": -0.0})
    table = Table("t", ("a", "b"), ((1.0, None), ("s", math.nan)))
    summary = {"mean": 0.1 + 0.2, "nan": float("nan"), "zero": -0.0}
    return ScenarioResult("x", 2**64 - 1, (t1, t2), (table,), summary)


#: What ``save_json`` wrote for :func:`_result` while the figures were dicts.
GOLDEN = (
    b'{\n  "scenario": "x",\n  "seed": 18446744073709551615,\n  "summary": {\n'
    b'    "mean": 0.30000000000000004,\n    "nan": null,\n    "zero": -0.0\n  },\n'
    b'  "tables": [\n    {\n      "title": "t",\n      "columns": [\n        "a",\n'
    b'        "b"\n      ],\n      "rows": [\n        [\n          1.0,\n          null\n'
    b'        ],\n        [\n          "s",\n          null\n        ]\n      ],\n'
    b'      "notes": []\n    }\n  ],\n  "trials": [\n    {\n      "case": "a",\n'
    b'      "case_index": 0,\n      "index": 0,\n      "seed": 7,\n      "values": {\n'
    b'        "error": 0.02,\n        "ok": 1.0,\n        "nan": null,\n        "n": 3.0\n'
    b'      },\n      "wall_time": 0.5\n    },\n    {\n      "case": "b",\n'
    b'      "case_index": 1,\n      "index": 0,\n      "seed": 9223372036854775813,\n'
    b'      "values": {\n        "error": 1e-300,\n        "z": -0.0\n      },\n'
    b'      "wall_time": 0.0\n    }\n  ]\n}\n'
)


def test_the_figures_cannot_be_changed_in_place() -> None:
    result = _result()
    with pytest.raises(TypeError, match="read-only: cannot set 'mean'"):
        result.summary["mean"] = 1.0  # type: ignore[index]
    with pytest.raises(TypeError, match="read-only: cannot delete 'error'"):
        del result.trials[0].values["error"]  # type: ignore[attr-defined]
    assert result.summary["mean"] == 0.1 + 0.2 and "error" in result.trials[0].values
    assert isinstance(result.summary, FrozenDict)
    assert isinstance(result.trials[0].values, FrozenDict)


def test_the_figures_still_equal_print_and_convert_as_dicts() -> None:
    result = _result()
    assert result.trials[1].values == {"error": 1e-300, "z": -0.0}
    assert {"error": 1e-300, "z": -0.0} == result.trials[1].values  # noqa: SIM300 (reflected)
    assert dict(result.trials[0].values)["ok"] == 1.0
    assert "summary={'mean': 0.30000000000000004, 'nan': nan, 'zero': -0.0}" in repr(result)
    assert "values={'error': 1e-300, 'z': -0.0}" in repr(result.trials[1])


def test_the_callers_dict_is_copied_not_kept() -> None:
    summary = {"a": 1.0}
    result = ScenarioResult("x", 0, (), (), summary)
    summary["a"] = 2.0
    assert result.summary == {"a": 1.0}
    assert summary == {"a": 2.0}  # and the input is left as given


@pytest.mark.parametrize("copier", [copy.copy, copy.deepcopy], ids=["copy", "deepcopy"])
def test_copies_are_independent_of_their_originals(copier: object) -> None:
    result = _result()
    twin = copier(result)  # type: ignore[operator]
    with pytest.raises(TypeError, match="read-only"):
        twin.summary["mean"] = 5.0
    with pytest.raises(TypeError, match="read-only"):
        twin.trials[0].values["error"] = 5.0
    # Editing a dict made from the copy reaches neither.
    edited = dict(twin.summary)
    edited["mean"] = 5.0
    assert result.summary["mean"] == twin.summary["mean"] == 0.1 + 0.2


@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
def test_results_pickle_under_every_protocol_with_read_only_figures(protocol: int) -> None:
    result = _result()
    back = pickle.loads(pickle.dumps(result, protocol))
    assert isinstance(back.summary, FrozenDict) and isinstance(back.trials[0].values, FrozenDict)
    with pytest.raises(TypeError, match="read-only"):
        back.summary["mean"] = 1.0
    assert save_json(back, "/dev/null") and back.to_dict() == json.loads(GOLDEN)


def test_pickles_made_while_the_figures_were_dicts_load_read_only() -> None:
    result = _result()
    # What a pickle of an earlier navkit holds: the same fields, plain dicts.
    object.__setattr__(result, "summary", dict(result.summary))
    for r in result.trials:
        object.__setattr__(r, "values", dict(r.values))
    for protocol in range(pickle.HIGHEST_PROTOCOL + 1):
        back = pickle.loads(pickle.dumps(result, protocol))
        assert type(back.summary) is FrozenDict
        assert all(type(r.values) is FrozenDict for r in back.trials)
        assert comparable_dict(back.to_dict()) == comparable_dict(json.loads(GOLDEN))


def test_the_json_written_is_unchanged_byte_for_byte(tmp_path: Path) -> None:
    assert save_json(_result(), tmp_path / "r.json").read_bytes() == GOLDEN  # type: ignore[arg-type]


class Figures(Scenario):
    """Trials whose figures are drawn from their seeds (module level: workers import it)."""

    name = "figures"
    title = "test"
    paper = "none"
    default_trials = 3

    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        return (("a", trials),)

    def run_trial(self, trial: Trial) -> TrialResult:
        draw = float(np.random.default_rng(trial.seed).random())
        return TrialResult(trial, {"draw": draw, "none": math.nan})

    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        mean = float(np.mean([r.values["draw"] for r in results]))
        return ScenarioResult(self.name, seed, tuple(results), (), {"mean": mean})


def test_figures_come_back_read_only_from_a_process_pool() -> None:
    serial = sweep(Figures(), trials=3, seeds=4, workers=1)
    pooled = sweep(Figures(), trials=3, seeds=4, workers=2)
    assert all(type(r.values) is FrozenDict for r in pooled.trials)
    assert type(pooled.summary) is FrozenDict
    assert [r.values["draw"] for r in pooled.trials] == [r.values["draw"] for r in serial.trials]
    assert pooled.summary == serial.summary


def test_the_command_writes_the_json_of_the_result_it_ran(tmp_path: Path) -> None:
    target = tmp_path / "r.json"
    argv = ["run", "omni-apf", "--trials", "1", "--seed", "3", "--workers", "1", "--quiet"]
    assert main([*argv, "--json", str(target)]) == 0
    written = target.read_text(encoding="utf-8")
    data = json.loads(written)
    # The bytes are json.dumps of the plain data, laid out as write_json lays it out.
    assert written == json.dumps(data, indent=2, ensure_ascii=False) + "\n"
    again = sweep("omni-apf", trials=1, seeds=3, workers=1).to_dict()
    assert comparable_dict(data) == comparable_dict(json.loads(json.dumps(again)))
