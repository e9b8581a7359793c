"""The MovingAI readers give the same answer whatever a file's line ends (review 46, HYPO7).

LEFTOVERS made CR-only files (classic Mac OS) readable, with messages naming
the file's own lines; the readers took LF and CRLF files before. Here the
same random file, valid or damaged within its lines (a character changed,
dropped or added, a line dropped or repeated, the file cut inside a line),
is written with each of the three line ends, with and without a last line
end and a UTF-8 byte-order mark: the three read alike, or are refused with
the same message (the file's name aside) - same terrain, same problems bit
for bit, same line numbers.
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping.io import read_movingai_map, read_movingai_scenarios
from navkit.mapping.io._movingai import TERRAIN

_ENDS = (b"\n", b"\r\n", b"\r")
_BOM = b"\xef\xbb\xbf"


@st.composite
def _map_lines(draw: st.DrawFn) -> list[bytes]:
    height, width = draw(st.integers(1, 8)), draw(st.integers(1, 8))
    header = [b"type octile", b"height %d" % height, b"width %d" % width]
    header = draw(st.permutations(header))
    blanks = st.sampled_from([b"", b" ", b"\t", b"  \t"])
    rows = [
        "".join(draw(st.lists(st.sampled_from(TERRAIN), min_size=width, max_size=width))).encode()
        + draw(blanks)
        for _ in range(height)
    ]
    tail = draw(st.lists(blanks, max_size=2))  # blank lines after the rows
    return [*header, b"map", *rows, *tail]


@st.composite
def _scenario_lines(draw: st.DrawFn) -> list[bytes]:
    lines = [draw(st.sampled_from([b"version 1", b"version 1.0", b"version  1 "]))]
    sep = draw(st.sampled_from([b"\t", b" "]))
    decimals = draw(st.sampled_from([8, 8, 8, 3, 0]))
    for _ in range(draw(st.integers(1, 5))):
        width, height = draw(st.integers(1, 600)), draw(st.integers(1, 600))
        cells = [draw(st.integers(0, n - 1)) for n in (width, height, width, height)]
        length = draw(st.floats(0, 2000, allow_nan=False))
        name = draw(st.sampled_from([b"a.map", b"maps/dao/arena.map", b"x-1_2.map"]))
        fields = [b"%d" % draw(st.integers(0, 99)), name, b"%d" % width, b"%d" % height]
        fields += [b"%d" % c for c in cells]
        fields.append(b"%.*f" % (decimals, length))
        lines.append(sep.join(fields))
        if draw(st.booleans()):
            lines.append(draw(st.sampled_from([b"", b" ", b"\t"])))  # a blank line
    return lines


_NOISE = st.sampled_from([*b"0123456789.@TGSOW -\t\xe9eE", 0x07])


@st.composite
def _damaged(draw: st.DrawFn, lines: list[bytes]) -> list[bytes]:
    """``lines`` changed inside their text (never a line end added or taken away)."""
    lines = list(lines)
    for _ in range(draw(st.integers(0, 2))):
        i = draw(st.integers(0, len(lines) - 1))
        line = lines[i]
        kind = draw(st.sampled_from(["set", "drop", "insert", "line out", "line twice"]))
        at = draw(st.integers(0, len(line)))
        if kind == "set" and line:
            at = min(at, len(line) - 1)
            lines[i] = line[:at] + bytes([draw(_NOISE)]) + line[at + 1 :]
        elif kind == "drop" and line:
            at = min(at, len(line) - 1)
            lines[i] = line[:at] + line[at + 1 :]
        elif kind == "insert":
            lines[i] = line[:at] + bytes([draw(_NOISE)]) + line[at:]
        elif kind == "line out" and len(lines) > 1:
            del lines[i]
        elif kind == "line twice":
            lines.insert(i, line)
    return lines


def _outcome(reader: Any, data: bytes, folder: Path, name: str) -> tuple[str, Any]:
    path = folder / name
    path.write_bytes(data)
    try:
        result = reader(path)
    except ValueError as exc:
        return "refused", str(exc).replace(str(path), "FILE")
    if reader is read_movingai_map:
        return "read", result.terrain.tobytes()
    arrays = ("buckets", "map_shapes", "start_cells", "goal_cells", "optimal_lengths")
    return "read", (result.map_names, *(getattr(result, a).tobytes() for a in arrays))


def _same_for_every_line_end(
    reader: Any, lines: list[bytes], last_end: bool, bom: bool, cut: int | None
) -> tuple[str, Any]:
    outcomes = []
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        for k, end in enumerate(_ENDS):
            data = end.join(lines) + (end if last_end else b"")
            if cut is not None:
                # Cut inside the last line's text (the same text for every line end).
                body = end.join(lines[:-1]) + (end if len(lines) > 1 else b"")
                data = body + lines[-1][: cut % (len(lines[-1]) + 1)]
            outcomes.append(_outcome(reader, (_BOM if bom else b"") + data, folder, f"f{k}"))
    assert outcomes[1] == outcomes[0], (outcomes, lines)
    assert outcomes[2] == outcomes[0], (outcomes, lines)
    return outcomes[0]


_CUT = st.one_of(st.none(), st.integers(0, 60))


@settings(max_examples=100, deadline=None)
@given(lines=_map_lines(), last_end=st.booleans(), bom=st.booleans())
def test_a_valid_map_reads_alike_with_any_line_end(
    lines: list[bytes], last_end: bool, bom: bool
) -> None:
    kind, _ = _same_for_every_line_end(read_movingai_map, lines, last_end, bom, None)
    assert kind == "read"


@settings(max_examples=150, deadline=None)
@given(data=st.data(), last_end=st.booleans(), bom=st.booleans(), cut=_CUT)
def test_a_damaged_map_is_read_or_refused_alike_with_any_line_end(
    data: st.DataObject, last_end: bool, bom: bool, cut: int | None
) -> None:
    lines = data.draw(_damaged(data.draw(_map_lines())))
    _same_for_every_line_end(read_movingai_map, lines, last_end, bom, cut)


@settings(max_examples=100, deadline=None)
@given(lines=_scenario_lines(), last_end=st.booleans(), bom=st.booleans())
def test_valid_scenarios_read_alike_with_any_line_end(
    lines: list[bytes], last_end: bool, bom: bool
) -> None:
    kind, _ = _same_for_every_line_end(read_movingai_scenarios, lines, last_end, bom, None)
    assert kind == "read"


@settings(max_examples=150, deadline=None)
@given(data=st.data(), last_end=st.booleans(), bom=st.booleans(), cut=_CUT)
def test_damaged_scenarios_are_read_or_refused_alike_with_any_line_end(
    data: st.DataObject, last_end: bool, bom: bool, cut: int | None
) -> None:
    lines = data.draw(_damaged(data.draw(_scenario_lines())))
    _same_for_every_line_end(read_movingai_scenarios, lines, last_end, bom, cut)


def test_the_line_ends_are_really_written() -> None:
    # The comparison above would pass for readers that all fail alike: one of each read.
    lines = [b"version 1", b"0\ta.map\t4\t3\t0\t0\t3\t2\t3.82842712"]
    kind, problems = _same_for_every_line_end(read_movingai_scenarios, lines, True, False, None)
    assert kind == "read"
    assert list(problems[0]) == ["a.map"]
    assert np.frombuffer(problems[4], dtype=np.int64).tolist() == [2, 3]
