"""A missing file named by a relative path says where it was looked for (a newcomer's review, s37).

The documentation's examples name ``../shared/data/...`` relative to the
repository's root. A reader who ran one from their own folder was told only
"map YAML file ../shared/data/... does not exist", which does not say that the
path was looked up from the working directory.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from navkit.cli import main
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_bag_odometry, read_carmen, read_map, read_movingai_map

READERS: list[tuple[Callable[[Any], object], str, str]] = [
    (OccupancyGrid.load, "map.yaml", "map YAML file"),
    (read_map, "map.yaml", "map YAML file"),
    (read_carmen, "intel.log.gz", "CARMEN log"),
    (read_bag_odometry, "test2.bag", "ROS bag"),
    (read_movingai_map, "arena.map", "MovingAI map"),
]


@pytest.mark.parametrize(("reader", "name", "what"), READERS)
def test_a_relative_path_names_the_working_directory(
    reader: Callable[[Any], object], name: str, what: str, tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:  # fmt: skip
    monkeypatch.chdir(tmp_path)
    relative = Path("..") / "shared" / "data" / name
    expected = f"{what} {relative} does not exist (relative to the working directory {tmp_path})"
    with pytest.raises(FileNotFoundError, match=f"^{re.escape(expected)}$"):
        reader(relative)


@pytest.mark.parametrize(("reader", "name", "what"), READERS)
def test_an_absolute_path_is_named_alone(
    reader: Callable[[Any], object], name: str, what: str, tmp_path: Path
) -> None:
    missing = tmp_path / name
    expected = f"{what} {missing} does not exist"
    with pytest.raises(FileNotFoundError, match=f"^{re.escape(expected)}$"):
        reader(missing)


def test_the_command_line_says_it_too(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["plan", "map.yaml", "--start", "0,0", "--goal", "1,1", "--quiet"]) == 1
    assert capsys.readouterr().err == (
        f"navkit: error: map YAML file map.yaml does not exist "
        f"(relative to the working directory {tmp_path})\n"
    )


def test_a_relative_data_folder_names_the_working_directory(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["run", "greedy", "--data", "../shared/data", "--quiet"]) == 1
    assert capsys.readouterr().err == (
        "navkit: error: --data: ../shared/data is not a folder "
        f"(relative to the working directory {tmp_path})\n"
    )
    assert main(["run", "greedy", "--data", str(tmp_path / "absent"), "--quiet"]) == 1
    absent = tmp_path / "absent"
    assert capsys.readouterr().err == f"navkit: error: --data: {absent} is not a folder\n"
