"""An empty output file name is refused as such, before a run starts."""

from __future__ import annotations

import pytest

from navkit.cli import main


@pytest.mark.parametrize("option", ["--json", "--plot", "--animate"])
def test_an_empty_output_name_is_named_as_empty(
    option: str, capsys: pytest.CaptureFixture[str]
) -> None:
    # Path("") is ".": the message said "--json:  is a folder, not a file".
    assert main(["demo", "--quiet", option, ""]) == 1
    err = capsys.readouterr().err
    assert err == f"navkit: error: {option}: the file name is empty\n"
