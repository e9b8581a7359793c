"""Building the parser lists no lazy choices, on Python 3.14 too (issue 17's start-up time).

Python 3.14's ``add_argument`` checks a help string by expanding it at once, so
a ``%(choices)s`` given to it listed the scenarios (importing the simulator)
and the warm-up steps while ``navkit --help`` or ``navkit plan`` built the
parser. The names must be looked up only when an argument that has them is
parsed or its help is shown.
"""

from __future__ import annotations

import pytest

from navkit.cli import _parser


@pytest.fixture
def lookups(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """Count the look-ups of the scenario names and warm-up steps (the real answers)."""
    calls: list[str] = []
    names, known, steps = _parser._scenario_names, _parser._is_scenario, _parser._warmup_steps

    def scenario_names() -> list[str]:
        calls.append("scenarios")
        return names()

    def is_scenario(name: str) -> bool:
        calls.append("is_scenario")
        return known(name)

    def warmup_steps() -> tuple[str, ...]:
        calls.append("steps")
        return steps()

    monkeypatch.setattr(_parser, "_scenario_names", scenario_names)
    monkeypatch.setattr(_parser, "_is_scenario", is_scenario)
    monkeypatch.setattr(_parser, "_warmup_steps", warmup_steps)
    return calls


def test_building_the_parser_looks_no_names_up(lookups: list[str]) -> None:
    parser = _parser.build_parser()
    assert lookups == []
    parser.parse_args(["plan", "m.yaml", "--start", "0,0", "--goal", "1,1"])
    parser.parse_args(["demo", "--trials", "2"])
    assert lookups == []


def test_the_help_still_lists_them_when_shown(
    lookups: list[str], capsys: pytest.CaptureFixture[str]
) -> None:
    parser = _parser.build_parser()
    with pytest.raises(SystemExit):
        parser.parse_args(["run", "--help"])
    assert "one of: demo, diff-astar, greedy" in " ".join(capsys.readouterr().out.split())
    assert lookups == ["scenarios"]
    with pytest.raises(SystemExit):
        parser.parse_args(["warmup", "--help"])
    shown = " ".join(capsys.readouterr().out.split())  # wrapped to the terminal's width
    assert "only this step (repeatable): " + ", ".join(_parser._warmup_steps()) in shown
    assert lookups[:2] == ["scenarios", "steps"]


def test_a_named_scenario_is_checked_alone(lookups: list[str]) -> None:
    parser = _parser.build_parser()
    assert parser.parse_args(["run", "greedy"]).scenario == "greedy"
    assert lookups == ["is_scenario"]
    with pytest.raises(SystemExit):
        parser.parse_args(["warmup", "--only", "nope"])
    assert lookups[-1] == "steps"
