"""A file where an output's folder should be: one answer from every writer (review 45).

After FOLDERLOOP made a looped folder a missing one everywhere, a file standing
in the folder's place (``notes.txt/out.json``) was still told two ways:
``NotADirectoryError`` from ``write_map`` and ``OccupancyGrid.save`` (through
``atomic_paths``), but "folder ... does not exist" (``FileNotFoundError``) from
``write_json``, ``save_figure``, ``animate_trace`` and the command's options.
Every writer now raises ``NotADirectoryError`` naming the file; nothing is
written and the file is untouched.
"""

from __future__ import annotations

import errno
from pathlib import Path

import numpy as np
import pytest

from navkit._shared.files import check_folder
from navkit.cli import main
from navkit.cli._files import write_json
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import write_map


def _blocker(tmp_path: Path) -> Path:
    blocker = tmp_path / "notes.txt"
    blocker.write_text("keep me")
    return blocker


@pytest.mark.parametrize("below", [(), ("sub",)])
def test_check_folder_names_the_file_with_and_without_a_name(
    tmp_path: Path, below: tuple[str, ...]
) -> None:
    blocker = _blocker(tmp_path)
    target = blocker.joinpath(*below, "out.json")
    with pytest.raises(NotADirectoryError) as named:
        check_folder(target, "--json")
    assert str(named.value) == f"--json: {blocker} is a file, not a folder"
    with pytest.raises(NotADirectoryError) as unnamed:
        check_folder(target)
    assert unnamed.value.errno == errno.ENOTDIR
    assert unnamed.value.filename == str(blocker)


@pytest.mark.parametrize("below", [(), ("sub",)])
def test_every_writer_says_not_a_folder(tmp_path: Path, below: tuple[str, ...]) -> None:
    blocker = _blocker(tmp_path)
    grid = OccupancyGrid.from_occupancy(np.zeros((4, 4), dtype=bool), resolution=0.1)
    calls = {
        "write_map": lambda: write_map(grid, blocker.joinpath(*below, "out.yaml")),
        "save": lambda: grid.save(blocker.joinpath(*below, "out.yaml")),
        "write_json": lambda: write_json({"a": 1}, blocker.joinpath(*below, "out.json")),
    }
    for label, call in calls.items():
        with pytest.raises(NotADirectoryError) as caught:
            call()
        assert str(blocker) in str(caught.value), label
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes.txt"]
    assert blocker.read_text() == "keep me"


def test_save_figure_says_not_a_folder(tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    import matplotlib.pyplot as plt

    from navkit.plot import save_figure

    blocker = _blocker(tmp_path)
    fig, ax = plt.subplots()
    try:
        with pytest.raises(NotADirectoryError) as caught:
            save_figure(ax, blocker / "out.png")
    finally:
        plt.close(fig)
    assert str(caught.value) == f"path: {blocker} is a file, not a folder"
    assert blocker.read_text() == "keep me"


def test_the_command_says_not_a_folder_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    blocker = _blocker(tmp_path)
    code = main(["run", "demo", "--quiet", "--workers", "1", "--json", str(blocker / "out.json")])
    err = capsys.readouterr().err
    assert code == 1
    assert err == f"navkit: error: --json: {blocker} is a file, not a folder\n"
    assert blocker.read_text() == "keep me"
