"""MovingAI readers on damaged and unusual copies of the real benchmark files (review 46).

Nothing follows a ``.scen`` line's optimal length: a file cut inside its last
line's length (``38.21320`` left of ``38.21320344``, or ``3``) read silently as
a shorter length. Such a last line, without its line end and with fewer
decimals than the file prints every other length with, is now refused, naming
the file and line. Maps cut anywhere or with a flipped bit are refused; line
ends (LF, CRLF) and a byte-order mark change nothing.
"""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import pytest

from navkit.mapping.io import (
    MovingAIMap,
    MovingAIScenarios,
    read_movingai_map,
    read_movingai_scenarios,
)
from reader_outcomes import outcome

SETS = "movingai-grid-benchmarks"
BOM = b"\xef\xbb\xbf"


def _scenarios(problems: MovingAIScenarios) -> tuple[Any, ...]:
    arrays = ("buckets", "map_shapes", "start_cells", "goal_cells", "optimal_lengths")
    return (problems.map_names, *(getattr(problems, name).tobytes() for name in arrays))


def _terrain(grid: MovingAIMap) -> bytes:
    return grid.terrain.tobytes()


# ------------------------------------------------------------------ scenario files
def _cut_last_lengths(text: bytes, lines: int) -> list[tuple[int, bytes]]:
    """(line number, file cut there) for every cut inside the length of each of the
    first ``lines`` problem lines."""
    cuts = []
    start = text.index(b"\n") + 1
    for number in range(2, lines + 2):
        end = text.index(b"\n", start)
        tab = text.rindex(b"\t", start, end)
        cuts.extend((number, text[:offset]) for offset in range(tab + 2, end))
        start = end + 1
    return cuts


@pytest.mark.parametrize("name", ["dao/arena.map.scen", "street/Berlin_0_256.map.scen"])
def test_a_file_cut_inside_its_last_optimal_length_is_refused(
    shared_data: Path, tmp_path: Path, name: str
) -> None:
    text = (shared_data / SETS / name).read_bytes()
    path = tmp_path / "cut.map.scen"
    for number, cut in _cut_last_lengths(text, 6):
        if number == 2:
            continue  # the first problem: no other length to compare with
        path.write_bytes(cut)
        with pytest.raises(ValueError, match="it looks truncated") as info:
            read_movingai_scenarios(path)
        assert str(info.value).startswith(f"{path}:{number}: the file ends inside this line")


def test_whole_last_lines_without_a_line_end_still_read(shared_data: Path, tmp_path: Path) -> None:
    text = (shared_data / SETS / "dao/arena.map.scen").read_bytes()
    full = _scenarios(read_movingai_scenarios(shared_data / SETS / "dao/arena.map.scen"))
    path = tmp_path / "arena.map.scen"
    for tail in (b"", b"\r", b" ", b"\t"):
        assert outcome(read_movingai_scenarios, _scenarios, path, text[:-1] + tail) == full
    # One problem: no other line tells how lengths are printed.
    first = text[: text.index(b"\n", text.index(b"\n") + 1)]
    path.write_bytes(first[:-3])
    assert len(read_movingai_scenarios(path)) == 1
    # Lengths printed with varying decimals (%g): not checked.
    lines = [b"version 1", b"0\ta.map\t9\t9\t0\t0\t1\t1\t1.41421", b"0\ta.map\t9\t9\t0\t0\t1\t0\t1",
             b"2\ta.map\t9\t9\t0\t0\t8\t8\t11.3137"]  # fmt: skip
    path.write_bytes(b"\n".join(lines))
    assert read_movingai_scenarios(path).optimal_lengths.tolist() == [1.41421, 1.0, 11.3137]
    # Printed alike (%.8f): the last, with other decimals, is refused.
    path.write_bytes(b"\n".join([*lines[:2], b"0\ta.map\t9\t9\t0\t0\t1\t0\t1.0000"]))
    with pytest.raises(ValueError, match=r":3: the file ends inside this line, its .* '1.0000'"):
        read_movingai_scenarios(path)


@pytest.mark.parametrize("name", ["dao/arena.map.scen", "street/Boston_0_256.map.scen"])
def test_scenario_files_cut_flipped_or_recoded(
    shared_data: Path, tmp_path: Path, name: str
) -> None:
    """Every cut gives the problems of its whole lines or a ValueError naming the file; line
    ends and a byte-order mark change nothing."""
    text = (shared_data / SETS / name).read_bytes()
    full = _scenarios(read_movingai_scenarios(shared_data / SETS / name))
    path = tmp_path / "damaged.map.scen"
    for variant in (text.replace(b"\n", b"\r\n"), BOM + text, BOM + text.replace(b"\n", b"\r\n")):
        assert outcome(read_movingai_scenarios, _scenarios, path, variant) == full
    ends = [i + 1 for i, byte in enumerate(text) if byte == ord("\n")]
    rng = random.Random(f"46{name}")
    for offset in rng.sample(range(len(text)), 150):
        got = outcome(read_movingai_scenarios, _scenarios, path, text[:offset])
        if got is not None:
            # The lines before the cut, or the cut line if only its line end is missing.
            whole = [end for end in ends if end <= offset + 1]
            assert outcome(read_movingai_scenarios, _scenarios, path, text[: whole[-1]]) == got
    for offset in rng.sample(range(len(text)), 100):
        flipped = bytearray(text)
        flipped[offset] ^= 1 << rng.randrange(8)
        outcome(read_movingai_scenarios, _scenarios, path, bytes(flipped))  # no other error


# ------------------------------------------------------------------ map files
@pytest.mark.parametrize(
    "name", ["dao/arena.map", "street/Berlin_0_256.map", "street/Berlin_0_512.map"]
)
def test_maps_cut_or_flipped_are_refused_and_line_ends_change_nothing(
    shared_data: Path, tmp_path: Path, name: str
) -> None:
    text = (shared_data / SETS / name).read_bytes()
    full = _terrain(read_movingai_map(shared_data / SETS / name))
    path = tmp_path / "damaged.map"
    lf = text.replace(b"\r\n", b"\n")
    for variant in (lf, lf.replace(b"\n", b"\r\n"), BOM + text, lf + b"\n\n \n"):
        assert outcome(read_movingai_map, _terrain, path, variant) == full
    rng = random.Random(f"46{name}")
    body = lf.rstrip(b"\n")
    for offset in rng.sample(range(len(body)), 40):
        assert outcome(read_movingai_map, _terrain, path, body[:offset]) is None, offset
    for offset in rng.sample(range(len(lf)), 40):
        flipped = bytearray(lf)
        flipped[offset] ^= 1 << rng.randrange(8)
        # No character of these maps ('.', '@', 'T') is one bit from another terrain
        # character: every flip (in a row, a line end or the header) is refused.
        assert outcome(read_movingai_map, _terrain, path, bytes(flipped)) is None, offset


def test_huge_declared_sizes_are_refused_before_reading(tmp_path: Path) -> None:
    path = tmp_path / "huge.map"
    path.write_bytes(b"type octile\nheight 1000000000\nwidth 1000000000\nmap\n..\n")
    with pytest.raises(ValueError, match=r"huge.map: 1000000000 x 1000000000 cells, more than"):
        read_movingai_map(path)
    path.write_bytes(b"type octile\nheight 8192\nwidth 8192\nmap\n..\n")
    with pytest.raises(ValueError, match=r"huge.map: 1 row after the 'map' line"):
        read_movingai_map(path)


@pytest.mark.parametrize("digits", [310, 400, 4000])
def test_sizes_of_hundreds_of_digits_are_refused_naming_the_file(
    tmp_path: Path, digits: int
) -> None:
    """A header line holds 4096 bytes: 4.0 x height x width overflowed a float, and the
    message's size in bytes raised OverflowError."""
    path = tmp_path / "huge.map"
    size = "9" * digits
    path.write_bytes(f"type octile\nheight {size}\nwidth 7\nmap\n..\n".encode())
    with pytest.raises(ValueError, match=rf"^{path}: 999999\.\.\. \({digits} digits\) x 7 cells"):
        read_movingai_map(path)
    scenarios = tmp_path / "huge.map.scen"
    scenarios.write_bytes(f"version 1\n{size}\ta.map\t3\t3\t0\t0\t1\t1\t1.0\n".encode())
    with pytest.raises(
        ValueError, match=rf"^{scenarios}:2: bucket 999999\.\.\. \({digits} digits\)"
    ):
        read_movingai_scenarios(scenarios)
