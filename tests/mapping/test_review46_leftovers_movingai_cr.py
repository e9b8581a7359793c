"""MovingAI files whose lines end in CR alone (classic Mac OS) are read (review 46, LEFTOVERS).

HOG2, the benchmark's own code, reads a ``.map`` with ``fscanf`` (whose
``\\n`` directives skip any white space, CR included) and a ``.scen`` with
``>>`` (fields separated by any white space): to it a CR-only file is a
benchmark file like any other. navkit read such a file as one line of the
whole file and refused it with that line's ``\\r``-joined text (or as a line
too long). A file whose first line ends in CR alone is now read with CR as its
line end, one byte for one, so its messages name the file's own lines.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from navkit.mapping.io import (
    MovingAIScenarios,
    read_movingai_map,
    read_movingai_scenarios,
)

_MAP = b"type octile\nheight 3\nwidth 4\nmap\n..@.\nT.GS\nOW..\n"
_SCEN = b"".join(
    [
        b"version 1\n",
        b"0\tt.map\t4\t3\t0\t0\t3\t2\t3.82842712\n",
        b"1\tt.map\t4\t3\t1\t1\t1\t0\t1.00000000\n",
    ]
)
BOM = b"\xef\xbb\xbf"


def _cr(data: bytes) -> bytes:
    return data.replace(b"\r\n", b"\n").replace(b"\n", b"\r")


def _write(tmp_path: Path, name: str, data: bytes) -> Path:
    path = tmp_path / name
    path.write_bytes(data)
    return path


def _scenarios(problems: MovingAIScenarios) -> tuple[Any, ...]:
    arrays = ("buckets", "map_shapes", "start_cells", "goal_cells", "optimal_lengths")
    return (problems.map_names, *(getattr(problems, name).tobytes() for name in arrays))


@pytest.mark.parametrize("prefix", [b"", BOM])
@pytest.mark.parametrize("tail", [b"", b"\r", b"\r\r\r"])
def test_a_cr_only_map_reads_as_its_lf_copy(tmp_path: Path, prefix: bytes, tail: bytes) -> None:
    lf = read_movingai_map(_write(tmp_path, "lf.map", _MAP))
    body = _cr(_MAP).removesuffix(b"\r") + tail
    cr = read_movingai_map(_write(tmp_path, "cr.map", prefix + body))
    assert cr.terrain.tobytes() == lf.terrain.tobytes()
    assert cr.terrain.tolist()[1] == ["T", ".", "G", "S"]


@pytest.mark.parametrize("prefix", [b"", BOM])
def test_a_cr_only_scenario_file_reads_as_its_lf_copy(tmp_path: Path, prefix: bytes) -> None:
    lf = read_movingai_scenarios(_write(tmp_path, "lf.scen", _SCEN))
    cr = read_movingai_scenarios(_write(tmp_path, "cr.scen", prefix + _cr(_SCEN)))
    assert _scenarios(cr) == _scenarios(lf)
    assert cr.start_cells.tolist() == [[0, 0], [1, 1]]


def test_messages_name_the_cr_only_files_own_lines(tmp_path: Path) -> None:
    short_row = _cr(_MAP).replace(b"T.GS", b"T.G")
    with pytest.raises(ValueError, match=r"cr\.map:6: a row of 3 characters, the header's width"):
        read_movingai_map(_write(tmp_path, "cr.map", short_row))
    bad = _cr(_SCEN).replace(b"1\tt.map\t4\t3\t1\t1\t1\t0", b"1\tt.map\t4\t3\t1\t9\t1\t0")
    with pytest.raises(ValueError, match=r"cr\.scen:3: start \(x, y\) = \(1, 9\) is outside"):
        read_movingai_scenarios(_write(tmp_path, "cr.scen", bad))
    with pytest.raises(ValueError, match=r"cr\.scen:1: 'version 2', expected 'version 1'"):
        read_movingai_scenarios(_write(tmp_path, "cr.scen", b"version 2\r" + _cr(_SCEN)[10:]))


def test_a_cr_only_scenario_cut_inside_its_last_length_is_still_refused(tmp_path: Path) -> None:
    cut = _cr(_SCEN).removesuffix(b"00000000\r")
    with pytest.raises(ValueError, match=r"cr\.scen:3: the file ends inside this line"):
        read_movingai_scenarios(_write(tmp_path, "cr.scen", cut))


def test_crlf_and_a_cr_inside_an_lf_file_read_as_before(tmp_path: Path) -> None:
    # The first line's end decides: CRLF files are not CR-only files.
    crlf = _MAP.replace(b"\n", b"\r\n")
    assert read_movingai_map(_write(tmp_path, "crlf.map", crlf)).shape == (3, 4)
    trailing = _MAP.replace(b"..@.\n", b"..@.\r\n")
    assert read_movingai_map(_write(tmp_path, "t.map", trailing)).shape == (3, 4)


@pytest.mark.parametrize(
    ("folder", "name"),
    [("room", "8room_000"), ("dao", "arena")],
)
def test_real_benchmark_files_with_cr_line_ends(
    shared_data: Path, tmp_path: Path, folder: str, name: str
) -> None:
    # Files of many lines and well over the 4096-byte longest line: read whole.
    source = shared_data / "movingai-grid-benchmarks" / folder
    lf_map = read_movingai_map(source / f"{name}.map")
    cr_map = read_movingai_map(
        _write(tmp_path, f"{name}.map", _cr((source / f"{name}.map").read_bytes()))
    )
    assert cr_map.terrain.tobytes() == lf_map.terrain.tobytes()
    lf_scen = read_movingai_scenarios(source / f"{name}.map.scen")
    cr_scen = read_movingai_scenarios(
        _write(tmp_path, f"{name}.map.scen", _cr((source / f"{name}.map.scen").read_bytes()))
    )
    assert _scenarios(cr_scen) == _scenarios(lf_scen)
    assert len(cr_scen.map_names) > 100
