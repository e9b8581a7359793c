"""Fuzz specs of the MovingAI readers and records (``navkit.mapping.io``), registered on
import by ``fuzz_specs.py``."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from fuzz_engine import Array, FileKind, SequenceOf, call, spec

from navkit.mapping.io import (
    MovingAIMap,
    MovingAIScenarios,
    read_movingai_map,
    read_movingai_scenarios,
)

A = np.array
IO = "navkit.mapping.io."
_MAP = "type octile\nheight 2\nwidth 3\nmap\n..@\nT.S\n"
_SCEN = "version 1\n0\ttiny.map\t3\t2\t0\t0\t1\t1\t1.41421356\n"


def _file(folder: Path, name: str, text: str | bytes) -> Path:
    path = folder / name
    path.write_bytes(text.encode() if isinstance(text, str) else text)
    return path


_INF_OK = "costs is inf on the impassable cells (documented)"
MAP_FILES = FileKind(
    files=[
        ("a row too short", lambda d: _file(d, "a.map", _MAP.replace("T.S", "T."))),
        ("a row missing", lambda d: _file(d, "a.map", _MAP.replace("T.S\n", ""))),
        ("a row too many", lambda d: _file(d, "a.map", _MAP + "...\n")),
        ("height 0", lambda d: _file(d, "a.map", _MAP.replace("height 2", "height 0"))),
        ("height -2", lambda d: _file(d, "a.map", _MAP.replace("height 2", "height -2"))),
        ("width 1e9", lambda d: _file(d, "a.map", _MAP.replace("width 3", "width 1000000000"))),
        ("no type", lambda d: _file(d, "a.map", _MAP.replace("type octile\n", ""))),
        ("type tile", lambda d: _file(d, "a.map", _MAP.replace("octile", "tile"))),
        ("a second height", lambda d: _file(d, "a.map", "height 2\n" + _MAP)),
        ("no map line", lambda d: _file(d, "a.map", _MAP.replace("map\n", ""))),
        ("a digit in a row", lambda d: _file(d, "a.map", _MAP.replace("..@", ".1@"))),
        ("a byte not ASCII", lambda d: _file(d, "a.map", _MAP.encode().replace(b"T", b"\xff"))),
        ("a scenario file", lambda d: _file(d, "a.map", _SCEN)),
        (
            "2**31 - 1 rows claimed",
            lambda d: _file(d, "a.map", _MAP.replace("height 2", "height 2147483647")),
        ),
    ]
)
SCEN_FILES = FileKind(
    files=[
        ("no version", lambda d: _file(d, "a.scen", _SCEN.split("\n", 1)[1])),
        ("version 2", lambda d: _file(d, "a.scen", _SCEN.replace("version 1", "version 2"))),
        ("8 fields", lambda d: _file(d, "a.scen", _SCEN.replace("\t1.41421356", ""))),
        ("a negative x", lambda d: _file(d, "a.scen", _SCEN.replace("\t0\t0\t1", "\t-1\t0\t1"))),
        (
            "a goal outside",
            lambda d: _file(d, "a.scen", _SCEN.replace("\t1\t1\t1.4", "\t3\t1\t1.4")),
        ),
        ("a NaN length", lambda d: _file(d, "a.scen", _SCEN.replace("1.41421356", "nan"))),
        ("width 0", lambda d: _file(d, "a.scen", _SCEN.replace("map\t3", "map\t0"))),
        ("a map file", lambda d: _file(d, "a.scen", _MAP)),
        (
            "a bucket of 30 digits",
            lambda d: _file(d, "a.scen", _SCEN.replace("1\n0", "1\n" + "9" * 30)),
        ),
        ("a length 1_0", lambda d: _file(d, "a.scen", _SCEN.replace("1.41421356", "1_0"))),
        ("no map name", lambda d: _file(d, "a.scen", _SCEN.replace("tiny.map", ""))),
    ]
)

spec(
    IO + "read_movingai_map",
    lambda c: call(read_movingai_map, _file(c.tmp, "t.map", _MAP)),
    kinds={"path": MAP_FILES},
    inf_ok=_INF_OK,
)
spec(
    IO + "read_movingai_scenarios",
    lambda c: call(read_movingai_scenarios, _file(c.tmp, "t.scen", _SCEN)),
    kinds={"path": SCEN_FILES},
)
spec(
    IO + "MovingAIMap",
    lambda c: call(MovingAIMap, ["..@", "T.S"]),
    kinds={"terrain": SequenceOf(str)},
    inf_ok=_INF_OK,
)
spec(
    IO + "MovingAIScenarios",
    lambda c: call(
        MovingAIScenarios, A([0]), ("tiny.map",), A([[2, 3]]), A([[0, 0]]), A([[1, 1]]), A([1.5])
    ),
    kinds={
        "buckets": Array(),
        "map_names": SequenceOf(str),
        "map_shapes": Array(),
        "start_cells": Array(),
        "goal_cells": Array(),
        "optimal_lengths": Array(),
    },
)
