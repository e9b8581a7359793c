"""Leftovers of the command line (session 26): dash values and ``navkit plan --json``'s layout.

``navkit plan --start -inf,0`` said "expected one argument" (argparse takes a
value beginning with ``-`` for an option unless it is a plain negative
number): every option taking a point or a number now reads such a value and
its own check names the problem. ``--json`` wrote one coordinate a line; each
point ``[x, y]`` is now on one line. The plan's points begin and end at the
points given (``MapPlanner.plan``).
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.cli import main
from navkit.cli._files import json_text, write_json
from navkit.cli._parser import build_parser, join_negative_points
from navkit.mapping import OccupancyGrid


def usage_error(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    """The last line of a usage error (exit code 2, no traceback)."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("usage: navkit") and "Traceback" not in err
    return err.strip().splitlines()[-1]


# ----------------------------------------------------------------- dash values


@pytest.mark.parametrize("option", ["--start", "--goal", "--go", "--g"])
@pytest.mark.parametrize("text", ["-inf,0", "-Infinity,-1", "-nan,0", "-inf, 2", "-1,-inf"])
def test_a_non_finite_point_after_a_space_is_refused_as_non_finite(
    option: str, text: str, capsys: pytest.CaptureFixture[str]
) -> None:
    other = "--goal" if option == "--start" else "--start"
    line = usage_error(["plan", "m.yaml", other, "0,0", option, text], capsys)
    name = "--start" if option == "--start" else "--goal"
    assert line.endswith(f"argument {name}: X,Y must be finite, got {text!r}")


@pytest.mark.parametrize("text", ["-x,0", "-1;2", "-1,2,3", "-"])
def test_a_malformed_dash_point_names_the_shape(
    text: str, capsys: pytest.CaptureFixture[str]
) -> None:
    line = usage_error(["plan", "m.yaml", "--goal", "0,0", "--start", text], capsys)
    assert line.endswith(f"argument --start: expected X,Y in metres, got {text!r}")


finite = st.floats(min_value=-1e300, max_value=-1e-300, width=64)


@given(x=finite, y=st.floats(allow_nan=False, allow_infinity=False, width=64))
def test_every_negative_spelling_is_read(x: float, y: float) -> None:
    # repr gives exponents (-1e-300, -1.5e+200), which argparse took for options.
    for text in (f"{x!r},{y!r}", f"{x:.3e},{y!r}"):
        argv = join_negative_points(["plan", "m.yaml", "--start", text, "--goal", text])
        args = build_parser().parse_args(argv)
        assert args.start == args.goal == (float(text.split(",")[0]), y)


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["plan", "m.yaml", "--start", "0,0", "--goal", "1,1", "--radius", "-inf"],
         "argument --radius: must be in [0, 100] m, got '-inf'"),
        (["plan", "m.yaml", "--start", "0,0", "--goal", "1,1", "--start-tolerance", "-1e-3"],
         "argument --start-tolerance: must be in [0, 1e9] m, got '-1e-3'"),
        (["run", "demo", "--seed", "-1e3"], "argument --seed: expected an integer, got '-1e3'"),
        (["run", "demo", "--trials", "-inf"], "argument --trials: expected an integer, got '-inf'"),
        (["run", "demo", "--workers", "-2"], "argument --workers: must be in [1, 1024], got -2"),
    ],
)  # fmt: skip
def test_number_options_name_the_problem_of_a_dash_value(
    argv: list[str], words: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert usage_error(argv, capsys).endswith(words)


def test_options_and_other_values_are_left_alone(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["plan", "m.yaml", "--start", "-h", "--goal", "--plot", "--json", "-"]
    assert join_negative_points(argv) == argv
    # "-h" and "--plot" after a point option stay options, as before.
    line = usage_error(["plan", "m.yaml", "--start", "0,0", "--goal", "--plot", "p.png"], capsys)
    assert line.endswith("argument --goal: expected one argument")
    assert join_negative_points(["plan", "--start=-inf,0", "--goal", "-1,2"]) == [
        "plan", "--start=-inf,0", "--goal=-1,2"]  # fmt: skip


# ---------------------------------------------------------------- JSON layout

json_values = st.recursive(
    st.none() | st.booleans() | st.integers() | st.text(max_size=5)
    | st.floats(allow_nan=False, allow_infinity=False),
    lambda inner: st.lists(inner, max_size=4)
    | st.dictionaries(st.text(max_size=4), inner, max_size=4),
    max_leaves=20,
)  # fmt: skip


def _number_lists(value: Any) -> list[list[Any]]:
    """Every non-empty list of numbers (and None) inside ``value``."""
    if isinstance(value, dict):
        return [x for v in value.values() for x in _number_lists(v)]
    if isinstance(value, list):
        if value and all(
            v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)) for v in value
        ):
            return [value]
        return [x for v in value for x in _number_lists(v)]
    return []


@given(json_values)
def test_json_text_holds_the_same_data(data: Any) -> None:
    plain = json_text(data)
    assert plain == json.dumps(data, indent=2, allow_nan=False)  # the default is unchanged
    compact = json_text(data, number_lists_on_one_line=True)
    assert json.loads(compact) == json.loads(plain)
    lines = compact.splitlines()
    for numbers in _number_lists(json.loads(plain)):
        one_line = json.dumps(numbers)
        assert any(line.strip().rstrip(",").endswith(one_line) for line in lines), one_line
    if not _number_lists(json.loads(plain)):
        assert compact == plain


def test_json_text_refuses_what_json_dumps_refuses(tmp_path: Path) -> None:
    for bad, error in (({"a": [1.0, math.nan]}, ValueError), ({"a": [object()]}, TypeError)):
        with pytest.raises(error):
            json_text(bad, number_lists_on_one_line=True)
        with pytest.raises(error):
            write_json(bad, tmp_path / "x.json", number_lists_on_one_line=True)
    assert list(tmp_path.iterdir()) == []  # nothing written


@pytest.fixture
def corridor(tmp_path: Path) -> Path:
    """A 3 x 2 m map with a wall leaving a gap at the top."""
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:14, 14:16] = True
    OccupancyGrid.from_occupancy(occupied, resolution=0.1).save(tmp_path / "corridor.yaml")
    return tmp_path / "corridor.yaml"


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
def test_plan_json_has_one_point_a_line_from_the_start_given_to_the_goal_given(
    corridor: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str], planner: str
) -> None:
    target = tmp_path / "plan.json"
    # Off the cells' centres: the path begins and ends at these points exactly.
    argv = ["plan", str(corridor), "--start", "0.52,0.61", "--goal", "(2.58, 0.5)",
            "--planner", planner, "--radius", "0.1", "--json", str(target), "--quiet"]  # fmt: skip
    assert main(argv) == 0
    capsys.readouterr()
    text = target.read_text(encoding="utf-8")
    data = json.loads(text)
    points = data["points"]
    assert points[0] == data["start"] == [0.52, 0.61]
    assert points[-1] == data["goal"] == [2.58, 0.5]
    np.testing.assert_allclose(points[1], [0.55, 0.65], atol=1e-12)  # the start cell's centre
    point_lines = [line for line in text.splitlines() if re.fullmatch(r"\s*\[[^\[\]]*\],?", line)]
    assert [json.loads(line.strip().rstrip(",")) for line in point_lines] == points
    assert '  "start": [0.52, 0.61],' in text.splitlines()
    length = float(np.hypot(*np.diff(np.array(points), axis=0).T).sum())
    assert math.isclose(data["length"], length, rel_tol=1e-9)
    # Every other value as json.dumps lays it out: the same data, a shorter file.
    assert len(text.splitlines()) == len(json.dumps(data, indent=2).splitlines()) - 3 * (
        len(points) + 2
    )
