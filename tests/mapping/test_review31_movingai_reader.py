"""Review 31 of the MovingAI readers: real variants accepted, hostile files refused cheaply.

The format is movingai.com/benchmarks/formats.html and HOG2's loaders: scenario
lines read as whitespace-separated C++ streams (``version 1.0``, trailing blanks
allowed), map rows character by character with whitespace skipped after each row.
"""

from __future__ import annotations

import tracemalloc
from pathlib import Path

import numpy as np
import pytest
from test_movingai_files import _scenarios  # the valid record, fields changed

from navkit.mapping.io import (
    MovingAIMap,
    read_movingai_map,
    read_movingai_scenarios,
)

TINY = "type octile\nheight 2\nwidth 3\nmap\n..@\nT.S\n"
LINE = "0\ttiny.map\t3\t2\t0\t0\t2\t1\t2.41421356"
SCEN = f"version 1\n{LINE}\n"


def _write(folder: Path, name: str, data: str | bytes) -> Path:
    path = folder / name
    path.write_bytes(data.encode("utf-8") if isinstance(data, str) else data)
    return path


def test_a_tiny_map_claiming_two_gigacells_is_refused_without_allocating_them(
    tmp_path: Path,
) -> None:
    # 46340**2 cells was within the limit then (2**31 - 1); the body read once asked
    # for all of it (read(n) allocates n bytes first): 2.1 GB for a 50-byte file,
    # 6.4 GB for height 2**31 - 1 and width 1. The limit is 2**26 cells since
    # review 44 (test_review44_memcap_movingai_limit.py): the same claims within it.
    claims = [("8192", "8192"), ("67108864", "1"), ("1", "67108864")]
    for height, width in claims:
        text = TINY.replace("height 2", f"height {height}").replace("width 3", f"width {width}")
        path = _write(tmp_path, "claim.map", text)
        tracemalloc.start()
        try:
            with pytest.raises(ValueError, match=r"rows after the 'map' line|than the 1 row of"):
                read_movingai_map(path)
            peak = tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()
        assert peak < 1_000_000, (height, width, peak)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        # Values beyond int64: an OverflowError from NumPy, no file or line named.
        (SCEN.replace("tiny.map\t3", "tiny.map\t" + "9" * 30), r":2: a map of 2 x 9{30} cells"),
        (SCEN.replace("0\ttiny", "9" * 30 + "\ttiny"), r":2: bucket 9{30} is more than"),
        (SCEN.replace("\t3\t2\t", "\t65536\t65536\t"), r":2: a map of 65536 x 65536 cells"),
        # Numbers no C reader takes, or not >= 0: float() read them.
        (SCEN.replace("2.41421356", "1_0"), ":2: optimal_length '1_0' is not a finite number"),
        (SCEN.replace("2.41421356", "-0.0"), ":2: optimal_length '-0.0' is not a finite number"),
        (SCEN.replace("2.41421356", "+2.5"), ":2: optimal_length '\\+2.5' is not a finite"),
        # A map field that names no file.
        (SCEN.replace("tiny.map", ""), ":2: an empty map name"),
        (SCEN.replace("tiny.map", "  "), ":2: an empty map name"),
        (SCEN.replace("tiny.map", "ti\x00ny.map"), ":2: a control character"),
        (SCEN.replace("tiny.map", "ti\x0cny.map"), ":2: a control character"),
        (SCEN.replace("\t", "\x0b"), ":2: a control character"),
    ],
)
def test_scenario_fields_out_of_range_or_not_numbers_are_refused_naming_the_line(
    tmp_path: Path, text: str, message: str
) -> None:
    path = _write(tmp_path, "bad.scen", text)
    with pytest.raises(ValueError, match=message) as info:
        read_movingai_scenarios(path)
    assert str(path) in str(info.value)


@pytest.mark.parametrize(
    "text",
    [
        "\ufeff" + SCEN,  # a UTF-8 byte-order mark, as Windows editors write
        SCEN.replace(LINE, LINE + "\t"),  # a trailing tab
        SCEN.replace(LINE, LINE + " \t "),
        SCEN.replace(LINE, LINE + "\t").replace("\n", "\r\n"),
        SCEN.replace("2.41421356", "2.41421356e0"),  # a C double: exponent allowed
    ],
)
def test_scenario_files_real_tools_write_are_read(tmp_path: Path, text: str) -> None:
    problems = read_movingai_scenarios(_write(tmp_path, "ok.scen", text))
    assert problems.map_names == ("tiny.map",)
    assert problems.start_cells.tolist() == [[0, 0]] and problems.goal_cells.tolist() == [[1, 2]]
    assert problems.optimal_lengths.tolist() == [2.41421356]


@pytest.mark.parametrize(
    "text",
    [
        "\ufeff" + TINY,
        TINY.replace("..@\n", "..@ \n").replace("T.S\n", "T.S\t\n"),  # blanks after rows
        TINY.replace("\n", " \r\n"),
    ],
)
def test_map_files_real_tools_write_are_read(tmp_path: Path, text: str) -> None:
    grid = read_movingai_map(_write(tmp_path, "ok.map", text))
    assert ["".join(row) for row in grid.terrain.tolist()] == ["..@", "T.S"]


def test_a_row_with_a_character_before_its_blanks_is_still_a_wrong_width(
    tmp_path: Path,
) -> None:
    path = _write(tmp_path, "bad.map", TINY.replace("..@\n", "..@. \n"))
    with pytest.raises(ValueError, match=":5: a row of 4 characters, the header's width is 3"):
        read_movingai_map(path)
    path = _write(tmp_path, "bad.map", TINY.replace("T.S\n", "T.\n").replace("\n", "\r\n"))
    with pytest.raises(ValueError, match=":6: a row of 2 characters, the header's width is 3"):
        read_movingai_map(path)


def test_the_terrain_record_takes_object_arrays_and_refuses_cells_that_are_not_str() -> None:
    rows = ["..@", "T.S"]
    chars = np.array([list(row) for row in rows], dtype=object)
    assert MovingAIMap(chars).terrain.tolist() == [list(row) for row in rows]
    assert chars.dtype == object  # the caller's array is not converted in place
    # NumPy made str of the int and of the bytes: the int was reported as terrain
    # '1', the bytes read as '.'.
    with pytest.raises(TypeError, match="terrain must hold str cells, got an element of type int"):
        MovingAIMap([[".", "@"], [".", 1]])
    with pytest.raises(TypeError, match="got an element of type bytes"):
        MovingAIMap([[".", "@"], [".", b"."]])
    with pytest.raises(TypeError, match="got an element of type NoneType"):
        MovingAIMap(np.array([[".", None]], dtype=object))


def test_scenario_records_take_integers_numpy_would_make_floats() -> None:
    # NumPy makes float64 of [0, 2**63] and of int8 mixed with uint64: they were
    # refused as "not integers".
    mixed = _scenarios(buckets=[np.int8(0), np.uint64(7)])
    assert mixed.buckets.tolist() == [0, 7] and mixed.buckets.dtype == np.int64
    with pytest.raises(ValueError, match="buckets must be at most 9223372036854775807"):
        _scenarios(buckets=[0, 2**63])
    with pytest.raises(TypeError, match="buckets must hold integers, got dtype float64"):
        _scenarios(buckets=[0, 1.0])


def test_scenario_records_refuse_empty_names_and_maps_beyond_the_cell_limit() -> None:
    with pytest.raises(ValueError, match=r"map_names\[1\] is empty"):
        _scenarios(map_names=["a.map", ""])
    with pytest.raises(ValueError, match=r"map_shapes\[1\] \(4611686018427387904, 3\) has more"):
        _scenarios(map_shapes=[[2, 3], [2**62, 3]])
    names = _scenarios(map_names=[np.str_("a.map"), "b.map"]).map_names
    assert [type(name) for name in names] == [str, str]
    lengths = _scenarios(optimal_lengths=[-0.0, 2.5]).optimal_lengths
    assert not np.signbit(lengths).any()
