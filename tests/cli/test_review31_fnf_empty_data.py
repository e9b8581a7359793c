"""``--data ''`` is refused in the command's words (review 31, FNF).

Before: ``navkit demo --data ''`` said "data_dir must not be empty (None looks in
the default places)", the library's keyword and value, not the option typed;
``navkit run omni-apf --data ''`` ran, taking the empty path for the working
directory (``Path('')`` is ``.``), as the check for a folder does. Checked against
the source before the fix: both tests failed there.
"""

from __future__ import annotations

import pytest

from navkit.cli import main


def _one_error_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("navkit: error: "), err
    return lines[0]


@pytest.mark.parametrize("argv", [["demo"], ["run", "omni-apf", "--trials", "1"]],
                         ids=["demo", "run"])  # fmt: skip
def test_an_empty_data_option_is_refused_naming_it(
    capsys: pytest.CaptureFixture[str], argv: list[str]
) -> None:
    assert main([*argv, "--quiet", "--data", ""]) == 1
    out, err = capsys.readouterr()
    line = _one_error_line(err)
    assert line == (
        "navkit: error: --data must not be empty: leave it out to look in $NAVKIT_DATA, "
        "then shared/data nearby"
    )
    assert "data_dir" not in line and "None" not in line
    assert out == ""
