"""The command line's grammar: gaps a mutation review found (review 44, MUTANT17).

Each test here failed on a mutant of ``navkit.cli._parser`` that every
earlier test passed.
"""

from __future__ import annotations

import pytest

from navkit.cli import main
from navkit.cli._parser import closest_choice


def usage_line(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    """The last line of a usage error (exit code 2)."""
    assert main(argv) == 2
    return capsys.readouterr().err.strip().splitlines()[-1]


@pytest.mark.parametrize(
    ("argv", "meant"),
    [
        (["demo", "--trail=100000"], "--trials"),
        (["run", "omni-apf", "--wrkers=1024"], "--workers"),
    ],
)
def test_an_unknown_option_with_its_value_is_guessed_from_its_name_alone(
    argv: list[str], meant: str, capsys: pytest.CaptureFixture[str]
) -> None:
    # "--trail=100000" is compared as "--trail": the value made it too far from any option.
    assert usage_line(argv, capsys).endswith(f"maybe you meant {meant!r}?")


@pytest.mark.parametrize("choices", [["a_b", "a-b", "A-B"], ["Field-Dstar", "field_dstar"]])
def test_of_equal_spellings_the_first_choice_is_named(choices: list[str]) -> None:
    # Case and "_" against "-" are ignored: every choice here spells the same name.
    for value in choices:
        assert closest_choice(value.upper(), choices) == choices[0]


def test_an_ambiguous_or_empty_prefix_names_no_choice() -> None:
    # A prefix names a choice only when it alone starts with it: "d" is "demo" or
    # "diff-astar", "" any of them (even of a single choice).
    scenarios = ("demo", "diff-astar", "greedy", "indoor-nav", "omni-apf", "soccer")
    assert closest_choice("d", scenarios) is None
    assert closest_choice("", scenarios) is None
    assert closest_choice("", ["demo"]) is None
    assert closest_choice("de", scenarios) == "demo"
