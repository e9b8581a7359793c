"""The command's number options at both ends of their ranges, and its defaults
(review 44, MUTANT20: mutants of ``_parser`` moving a bound or a default survived).
"""

from __future__ import annotations

import math
from typing import Any

import pytest

from navkit.cli._parser import build_parser, parse_command_line

_PLAN = ["plan", "map.yaml", "--start", "0,0", "--goal", "1,1"]

# (command before the option, option, its attribute, lowest, highest, just below, just above)
_RANGES = [
    (["demo"], "--trials", "trials", "1", "100000", "0", "100001"),
    (["run", "demo"], "--workers", "workers", "1", "1024", "0", "1025"),
    (["warmup"], "--workers", "workers", "1", "1024", "0", "1025"),
    (["demo"], "--seed", "seed", "0", str(2**64 - 1), "-1", str(2**64)),
    (_PLAN, "--radius", "radius", "0", "100", "-1e-9", "100.000001"),
    (_PLAN, "--start-tolerance", "start_tolerance", "0", "1e9", "-1e-9", "1000000000.5"),
]


def _parse(argv: list[str]) -> Any:
    return parse_command_line(build_parser(["demo"]), argv)


@pytest.mark.parametrize(
    ("command", "option", "attribute", "low", "high", "below", "above"), _RANGES
)
def test_both_ends_of_a_range_are_taken(
    command: list[str], option: str, attribute: str, low: str, high: str, below: str, above: str
) -> None:
    integer = option in ("--trials", "--workers", "--seed")
    for text in (low, high):
        value = getattr(_parse([*command, f"{option}={text}"]), attribute)
        assert type(value) is (int if integer else float)
        assert value == (int(text) if integer else float(text))


@pytest.mark.parametrize(
    ("command", "option", "attribute", "low", "high", "below", "above"), _RANGES
)
def test_just_outside_a_range_is_refused_naming_the_option(
    command: list[str], option: str, attribute: str, low: str, high: str, below: str, above: str,
    capsys: pytest.CaptureFixture[str],
) -> None:  # fmt: skip
    for text in (below, above):
        with pytest.raises(SystemExit) as stop:
            _parse([*command, f"{option}={text}"])
        assert stop.value.code == 2
        assert f"argument {option}: must be in [" in capsys.readouterr().err


def test_a_negative_zero_tolerance_is_written_as_zero() -> None:
    # The JSON output repeats the tolerance: "-0.0" there would read as a distance.
    value = _parse([*_PLAN, "--start-tolerance=-0"]).start_tolerance
    assert value == 0.0 and math.copysign(1.0, value) == 1.0


def test_the_defaults_are_the_ones_the_help_gives() -> None:
    plan = _parse(_PLAN)
    assert (plan.planner, plan.radius, plan.start_tolerance) == ("astar", 0.0, 0.0)
    demo = _parse(["demo"])
    assert (demo.map, demo.seed, demo.trials) == ("auto", 0, None)
    assert _parse(["warmup"]).workers is None and _parse(["warmup"]).only is None


def test_a_command_is_required() -> None:
    with pytest.raises(SystemExit) as stop:
        _parse([])
    assert stop.value.code == 2


@pytest.mark.parametrize("text", ["(1,23", "1,2)", "((1,2)", "(1,2))"])
def test_a_point_with_one_parenthesis_is_refused(
    text: str, capsys: pytest.CaptureFixture[str]
) -> None:
    # Only a pair of parentheses around X,Y is taken off: "(1,23" is not (1, 2).
    with pytest.raises(SystemExit) as stop:
        _parse(["plan", "map.yaml", f"--start={text}", "--goal", "1,1"])
    assert stop.value.code == 2
    assert f"argument --start: expected X,Y in metres, got {text!r}" in capsys.readouterr().err


def test_a_point_in_parentheses_is_taken() -> None:
    assert _parse(["plan", "map.yaml", "--start= (1.5, -2) ", "--goal", "1,1"]).start == (1.5, -2.0)


def test_only_given_twice_keeps_both_steps() -> None:
    from navkit.cli._parser import _warmup_steps

    first, second = _warmup_steps()[:2]
    assert _parse(["warmup", "--only", first, "--only", second]).only == [first, second]
