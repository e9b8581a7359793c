"""Unknown options after ``--`` (a fresh-eyes review of review 33's closest-option message).

Words after ``--`` are no options, whatever they look like. ``navkit run
omni-apf -- --trials`` was answered "maybe you meant '--trials'?", the very
word typed, and ``navkit demo -- --tri`` "maybe you meant '--trials'?" (an
abbreviation that argparse does not read there). They now say why the word
was not read instead of guessing.
"""

from __future__ import annotations

import pytest

from navkit.cli import main


def last_usage_line(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert "Traceback" not in err
    return err.splitlines()[-1]


@pytest.mark.parametrize(
    ("argv", "line"),
    [
        (["run", "omni-apf", "--", "--trials"],
         "navkit run: error: unrecognized arguments: --trials "
         "(after '--' no word is read as an option)"),
        (["demo", "--", "--tri"],
         "navkit demo: error: unrecognized arguments: -- --tri "
         "(after '--' no word is read as an option)"),
        (["demo", "--", "--trials=3"],
         "navkit demo: error: unrecognized arguments: -- --trials=3 "
         "(after '--' no word is read as an option)"),
        # Before the "--" a mistyped option is still guessed; "--" alone says nothing more.
        (["demo", "--trail", "--", "--trials"],
         "navkit demo: error: unrecognized arguments: --trail -- --trials, "
         "maybe you meant '--trials'?"),
        (["demo", "--"], "navkit demo: error: unrecognized arguments: --"),
        (["run", "omni-apf", "--", "x"], "navkit run: error: unrecognized arguments: x"),
    ],
)  # fmt: skip
def test_words_after_dashdash_are_not_guessed_from(
    argv: list[str], line: str, capsys: pytest.CaptureFixture[str]
) -> None:
    got = last_usage_line(argv, capsys)
    assert got == line
    typed = argv[-1].partition("=")[0]
    if "--" in argv[:-1] and typed.startswith("--") and "--trail" not in argv:
        assert f"maybe you meant {typed!r}" not in got
