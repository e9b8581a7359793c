"""Fuzz specs of the experiment framework: ``navkit.sim``'s ``Scenario`` records,
``trial_seed``, ``navkit.sim.scenarios.find_data`` / ``get_scenario`` and
``navkit.errors.DataNotFoundError`` (registered on import by ``fuzz_specs.py``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from fuzz_engine import (
    Anything,
    Call,
    Choice,
    Ctx,
    Hostile,
    Kind,
    Real,
    SequenceOf,
    Text,
    call,
    h,
    method,
    spec,
)

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
from navkit.sim.scenarios import find_data, get_scenario

S = "navkit.sim."
ROWS = Anything()


class Figures(Kind):
    """Named figures: a mapping of str to a real number (NaN allowed, infinities refused)."""

    name = "a mapping of str to float"

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        return [
            h("{}", {}),
            h("{1: 2.0}", {1: 2.0}),
            h("{'a': 'x'}", {"a": "x"}),
            h("{'a': None}", {"a": None}),
            h("{'a': inf}", {"a": math.inf}),
            h("{'a': nan}", {"a": math.nan}),
            h("{'a': True}", {"a": True}),
            h("[('a', 1.0)]", [("a", 1.0)]),
            h("1.0", 1.0),
            h("'a'", "a"),
        ]

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if not isinstance(value, Mapping):
            return f"a {type(value).__name__}"
        for key, figure in value.items():
            if not isinstance(key, str):
                return "a key that is not a str"
            if not isinstance(figure, (int, float, np.integer, np.floating)):
                return "a figure that is not a number"
            if math.isinf(float(figure)):
                return "an infinite figure"
        return None


FIGURES = Figures()
DIGITS = {"digits": Real(integer=True)}


def trial() -> Call:
    return call(Trial, "case", 0, 1, 12345)


def table() -> Call:
    return call(
        Table, "errors", ("target", "navkit (mm)", "paper (mm)"), (("(0, 3)", 12.5, 31.0),),
        notes=("a note",),
    )  # fmt: skip


def result() -> Call:
    return call(
        ScenarioResult,
        "x",
        3,
        (TrialResult(Trial("case", 0, 0, 1), {"error": 0.02}),),
        (Table("t", ("a",), ((1.0,),)),),
        {"error": 0.02, "missing": float("nan")},
        scene=None,
    )


spec(
    "navkit.errors.DataNotFoundError",
    lambda c: call(DataNotFoundError, "map.yaml not found"),
)
spec(
    S + "trial_seed",
    lambda c: call(trial_seed, 7, 1, 2),
    kinds={
        "base": Real(integer=True),
        "case_index": Real(integer=True),
        "trial_index": Real(integer=True),
    },
)
spec(
    S + "Trial",
    lambda c: trial(),
    kinds={
        "case": Text(),
        "case_index": Real(integer=True),
        "index": Real(integer=True),
        "seed": Real(integer=True),
    },
)
spec(
    S + "TrialResult",
    lambda c: call(TrialResult, trial(), {"error": 0.02, "time": float("nan")}, wall_time=0.5),
    kinds={"values": FIGURES, "wall_time": Real(), "trace": Anything(optional=True)},
    nan_ok="a figure that does not apply is NaN",
)
spec(
    S + "Table",
    lambda c: table(),
    kinds={"title": Text(), "columns": Anything(), "rows": ROWS, "notes": Anything()},
)
spec(S + "Table.render", lambda c: method(table(), "render", digits=4), kinds=DIGITS)
spec(S + "Table.to_dict", lambda c: method(table(), "to_dict"))
spec(
    S + "Table.from_dict",
    lambda c: call(Table.from_dict, Table("t", ("a", "b"), (("x", 1.0),), ("n",)).to_dict()),
    kinds={"data": Anything()},
)
spec(
    S + "Scene",
    lambda c: call(
        Scene,
        "title",
        paths=(("plan", np.array([[0.0, 0.0], [1.0, 1.0]])),),
        points=(("goal", np.array([1.0, 1.0])),),
    ),
    kinds={
        "title": Text(),
        "world": Anything(optional=True),
        "paths": Anything(),
        "traces": Anything(),
        "points": Anything(),
    },
)
spec(
    S + "ScenarioResult",
    lambda c: result(),
    kinds={
        "scenario": Text(),
        "scene": Anything(optional=True),
        "seed": Real(integer=True),
        "trials": SequenceOf(TrialResult),
        "tables": SequenceOf(Table),
        "summary": FIGURES,
    },
    nan_ok="a figure that does not apply is NaN",
)
spec(S + "ScenarioResult.table", lambda c: method(result(), "table", digits=2), kinds=DIGITS)
spec(S + "ScenarioResult.to_dict", lambda c: method(result(), "to_dict"))
spec(
    S + "ScenarioResult.from_dict",
    lambda c: call(
        ScenarioResult.from_dict,
        ScenarioResult(
            "x",
            3,
            (TrialResult(Trial("case", 0, 0, 1), {"error": 0.02}),),
            (Table("t", ("a",), ((1.0,),)),),
            {"error": 0.02, "missing": float("nan")},
        ).to_dict(),
    ),
    kinds={"data": Anything()},
    nan_ok="a figure that does not apply is NaN",
)
spec(
    S + "Scenario",
    lambda c: call(Scenario),
    expect_error=TypeError,  # abstract: the scenarios are its subclasses
)
spec(
    "navkit.sim.scenarios.get_scenario",
    lambda c: call(get_scenario, "omni-apf"),
    kinds={"name": Choice("omni-apf", "greedy", "indoor-nav", "soccer", "diff-astar", "demo")},
)


def _find_data(c: Ctx) -> Call:
    (c.tmp / "maps").mkdir(exist_ok=True)
    (c.tmp / "maps" / "x.yaml").write_text("image: x.pgm\n")
    return call(find_data, "maps/x.yaml", data_dir=str(c.tmp))


spec(
    "navkit.sim.scenarios.find_data",
    _find_data,
    kinds={"relative": Anything(), "data_dir": Anything(optional=True)},
)
