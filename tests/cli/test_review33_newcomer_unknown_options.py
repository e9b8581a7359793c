"""An option the command does not have is reported by that command (a newcomer's review, s37).

``navkit demo --trail 3`` and ``navkit plan ... --robot-radius 0.2`` were
reported by the top-level parser: its usage, ``navkit [-h] [--version]
COMMAND ...``, lists none of the command's options, and nothing named the
option meant (``--trials``, ``--radius``).
"""

from __future__ import annotations

import pytest

from navkit.cli import main

PLAN = ["plan", "m.yaml", "--start", "0,0", "--goal", "1,1"]


def usage_error(argv: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[str, str]:
    """The first and the last line of a usage error (exit code 2, no traceback)."""
    assert main(argv) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert "Traceback" not in "\n".join(lines)
    return lines[0], lines[-1]


@pytest.mark.parametrize(
    ("argv", "usage", "line"),
    [
        (["demo", "--trail", "3"], "usage: navkit demo [-h] [--trials N]",
         "navkit demo: error: unrecognized arguments: --trail 3, maybe you meant '--trials'?"),
        ([*PLAN, "--robot-radius", "0.2"], "usage: navkit plan [-h] --start X,Y",
         "navkit plan: error: unrecognized arguments: --robot-radius 0.2, "
         "maybe you meant '--radius'?"),
        ([*PLAN, "--start_tolerance=0.1"], "usage: navkit plan [-h] --start X,Y",
         "navkit plan: error: unrecognized arguments: --start_tolerance=0.1, "
         "maybe you meant '--start-tolerance'?"),
        (["run", "omni-apf", "--worker", "2", "--plott", "x.png"], "usage: navkit run [-h]",
         "navkit run: error: unrecognized arguments: --plott x.png, maybe you meant '--plot'?"),
        (["warmup", "--onyl", "astar"], "usage: navkit warmup [-h]",
         "navkit warmup: error: unrecognized arguments: --onyl astar, maybe you meant '--only'?"),
    ],
)  # fmt: skip
def test_the_command_reports_its_own_usage_and_the_closest_option(
    argv: list[str], usage: str, line: str, capsys: pytest.CaptureFixture[str]
) -> None:
    first, last = usage_error(argv, capsys)
    assert first.startswith(usage)
    assert last == line


@pytest.mark.parametrize(
    ("argv", "line"),
    [
        # Nothing close: no guess. --help is never guessed ("--step" is closest to it).
        (["warmup", "--step", "astar"],
         "navkit warmup: error: unrecognized arguments: --step astar"),
        (["list", "--all"], "navkit list: error: unrecognized arguments: --all"),
        (["run", "omni-apf", "--quiet", "-x"], "navkit run: error: unrecognized arguments: -x"),
    ],
)  # fmt: skip
def test_nothing_close_guesses_nothing(
    argv: list[str], line: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert usage_error(argv, capsys)[1] == line


def test_an_abbreviation_still_reads_as_its_option(capsys: pytest.CaptureFixture[str]) -> None:
    # Unique prefixes are argparse's own: they must not become "unrecognized".
    assert main(["demo", "--tri", "0"]) == 2
    assert "argument --trials: must be in [1, 100000], got 0" in capsys.readouterr().err
