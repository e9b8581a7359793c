"""The MovingAI readers: ``read_movingai_map``, ``read_movingai_scenarios`` and their records.

Oracles: a plain-Python parser here (as the benchmark tests' own in
``tests/planning/grid/test_movingai.py``), the published optimal lengths
through A*, and files written here from random terrain.
"""

from __future__ import annotations

import copy
import pickle
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping.io import (
    MovingAIMap,
    MovingAIScenarios,
    read_movingai_map,
    read_movingai_scenarios,
)
from navkit.planning import AStarPlanner


def read_map(path: Path) -> np.ndarray:
    """The oracle: a ``.map`` as 1 (``.``, ``G``, ``S``) or inf, in plain Python."""
    lines = path.read_text(encoding="ascii").splitlines()
    start = lines.index("map") + 1
    height = int(next(line.split()[1] for line in lines[:start] if line.startswith("height")))
    return np.array(
        [[1.0 if ch in ".GS" else np.inf for ch in row] for row in lines[start:][:height]]
    )


def read_scenarios(path: Path) -> list[tuple[tuple[int, int], tuple[int, int], float]]:
    """The oracle: a ``.scen`` as ((row, col) start, (row, col) goal, length) per line."""
    out = []
    for line in path.read_text(encoding="ascii").splitlines()[1:]:
        if line.strip():
            f = line.split("\t")
            out.append(((int(f[5]), int(f[4])), (int(f[7]), int(f[6])), float(f[8])))
    return out


FOLDER = "movingai-grid-benchmarks"
TERRAIN = ".G@OTSW"
TINY = "type octile\nheight 2\nwidth 3\nmap\n..@\nT.S\n"
SCEN = "version 1\n0\ttiny.map\t3\t2\t0\t0\t2\t1\t2.41421356\n"


def _maps(shared_data: Path) -> list[Path]:
    maps = sorted((shared_data / FOLDER).glob("*/*.map"))
    assert len(maps) >= 11
    return maps


def test_every_shared_map_and_scenario_file_reads_as_the_independent_parser(
    shared_data: Path,
) -> None:
    for path in _maps(shared_data):
        grid = read_movingai_map(path)
        np.testing.assert_array_equal(grid.costs, read_map(path))
        assert grid.passable.sum() == np.isfinite(read_map(path)).sum()
        problems = read_movingai_scenarios(path.with_name(path.name + ".scen"))
        expected = read_scenarios(path.with_name(path.name + ".scen"))
        assert len(problems) == len(expected) > 0
        np.testing.assert_array_equal(problems.start_cells, [s[0] for s in expected])
        np.testing.assert_array_equal(problems.goal_cells, [s[1] for s in expected])
        np.testing.assert_array_equal(problems.optimal_lengths, [s[2] for s in expected])
        assert set(problems.map_names) == {path.name}
        assert (problems.map_shapes == grid.shape).all()
        np.testing.assert_array_equal(problems.buckets, problems.optimal_lengths // 4)


def test_astar_on_a_read_map_reaches_the_read_optimal_lengths(shared_data: Path) -> None:
    base = shared_data / FOLDER / "dao"
    grid = read_movingai_map(base / "arena2.map")
    problems = read_movingai_scenarios(base / "arena2.map.scen")
    planner = AStarPlanner(grid.costs)
    for start, goal, optimal in list(
        zip(problems.start_cells, problems.goal_cells, problems.optimal_lengths, strict=True)
    )[::9]:
        assert planner.plan(start, goal).cost == pytest.approx(optimal, rel=1e-6, abs=1e-6)


def _write_map(folder: Path, rows: list[str], *, order: tuple[str, ...], newline: str) -> Path:
    values = {"type": "octile", "height": str(len(rows)), "width": str(len(rows[0]))}
    text = newline.join([*(f"{key} {values[key]}" for key in order), "map", *rows]) + newline
    path = folder / "random.map"
    path.write_bytes(text.encode("ascii"))
    return path


@settings(max_examples=60, deadline=None)
@given(
    data=st.data(),
    height=st.integers(1, 12),
    width=st.integers(1, 12),
    order=st.permutations(("type", "height", "width")),
    newline=st.sampled_from(["\n", "\r\n"]),
    blank_lines=st.integers(0, 3),
)
def test_random_terrain_reads_back_cell_for_cell(
    tmp_path_factory: pytest.TempPathFactory,
    data: st.DataObject,
    height: int,
    width: int,
    order: tuple[str, ...],
    newline: str,
    blank_lines: int,
) -> None:
    row = st.text(alphabet=TERRAIN, min_size=width, max_size=width)
    rows = data.draw(st.lists(row, min_size=height, max_size=height))
    path = _write_map(tmp_path_factory.mktemp("map"), rows, order=tuple(order), newline=newline)
    with path.open("ab") as fh:
        fh.write(newline.encode() * blank_lines)
    grid = read_movingai_map(path)
    assert grid.shape == (height, width)
    assert ["".join(r) for r in grid.terrain.tolist()] == rows
    for r, text in enumerate(rows):
        for c, char in enumerate(text):
            assert grid.passable[r, c] == (char in ".GS")
            assert grid.costs[r, c] == (1.0 if char in ".GS" else np.inf)
    assert MovingAIMap(rows).terrain.tolist() == grid.terrain.tolist()


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (TINY.replace("T.S", "T."), r":6: a row of 2 characters, the header's width is 3"),
        (TINY.replace("T.S\n", ""), r"1 row after the 'map' line, the header's height is 2"),
        (TINY + "...\n", "more than the 2 rows"),
        (TINY.replace("height 2", "height 0"), "height '0' is not a positive integer"),
        (TINY.replace("height 2", "height -2"), "height '-2' is not a positive integer"),
        (TINY.replace("width 3", "width 100000"), "more than the 2 rows|200000|a row of"),
        (
            TINY.replace("height 2", "height 100000").replace("width 3", "width 100000"),
            r"100000 x 100000 cells, more than 2\*\*26 = 67108864 \(37.3 GiB of <U1",
        ),
        (TINY.replace("type octile\n", ""), "no 'type' line"),
        (TINY.replace("octile", "tile"), "type 'tile', expected 'octile'"),
        ("height 2\n" + TINY, ":3: a second 'height' line"),
        (TINY.replace("map\n", ""), ":4: '..@' is not a header line"),
        (TINY.replace("..@", ".1@"), r":5: '1' at column 1 is not a MovingAI terrain character"),
        (SCEN, ":1: 'version 1' is not a header line"),
        ("", "no 'map' line"),
    ],
)
def test_malformed_maps_are_refused_naming_the_file_and_line(
    tmp_path: Path, text: str, message: str
) -> None:
    path = tmp_path / "bad.map"
    path.write_text(text)
    with pytest.raises(ValueError, match=message) as info:
        read_movingai_map(path)
    assert str(path) in str(info.value)


def test_binary_and_non_ascii_maps_are_refused_at_once(tmp_path: Path) -> None:
    path = tmp_path / "bad.map"
    path.write_bytes(b"\x00" * 10_000_000)
    with pytest.raises(ValueError, match="longer than 4096 bytes"):
        read_movingai_map(path)
    path.write_bytes(TINY.encode().replace(b"T", b"\xff"))
    with pytest.raises(ValueError, match=":6: byte 0xff at column 0"):
        read_movingai_map(path)
    path.write_bytes(b"type \xffoctile\n")
    with pytest.raises(ValueError, match=":1: bytes that are not ASCII"):
        read_movingai_map(path)


def test_paths_that_are_not_files_are_refused(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match=r"MovingAI map .* does not exist"):
        read_movingai_map(tmp_path / "missing.map")
    with pytest.raises(ValueError, match="is a directory"):
        read_movingai_scenarios(tmp_path)
    with pytest.raises(TypeError, match=r"path must be a str or an os\.PathLike"):
        read_movingai_map(3)  # type: ignore[arg-type]


def test_the_terrain_record_takes_rows_or_arrays_and_keeps_none_of_them() -> None:
    rows = ["..@", "T.S"]
    chars = np.array([list(row) for row in rows])
    from_rows, from_array = MovingAIMap(rows), MovingAIMap(chars)
    transposed = MovingAIMap(np.ascontiguousarray(chars.T).T)  # a Fortran-ordered copy
    for grid in (from_rows, from_array, transposed):
        assert grid.terrain.dtype == np.dtype("<U1")
        assert not grid.terrain.flags.writeable
        np.testing.assert_array_equal(grid.terrain, chars)
    assert chars.flags.writeable and not np.shares_memory(chars, from_array.terrain)
    costs = from_rows.costs
    costs[0, 0] = np.inf  # a new array each time: the record is unchanged
    assert from_rows.costs[0, 0] == 1.0
    for clone in (pickle.loads(pickle.dumps(from_rows)), copy.deepcopy(from_rows)):
        np.testing.assert_array_equal(clone.terrain, chars)
        assert not clone.terrain.flags.writeable
    assert repr(from_rows) == "MovingAIMap(<2 x 3 terrain, 4 passable>)"


@pytest.mark.parametrize(
    ("terrain", "error", "message"),
    [
        ("..@", TypeError, "terrain must be rows of characters"),
        (["..@", "T."], ValueError, r"equally long, got lengths \[2, 3\]"),
        (["..@", "T.x"], ValueError, r"terrain\[1, 2\] is 'x', not a MovingAI terrain"),
        ([], ValueError, "at least one cell"),
        (np.array([["..", "@"]]), ValueError, "one character per cell"),
        (np.zeros((2, 2)), TypeError, "one-character str cells, got dtype float64"),
        (np.array(list("..@")), ValueError, "2 dimensions"),
        (np.array([["ü"]]), ValueError, "'ü', not a MovingAI terrain"),
    ],
)
def test_bad_terrain_is_refused_naming_it(terrain: object, error: type, message: str) -> None:
    with pytest.raises(error, match=message):
        MovingAIMap(terrain)  # type: ignore[arg-type]


def test_scenario_lines_in_every_accepted_layout(tmp_path: Path) -> None:
    path = tmp_path / "a.scen"
    path.write_text(
        "version 1.0\r\n\r\n"
        "0\ttiny.map\t3\t2\t0\t0\t2\t1\t2.41421356\r\n"
        "1 tiny.map 3 2 2 1 0 0 2.41421356\n"  # spaces, as some copies have
        "0\tmy map.map\t3\t2\t1\t0\t1\t1\t1\n"  # a name with a space, tab-separated
    )
    problems = read_movingai_scenarios(path)
    assert problems.map_names == ("tiny.map", "tiny.map", "my map.map")
    assert problems.start_cells.tolist() == [[0, 0], [1, 2], [0, 1]]  # (row, col) = (y, x)
    assert problems.goal_cells.tolist() == [[1, 2], [0, 0], [1, 1]]
    assert problems.buckets.tolist() == [0, 1, 0]
    assert problems.optimal_lengths.tolist() == [2.41421356, 2.41421356, 1.0]
    for array in (problems.start_cells, problems.optimal_lengths, problems.map_shapes):
        assert not array.flags.writeable


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (SCEN.split("\n", 1)[1], ":1: '0\\\\ttiny.map|:1: .* expected 'version 1'"),
        (SCEN.replace("version 1", "version 2"), "expected 'version 1'"),
        (SCEN.replace("\t2.41421356", ""), ":2: 8 fields, a problem has 9"),
        (SCEN.replace("\t0\t0\t2", "\t-1\t0\t2"), ":2: start_x '-1' is not a non-negative integer"),
        (SCEN.replace("\t2\t1\t2.4", "\t3\t1\t2.4"), r":2: goal \(x, y\) = \(3, 1\) is outside"),
        (SCEN.replace("2.41421356", "nan"), ":2: optimal_length 'nan' is not a finite number"),
        (SCEN.replace("2.41421356", "-1"), ":2: optimal_length '-1' is not a finite number"),
        (SCEN.replace("map\t3", "map\t0"), ":2: a map of width 0"),
        (TINY, ":1: 'type octile', expected 'version 1'"),
    ],
)
def test_malformed_scenario_files_are_refused_naming_the_line(
    tmp_path: Path, text: str, message: str
) -> None:
    path = tmp_path / "bad.scen"
    path.write_text(text)
    with pytest.raises(ValueError, match=message) as info:
        read_movingai_scenarios(path)
    assert str(path) in str(info.value)


def _scenarios(**changes: object) -> MovingAIScenarios:
    fields: dict[str, object] = {
        "buckets": [0, 1],
        "map_names": ["a.map", "a.map"],
        "map_shapes": [[2, 3], [2, 3]],
        "start_cells": [[0, 0], [1, 2]],
        "goal_cells": [[1, 2], [0, 0]],
        "optimal_lengths": [2.5, 2.5],
    }
    fields.update(changes)
    return MovingAIScenarios(**fields)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("changes", "error", "message"),
    [
        ({"buckets": [0, True]}, TypeError, "buckets must hold integers"),
        ({"buckets": [0.0, 1.0]}, TypeError, "buckets must hold integers, got dtype float64"),
        ({"buckets": [0, 2**70]}, ValueError, "buckets must be at most"),
        ({"buckets": [0, -1]}, ValueError, "buckets must be >= 0, got -1"),
        ({"map_shapes": [[2, 3], [0, 3]]}, ValueError, "map_shapes must be >= 1"),
        ({"start_cells": [[0, 0], [2, 0]]}, ValueError, r"start_cells\[1\] \(2, 0\) is outside"),
        ({"goal_cells": [[1, 2]]}, ValueError, r"goal_cells must have shape \(2, 2\)"),
        ({"map_names": ["a.map", 3]}, TypeError, "map_names must hold str, got int"),
        ({"optimal_lengths": [2.5, np.inf]}, ValueError, r"optimal_lengths\[1\] must be finite"),
        ({"optimal_lengths": [2.5]}, ValueError, "optimal_lengths"),
        ({"start_cells": [[0, 0], [1]]}, ValueError, "start_cells must be a rectangular array"),
    ],
)
def test_bad_scenario_records_are_refused_naming_the_field(
    changes: dict[str, object], error: type, message: str
) -> None:
    with pytest.raises(error, match=message):
        _scenarios(**changes)


def test_scenario_records_copy_their_inputs_and_survive_pickling() -> None:
    starts = np.array([[0, 0], [1, 2]], dtype=np.int32)
    problems = _scenarios(start_cells=starts)
    assert problems.start_cells.dtype == np.int64 and starts.flags.writeable
    starts[0, 0] = 1
    assert problems.start_cells[0, 0] == 0
    clone = pickle.loads(pickle.dumps(problems))
    np.testing.assert_array_equal(clone.goal_cells, problems.goal_cells)
    assert not clone.goal_cells.flags.writeable and len(clone) == 2
    assert len(_scenarios(**{k: [] for k in ("buckets", "map_names", "optimal_lengths")},
                          map_shapes=np.empty((0, 2), int), start_cells=np.empty((0, 2), int),
                          goal_cells=np.empty((0, 2), int))) == 0  # fmt: skip
