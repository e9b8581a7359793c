"""Hostile outputs (session 34): a failed write of ``--json`` or ``--plot`` names the file.

The system reports a failed write, flush or sync (a full disk, ``/dev/full``, a
file-size limit) without a file name: ``navkit plan ... --json /dev/full``
ended with ``navkit: error: No space left on device`` and ``--json out.json``
on a full disk with ``navkit: error: File too large``, leaving the user to
guess which of the command's files failed. The error now names the output
(``/dev/full: No space left on device``); no partial file is left behind.
"""

from __future__ import annotations

import errno
import os
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import navkit.plot
from navkit.cli import main
from navkit.cli._files import write_json
from navkit.mapping import OccupancyGrid


def _small_map(folder: Path) -> list[str]:
    """``navkit plan`` arguments for a plannable map saved in ``folder``."""
    occupied = np.zeros((10, 12), dtype=bool)
    occupied[:6, 6] = True
    OccupancyGrid.from_occupancy(occupied, resolution=0.1).save(folder / "m.yaml")
    return ["plan", str(folder / "m.yaml"), "--start", "0.15,0.15", "--goal", "1.05,0.15"]


def _no_space(*args: Any, **kwargs: Any) -> None:
    raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full (Linux)")
def test_json_onto_dev_full_names_it(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    argv = _small_map(tmp_path)
    assert main([*argv, "--quiet", "--json", "/dev/full"]) == 1
    err = capsys.readouterr().err
    assert err == f"navkit: error: /dev/full: {os.strerror(errno.ENOSPC)}\n"


def test_json_on_a_full_disk_names_it_and_leaves_nothing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # The disk fills as the temporary file is synced (what a delayed-allocation
    # file system reports): the error has no file name of its own.
    monkeypatch.setattr(os, "fsync", _no_space)
    target = tmp_path / "out.json"
    with pytest.raises(OSError, match="No space left on device") as caught:
        write_json({"a": 1}, target)
    assert caught.value.filename == str(target)
    assert list(tmp_path.iterdir()) == []


def test_plot_on_a_full_disk_names_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    argv = _small_map(tmp_path)
    monkeypatch.setattr(navkit.plot, "save_figure", _no_space)
    picture = tmp_path / "route.png"
    assert main([*argv, "--quiet", "--plot", str(picture)]) == 1
    err = capsys.readouterr().err
    assert err == f"navkit: error: {picture}: {os.strerror(errno.ENOSPC)}\n"


def test_an_error_naming_its_own_file_keeps_it(tmp_path: Path) -> None:
    # A folder given for the file: the error names it already, as the system does.
    folder = tmp_path / "out.json"
    folder.mkdir()
    with pytest.raises(IsADirectoryError, match="is a folder"):
        write_json({"a": 1}, folder)
    with pytest.raises(FileNotFoundError) as caught:
        write_json({"a": 1}, tmp_path / "missing" / "out.json")
    assert caught.value.filename is None  # navkit's own message names the folder
    assert "folder" in str(caught.value) and "missing" in str(caught.value)
