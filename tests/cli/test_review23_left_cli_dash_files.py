"""Leftovers of the command line (session 27): file names beginning with ``-``, and abbreviations.

``navkit plan ... --plot -x.png`` said "expected one argument" (argparse
takes a word beginning with ``-`` for an option unless it is a plain negative
number); ``./-x.png`` or ``--plot=-x.png`` worked. Every option taking one
value (a file, a name, a point, a number) now takes such a word, as a GNU
program's option takes its next word. An ambiguous abbreviation before a dash
value was reported in the joined form (``--st=-1,0``); it is reported as typed.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.cli import main
from navkit.cli._parser import build_parser, join_negative_points
from navkit.mapping import OccupancyGrid


def usage_error(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    """The last line of a usage error (exit code 2, no traceback)."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("usage: navkit") and "Traceback" not in err
    return err.strip().splitlines()[-1]


def parse(argv: list[str]) -> dict[str, object]:
    """``argv`` parsed as ``navkit`` parses it."""
    parser = build_parser(["demo", "omni-apf"])
    return vars(parser.parse_args(join_negative_points(argv, parser=parser)))


PLAN = ["plan", "m.yaml", "--start", "0,0", "--goal", "1,1"]

# (command line before the option, option, the attribute it sets)
FILE_OPTIONS = [
    (PLAN, "--plot", "plot"),
    (PLAN, "--json", "json"),
    (["run", "omni-apf"], "--plot", "plot"),
    (["run", "omni-apf"], "--animate", "animate"),
    (["run", "omni-apf"], "--json", "json"),
    (["run", "omni-apf"], "--data", "data"),
    (["run", "omni-apf"], "--scheduler", "scheduler"),
    (["demo"], "--plot", "plot"),
    (["demo"], "--json", "json"),
    (["demo"], "--data", "data"),
]

dash_names = st.text(
    st.characters(codec="utf-8", exclude_characters="\x00"), min_size=1, max_size=12
).map(lambda tail: "-" + tail).filter(lambda name: name != "-h" and not name.startswith("--"))


@pytest.mark.parametrize(("before", "option", "attribute"), FILE_OPTIONS)
@given(name=dash_names)
def test_a_file_option_takes_a_name_beginning_with_a_dash(
    before: list[str], option: str, attribute: str, name: str
) -> None:
    # As it takes the same name after "=", and as argparse took "./-x.png".
    assert parse([*before, option, name])[attribute] == name
    assert parse([*before, f"{option}={name}"])[attribute] == name


@pytest.mark.parametrize(("before", "option", "attribute"), FILE_OPTIONS)
def test_an_abbreviated_file_option_takes_it_too(
    before: list[str], option: str, attribute: str
) -> None:
    abbreviation = option[:4] if option not in ("--plot", "--scheduler") else option[:5]
    assert parse([*before, abbreviation, "-x"])[attribute] == "-x"


def test_plan_writes_the_json_file_named(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    occupied = np.zeros((10, 12), dtype=bool)
    occupied[:6, 6] = True
    OccupancyGrid.from_occupancy(occupied, resolution=0.1).save(tmp_path / "m.yaml")
    monkeypatch.chdir(tmp_path)
    argv = ["plan", "m.yaml", "--start", "0.15,0.15", "--goal", "1.05,0.15", "--quiet"]
    assert main([*argv, "--json", "-plan.json"]) == 0
    assert capsys.readouterr().err == ""
    data = json.loads((tmp_path / "-plan.json").read_text(encoding="utf-8"))
    assert data["start"] == [0.15, 0.15] and data["goal"] == [1.05, 0.15]
    # "-" alone is still standard output's name, refused before planning.
    assert main([*argv, "--json", "-"]) == 1
    assert "--json" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        ([*PLAN, "--planner", "-x"], "argument --planner: invalid choice: '-x'"),
        (["demo", "--map", "-willow"], "argument --map: invalid choice: '-willow'"),
        (["warmup", "--only", "-astar"], "argument --only: invalid choice: '-astar'"),
    ],
)  # fmt: skip
def test_a_name_option_names_a_dash_value_as_an_invalid_choice(
    argv: list[str], words: str, capsys: pytest.CaptureFixture[str]
) -> None:
    # Not "expected one argument", which said nothing of the word given.
    assert words in usage_error(argv, capsys)


@pytest.mark.parametrize(
    ("argv", "typed"),
    [
        (["plan", "m.yaml", "--goal", "0,0", "--st", "-1,0"], "--st"),
        (["plan", "m.yaml", "--goal", "0,0", "--sta", "-inf,0"], "--sta"),
        ([*PLAN, "--pl", "-x.png"], "--pl"),
        (["run", "omni-apf", "--s", "-1"], "--s"),
    ],
)  # fmt: skip
def test_an_ambiguous_abbreviation_is_named_as_typed(
    argv: list[str], typed: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert join_negative_points(argv) == argv
    line = usage_error(argv, capsys)
    assert f"ambiguous option: {typed} could match " in line
    assert "=" not in line


def test_an_abbreviation_is_read_per_command(capsys: pytest.CaptureFixture[str]) -> None:
    # "--p" is --plot alone in run and demo (plan also has --planner); "--s" is
    # --seed alone in demo (run also has --scheduler).
    assert parse(["run", "omni-apf", "--p", "-x.png"])["plot"] == "-x.png"
    assert "argument --seed: expected an integer, got '-1e3'" in usage_error(
        ["demo", "--s", "-1e3"], capsys
    )
    assert "ambiguous option: --p could match" in usage_error([*PLAN, "--p", "-x.png"], capsys)


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        ([*PLAN, "--seed", "-1"], "unrecognized arguments: --seed -1"),
        ([*PLAN, "--bogus", "-x"], "unrecognized arguments: --bogus -x"),
        (["run", "omni-apf", "--quiet", "-x"], "unrecognized arguments: -x"),
    ],
)  # fmt: skip
def test_options_other_commands_have_are_named_as_typed(
    argv: list[str], words: str, capsys: pytest.CaptureFixture[str]
) -> None:
    # --seed is run's and demo's, not plan's; --quiet takes no value.
    assert usage_error(argv, capsys).endswith(words)


def test_the_arguments_given_are_not_changed() -> None:
    argv = [*PLAN, "--plot", "-x.png"]
    kept = list(argv)
    joined = join_negative_points(tuple(argv))
    assert argv == kept and joined[-1] == "--plot=-x.png" and joined is not argv
    # Without a command, or with a mistyped one, nothing is joined.
    for other in (["--version", "--plot", "-x"], ["plna", "--plot", "-x"], []):
        assert join_negative_points(other) == other
