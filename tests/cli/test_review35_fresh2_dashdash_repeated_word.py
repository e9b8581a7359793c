"""An unknown option typed before ``--`` and again after it (a fresh review of review 34).

Review 34 stopped guessing from words after ``--`` by leaving out every extra
word *equal* to one after the ``--``: the same mistyped option before it
(``navkit demo --trail -- --trail``, a command line edited by hand) lost its
"maybe you meant '--trials'?" too, and the message said only that words after
``--`` are not read. Words are now told apart by their place, not their text.
"""

from __future__ import annotations

import pytest

from navkit.cli import main


def last_line(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert "Traceback" not in err
    return err.splitlines()[-1]


@pytest.mark.parametrize(
    ("argv", "line"),
    [
        (["demo", "--trail", "--", "--trail"],
         "navkit demo: error: unrecognized arguments: --trail -- --trail, "
         "maybe you meant '--trials'?"),
        (["run", "omni-apf", "--trails", "1", "--", "--trails"],
         "navkit run: error: unrecognized arguments: --trails 1 -- --trails, "
         "maybe you meant '--trials'?"),
        # An option read before the "--" and typed again after it: that one is not guessed.
        (["run", "omni-apf", "--trials", "1", "--", "--trials"],
         "navkit run: error: unrecognized arguments: -- --trials "
         "(after '--' no word is read as an option)"),
        # Review 34's cases are unchanged: after "--" alone, no guess.
        (["demo", "--", "--trail"],
         "navkit demo: error: unrecognized arguments: -- --trail "
         "(after '--' no word is read as an option)"),
        (["run", "omni-apf", "--", "--trials"],
         "navkit run: error: unrecognized arguments: --trials "
         "(after '--' no word is read as an option)"),
    ],
)  # fmt: skip
def test_a_word_is_guessed_from_by_its_place(
    argv: list[str], line: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert last_line(argv, capsys) == line
