"""``$NAVKIT_DATA`` with a ``~`` no shell expanded (portability review).

PowerShell and ``cmd`` do not expand ``~``, nor does a POSIX shell inside quotes
(``export NAVKIT_DATA="~/navkit-data"``): the variable then held a literal
``~/navkit-data``, refused as a folder that does not exist.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from navkit.sim.scenarios import find_data


def test_a_tilde_in_navkit_data_means_the_home_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    home = tmp_path / "home"
    data = home / "navkit-data"
    (data / "carmen-logs").mkdir(parents=True)
    (data / "carmen-logs" / "README.md").write_text("logs\n")
    monkeypatch.setenv("HOME", str(home))
    monkeypatch.setenv("USERPROFILE", str(home))
    monkeypatch.setenv("NAVKIT_DATA", "~/navkit-data")
    assert find_data("carmen-logs/README.md") == data / "carmen-logs" / "README.md"


def test_a_tilde_folder_that_does_not_exist_is_still_named(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("HOME", str(tmp_path))
    monkeypatch.setenv("NAVKIT_DATA", "~/misspelt")
    with pytest.raises(ValueError, match=r"\$NAVKIT_DATA names the data folder .*misspelt"):
        find_data("carmen-logs/README.md")
