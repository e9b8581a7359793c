"""Tables and scenario records hold Python objects, whatever NumPy gave (review 32, OBJECTS).

``Table`` kept its cells as given: a figure computed with NumPy printed as
``np.float64(2.0)`` in the table's repr (a notebook, an assertion message),
a label read from an array as ``np.str_('a')``, and a ``np.bool_`` flag was
refused as "got bool" though Python's bool is a cell (shown yes/no). Cells are
now stored as Python's str, bool, int or float, and the titles, column names,
notes and case names as plain str, as ``TrialResult.values`` already stored
floats. Tables compare and hash as before (a NumPy figure equals its float).
"""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest

from navkit.sim import ScenarioResult, Scene, Table, Trial, TrialResult


def _numpy_table() -> Table:
    labels = np.array(["a", "b"])
    return Table(
        labels[0],
        (labels[0], "figure", "ok"),
        (
            (labels[0], np.float64(2.0), np.bool_(True)),
            (labels[1], np.uint8(4), np.False_),
            (labels[0], np.float32(0.5), None),
        ),
        (labels[1],),
    )


def test_numpy_cells_are_stored_as_python_objects() -> None:
    table = _numpy_table()
    types = [[type(cell) for cell in row] for row in table.rows]
    assert types == [[str, float, bool], [str, int, bool], [str, float, type(None)]]
    assert table.rows == (("a", 2.0, True), ("b", 4, False), ("a", 0.5, None))
    assert type(table.title) is str and type(table.notes[0]) is str
    assert all(type(c) is str for c in table.columns)


def test_the_repr_shows_no_numpy_types_and_evaluates_back() -> None:
    table = _numpy_table()
    text = repr(table)
    assert "np." not in text, text
    assert text == (
        "Table(title='a', columns=('a', 'figure', 'ok'), "
        "rows=(('a', 2.0, True), ('b', 4, False), ('a', 0.5, None)), notes=('b',))"
    )
    assert eval(text) == table


def test_equality_hash_and_rendering_are_unchanged() -> None:
    table = _numpy_table()
    plain = Table("a", ("a", "figure", "ok"),
                  (("a", 2.0, True), ("b", 4, False), ("a", 0.5, None)), ("b",))  # fmt: skip
    assert table == plain and hash(table) == hash(plain)
    assert table.render() == plain.render()
    assert table.render().splitlines()[3].split()[-1] == "yes"
    assert pickle.loads(pickle.dumps(table)) == table
    nan_table = Table("t", ("x",), ((np.float64(math.nan),),))
    assert nan_table == Table("t", ("x",), ((math.nan,),))
    assert hash(nan_table) == hash(Table("t", ("x",), ((math.nan,),)))


@pytest.mark.parametrize("cell", [np.array([1.0]), 1 + 2j, np.complex128(1.0), [1.0], object()])
def test_other_cells_are_still_refused(cell: object) -> None:
    with pytest.raises(TypeError, match=r"rows\[0\]\[1\] must be text, a number or None"):
        Table("t", ("a", "b"), (("x", cell),))


def test_names_from_arrays_are_plain_str_in_the_other_records() -> None:
    name = np.array(["run"])[0]
    trial = Trial(name, 0, 0, 1)
    scene = Scene(name)
    result = ScenarioResult(name, 0, (TrialResult(trial, {"e": 1.0}),), (), {}, scene)
    assert type(trial.case) is str and type(scene.title) is str
    assert type(result.scenario) is str
    assert "np." not in repr(result), repr(result)
    assert trial == Trial("run", 0, 0, 1) and hash(trial) == hash(Trial("run", 0, 0, 1))
