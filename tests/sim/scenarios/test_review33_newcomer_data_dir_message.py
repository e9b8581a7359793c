"""A data folder given with ``data_dir=`` or ``--data`` lacking the file (a newcomer's review).

``navkit demo --map willow --data ~/navkit-data/ros-map-server-maps`` (one
level too deep) answered "... not found in ...; set NAVKIT_DATA or pass
data_dir= (--data on the command line)": the user had passed ``--data``, and
setting ``NAVKIT_DATA`` would change nothing, since ``data_dir`` is the only
folder looked in.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from navkit.cli import main
from navkit.errors import DataNotFoundError
from navkit.sim.scenarios import find_data
from navkit.sim.scenarios._data import ENV_VAR

WILLOW = "ros-map-server-maps/willow_garage_2010/willow-2010-02-18-0.10.yaml"


def test_a_given_data_dir_is_named_as_the_only_place_looked_in(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv(ENV_VAR, str(tmp_path))
    deep = tmp_path / "ros-map-server-maps"
    deep.mkdir()
    with pytest.raises(DataNotFoundError) as caught:
        find_data(WILLOW, data_dir=deep)
    message = str(caught.value)
    assert message.startswith(f"{WILLOW} not found in {deep}; ")
    assert "set NAVKIT_DATA" not in message and "or pass data_dir=" not in message
    assert (
        "data_dir= (--data on the command line) is the only folder looked in (not "
        "NAVKIT_DATA, not shared/data nearby): it must be the one that itself holds "
        "ros-map-server-maps, carmen-logs, ..."
    ) in message
    assert "docs/data.md" in message and "\n" not in message


def test_without_data_dir_the_advice_is_unchanged(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    work = tmp_path / "a" / "b" / "c" / "d"  # no shared/data here or up to 3 levels up
    work.mkdir(parents=True)
    monkeypatch.chdir(work)
    monkeypatch.delenv(ENV_VAR, raising=False)
    with pytest.raises(DataNotFoundError, match=r"no-such-set/x\.yaml not found in ") as caught:
        find_data("no-such-set/x.yaml")
    assert (
        "; set NAVKIT_DATA or pass data_dir= (--data on the command line): the folder "
        "holding ros-map-server-maps, carmen-logs, ... (where to download them"
    ) in str(caught.value)


def test_the_command_line_says_it_for_data(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["demo", "--map", "willow", "--data", str(tmp_path), "--quiet"]) == 1
    err = capsys.readouterr().err
    assert err.startswith(f"navkit: error: {WILLOW} not found in {tmp_path}; data_dir= (--data")
    assert "set NAVKIT_DATA" not in err
