"""``ScenarioResult.from_dict`` and ``Table.from_dict``: results saved as JSON read back.

A user comparing runs saved with ``navkit run --json`` (or ``to_dict``) had no
way back to a result: the tables could not be printed again, nor the figures
compared through the records. ``from_dict`` inverts ``to_dict``: the round trip
through JSON gives the same ``to_dict``, a table prints the same text.
"""

from __future__ import annotations

import json
import math
from typing import Any

import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit.sim import ScenarioResult, Table, Trial, TrialResult
from navkit.sim.scenarios import OmniApf


def _through_json(data: dict[str, Any]) -> Any:
    return json.loads(json.dumps(data, allow_nan=False))


def test_a_real_run_reads_back_with_its_figures_and_tables() -> None:
    result = OmniApf().run(trials=1, seed=3)
    back = ScenarioResult.from_dict(_through_json(result.to_dict()))
    assert back.to_dict() == result.to_dict()
    assert back.table() == result.table()
    assert back.scenario == "omni-apf" and back.seed == 3
    assert [r.trial for r in back.trials] == [r.trial for r in result.trials]
    assert all(r.trace is None for r in back.trials) and back.scene is None
    assert any(r.trace is not None for r in result.trials)  # what to_dict leaves out


FIGURE = st.one_of(st.floats(allow_infinity=False), st.integers(-(10**6), 10**6))
CELL = st.one_of(st.none(), st.text(max_size=5), st.booleans(), st.integers(), st.floats())
NAME = st.text(min_size=1, max_size=6)


@st.composite
def results(draw: st.DrawFn) -> ScenarioResult:
    columns = tuple(draw(st.lists(NAME, min_size=1, max_size=3)))
    rows = draw(st.lists(st.tuples(*[CELL] * len(columns)), max_size=3))
    table = Table(draw(NAME), columns, tuple(rows), tuple(draw(st.lists(NAME, max_size=2))))
    trials = tuple(
        TrialResult(
            Trial(draw(NAME), k, draw(st.integers(0, 9)), draw(st.integers(0, 2**64 - 1))),
            draw(st.dictionaries(NAME, FIGURE, max_size=3)),
            wall_time=draw(st.floats(0.0, 1e6)),
        )
        for k in range(draw(st.integers(0, 3)))
    )
    summary = draw(st.dictionaries(NAME, FIGURE, max_size=3))
    return ScenarioResult(draw(NAME), draw(st.integers(0, 2**64 - 1)), trials, (table,), summary)


# The strategies draw a non-finite cell or a NaN figure too rarely: 60 examples ran
# neither branch below (coverage), so these are written out.
_NON_FINITE = ScenarioResult(
    "x", 0, (TrialResult(Trial("c", 0, 0, 1), {"e": math.nan, "f": 1.5}, wall_time=0.1),),
    (Table("t", ("a", "b", "c", "d"),
           ((math.nan, math.inf, -math.inf, 2.5), ("s", None, 3, True))),),
    {"m": math.nan},
)  # fmt: skip


@settings(max_examples=60, deadline=None)
@given(result=results())
@example(result=_NON_FINITE)
def test_the_round_trip_through_json_keeps_every_figure(result: ScenarioResult) -> None:
    data = result.to_dict()
    back = ScenarioResult.from_dict(_through_json(data))
    assert back.to_dict() == data
    for mine, theirs in zip(back.trials, result.trials, strict=True):
        assert mine.trial == theirs.trial and mine.wall_time == theirs.wall_time
        for key, value in theirs.values.items():  # NaN is NaN again, not None
            assert mine.values[key] == value or (math.isnan(value) and math.isnan(mine.values[key]))
    # A NaN or infinite cell comes back empty (None): the JSON cannot tell them apart.
    cells = [c for row in result.tables[0].rows for c in row]
    back_cells = [c for row in back.tables[0].rows for c in row]
    for cell, got in zip(cells, back_cells, strict=True):
        if isinstance(cell, float) and not math.isfinite(cell):
            assert got is None
        else:
            assert got == cell and type(got) is type(cell)


def test_a_table_reads_back_equal_and_prints_the_same() -> None:
    table = Table("t", ("case", "error (m)"), (("a", 0.25), ("b", None)), ("note",))
    back = Table.from_dict(_through_json(table.to_dict()))
    assert back == table and back.render() == table.render()


def _data() -> dict[str, Any]:
    trial = TrialResult(Trial("c", 0, 0, 1), {"e": 1.0}, wall_time=0.1)
    return ScenarioResult("x", 0, (trial,), (Table("t", ("a",), ((1.0,),)),)).to_dict()


def _changed(path: tuple[Any, ...], value: Any) -> dict[str, Any]:
    data = _data()
    target: Any = data
    for key in path[:-1]:
        target = target[key]
    if value is KeyError:
        del target[path[-1]]
    else:
        target[path[-1]] = value
    return data


@pytest.mark.parametrize(
    ("data", "error", "message"),
    [
        ([], TypeError, r"^data must be a mapping \(what to_dict gives\), got list"),
        (_changed(("seed",), KeyError), ValueError, r"^data has no 'seed' key"),
        (_changed(("extra",), 1), ValueError, r"^data has an unknown key 'extra'"),
        (_changed(("seed",), -1), ValueError, r"^data: seed must be"),
        (_changed(("summary",), [1]), TypeError, r"^data: summary must be a mapping"),
        (_changed(("trials",), "ab"), TypeError, r"data\['trials'\]"),
        (_changed(("trials", 0, "values", "e"), "1"), TypeError,
         r"^data\['trials'\]\[0\]: values\['e'\] must be a real number"),
        (_changed(("trials", 0, "values", "e"), 1e309), ValueError,
         r"^data\['trials'\]\[0\]: values\['e'\] must be finite or NaN"),
        (_changed(("trials", 0, "case"), KeyError), ValueError,
         r"^data\['trials'\]\[0\] has no 'case' key"),
        (_changed(("trials", 0, "wall_time"), -1.0), ValueError,
         r"^data\['trials'\]\[0\]: wall_time must be >= 0"),
        (_changed(("tables", 0, "rows"), [[1.0, 2.0]]), ValueError,
         r"^data\['tables'\]\[0\]: rows\[0\] has 2 cells for 1 column"),
        (_changed(("tables", 0, "notes"), KeyError), ValueError,
         r"^data\['tables'\]\[0\] has no 'notes' key"),
    ],
)  # fmt: skip
def test_bad_data_is_refused_naming_where(data: Any, error: type, message: str) -> None:
    with pytest.raises(error, match=message):
        ScenarioResult.from_dict(data)
