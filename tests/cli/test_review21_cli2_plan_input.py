"""``navkit plan``'s points, abbreviations, standard output errors and ``--json`` (session 25).

Points are read as the table prints them (``(-2, -0.5)``) as well as ``X,Y``;
an abbreviated ``--goal`` takes a negative point as the full option does; a
failed write to standard output says so; ``--json FILE`` holds the plan.
"""

from __future__ import annotations

import errno
import io
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.cli import main
from navkit.cli._parser import build_parser, join_negative_points
from navkit.mapping import OccupancyGrid


def parsed(argv: list[str]) -> tuple[tuple[float, float], tuple[float, float]]:
    args = build_parser().parse_args(join_negative_points(["plan", "m.yaml", *argv]))
    return args.start, args.goal


def usage_error(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    """The last line of a usage error (exit code 2, no traceback)."""
    assert main(["plan", "m.yaml", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("usage: navkit") and "Traceback" not in err
    return err.strip().splitlines()[-1]


finite = st.floats(allow_nan=False, allow_infinity=False, width=64)


@given(x=finite, y=finite, spelling=st.sampled_from(["({x}, {y})", "({x},{y})", " ( {x} , {y} ) ",
                                                     "{x}, {y}", "{x},{y}"]))  # fmt: skip
def test_a_point_as_the_table_prints_it_is_read(x: float, y: float, spelling: str) -> None:
    text = spelling.format(x=repr(x), y=repr(y))
    start, goal = parsed(["--start", text, "--goal", text])
    assert start == goal == (x, y)


@pytest.mark.parametrize(
    "text", ["(1,2", "1,2)", "((1,2))", "(1,2,3)", "()", "(1;2)", "[1,2]", "(1 2)", "(,)", "1,2,"]
)
def test_other_shapes_are_refused_as_before(
    text: str, capsys: pytest.CaptureFixture[str]
) -> None:
    line = usage_error(["--start", text, "--goal", "1,1"], capsys)
    assert line.endswith(f"argument --start: expected X,Y in metres, got {text!r}")


def test_a_parenthesised_infinity_is_refused_as_infinite(
    capsys: pytest.CaptureFixture[str],
) -> None:
    line = usage_error(["--start", "(inf, 0)", "--goal", "1,1"], capsys)
    assert line.endswith("argument --start: X,Y must be finite, got '(inf, 0)'")


@pytest.mark.parametrize("option", ["--g", "--go", "--goa", "--goal"])
@pytest.mark.parametrize("point", ["-1,2", "-.5,-2", "(-1, 2)", "( -1,2)"])
def test_an_abbreviated_goal_takes_a_negative_point(option: str, point: str) -> None:
    full = parsed(["--start", "0,0", "--goal", point])
    assert parsed(["--start", "0,0", option, point]) == full
    assert parsed(["--start", "0,0", f"{option}={point}"]) == full


@pytest.mark.parametrize("option", ["--s", "--st", "--sta", "--star"])
def test_an_ambiguous_start_is_ambiguous_before_any_point(
    option: str, capsys: pytest.CaptureFixture[str]
) -> None:
    # --start's abbreviations also abbreviate --start-tolerance: argparse refuses
    # them whatever follows, a negative point now included (it said "expected one
    # argument" for the negative one alone).
    for point in ("1,2", "-1,2"):
        line = usage_error(["--goal", "0,0", option, point], capsys)
        assert "ambiguous option: " + option in line
        assert "--start, --start-tolerance" in line


def test_nothing_after_a_double_dash_is_joined() -> None:
    argv = ["plan", "m.yaml", "--go", "-1,2", "--", "--go", "-1,2"]
    assert join_negative_points(argv) == ["plan", "m.yaml", "--go=-1,2", "--", "--go", "-1,2"]
    # Numbers are joined since session 26, file names since session 27.
    assert join_negative_points(["run", "x", "--plot", "-1.png", "--seed", "-1", "--", "-2"]) == [
        "run", "x", "--plot=-1.png", "--seed=-1", "--", "-2"]  # fmt: skip


class _Full(io.StringIO):
    """Standard output on a full disk: every write fails as /dev/full's does."""

    def write(self, text: str) -> int:
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


def test_a_failed_write_to_standard_output_names_it(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setattr(sys, "stdout", _Full())
    assert main(["list"]) == 1
    err = capsys.readouterr().err
    assert err == f"navkit: error: standard output: {os.strerror(errno.ENOSPC)}\n"


def test_a_closed_pipe_still_ends_quietly(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    class Closed(io.StringIO):
        def write(self, text: str) -> int:
            raise BrokenPipeError(errno.EPIPE, os.strerror(errno.EPIPE))

        def fileno(self) -> int:
            raise io.UnsupportedOperation("no file")  # the devnull swap is skipped

    monkeypatch.setattr(sys, "stdout", Closed())
    assert main(["list"]) == 141
    assert capsys.readouterr().err == ""


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full")
def test_standard_output_on_dev_full_in_a_real_process() -> None:
    env = dict(os.environ)  # keeps NUMBA_CACHE_DIR
    with open("/dev/full", "w") as full:
        done = subprocess.run([sys.executable, "-m", "navkit", "list"], stdout=full,
                              stderr=subprocess.PIPE, text=True, env=env, timeout=120,
                              check=False)  # fmt: skip
    assert done.returncode == 1
    assert done.stderr == "navkit: error: standard output: No space left on device\n"


@pytest.fixture
def corridor(tmp_path: Path) -> Path:
    """A 3 x 2 m map with a wall leaving a gap at the top."""
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:14, 14:16] = True
    OccupancyGrid.from_occupancy(occupied, resolution=0.1).save(tmp_path / "corridor.yaml")
    return tmp_path / "corridor.yaml"


def table_value(out: str, name: str) -> str:
    return next(line for line in out.splitlines() if line.strip().startswith(name)).split()[-1]


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
def test_plan_json_holds_the_plan_the_table_prints(
    corridor: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str], planner: str
) -> None:
    target = tmp_path / "plan.json"
    argv = ["plan", str(corridor), "--start", "(0.55, 0.55)", "--goal", "2.55,0.55",
            "--planner", planner, "--radius", "0.1", "--json", str(target), "--quiet"]  # fmt: skip
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert f"wrote {target}" in out
    data = json.loads(target.read_text(encoding="utf-8"))
    assert data["planner"] == planner and data["map"] == str(corridor)
    assert data["start"] == [0.55, 0.55] and data["goal"] == [2.55, 0.55]
    assert data["robot_radius"] == 0.1 and data["start_tolerance"] == 0.0
    points = np.array(data["points"])
    assert points.shape[1] == 2 and len(points) == int(table_value(out, "path points"))
    # MapPlanner's paths begin and end at the points given (cell centres here).
    assert np.allclose(points[0], data["start"]) and np.allclose(points[-1], data["goal"])
    # The path rounds the wall's top (y >= 1.4 + radius), and its length is its points'.
    assert points[:, 1].max() > 1.4
    length = float(np.hypot(*np.diff(points, axis=0).T).sum())
    assert math.isclose(data["length"], length, rel_tol=1e-9)
    assert math.isclose(data["length"], float(table_value(out, "length (m)")), rel_tol=1e-3)
    assert data["cost"] >= data["length"] - 1e-9
    label = "cells expanded" if planner == "astar" else "nodes expanded"
    assert data["cells_expanded"] == int(table_value(out, label))
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []


@pytest.mark.parametrize(
    ("json_name", "words"),
    [
        ("-", "'-' (standard output) is not supported"),
        ("missing/plan.json", "folder"),
        ("corridor.yaml", "is the map's YAML"),
        ("corridor.pgm", "is the map's image"),
        ("plan.png", "--json and --plot name the same file"),
    ],
)
def test_plan_json_refusals_leave_every_file_as_it_was(
    corridor: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str], json_name: str,
    words: str, monkeypatch: pytest.MonkeyPatch
) -> None:  # fmt: skip
    monkeypatch.chdir(tmp_path)
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}
    argv = ["plan", "corridor.yaml", "--start", "0.55,0.55", "--goal", "2.55,0.55",
            "--json", json_name, "--plot", "plan.png", "--quiet"]  # fmt: skip
    assert main(argv) == 1
    captured = capsys.readouterr()
    assert captured.out == ""
    line = captured.err.strip()
    assert line.startswith("navkit: error: ") and "\n" not in line and words in line
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


def test_plan_help_and_docs_name_the_new_spellings(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["plan", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "--json FILE" in text and "(X, Y)" in text
