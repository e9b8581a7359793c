"""The command's outputs and ``write_json``: a looped folder is a missing one (review 45).

Before, an output in a folder that is a loop of symbolic links (``a -> b``,
``b -> a``, ``--json a/out.json``) was refused by the command line as "a/out.json
is a loop of symbolic links" (a ``ValueError``), while ``write_json`` said
"folder a does not exist" and ``write_map`` raised ``OSError`` (``ELOOP``). All
now give the missing folder's ``FileNotFoundError``, naming the folder and the
loop; the command line keeps its one line and exit code 1. See
``tests/shared/test_review45_folder_loops.py``.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

from navkit.cli import main
from navkit.cli._files import write_json

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from link_trees import loop as _loop
from link_trees import tree as _tree

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="symbolic links need rights")

_OPTIONS = [("--json", ".json"), ("--plot", ".png"), ("--animate", ".gif")]


@pytest.mark.parametrize("below", [(), ("b",)])
def test_write_json_names_a_looped_folder_and_writes_nothing(
    tmp_path: Path, below: tuple[str, ...]
) -> None:
    loop = _loop(tmp_path)
    folder = loop.joinpath(*below)
    before = _tree(tmp_path)
    with pytest.raises(FileNotFoundError) as caught:
        write_json({"a": 1}, folder / "out.json")
    assert str(caught.value) == (
        f"path: folder {folder} does not exist ({loop} is a loop of symbolic links)"
    )
    assert _tree(tmp_path) == before


def test_write_json_says_a_missing_folder_in_the_same_words(tmp_path: Path) -> None:
    # Before: "folder ... does not exist", the argument unnamed (save_figure named it).
    with pytest.raises(FileNotFoundError) as caught:
        write_json({"a": 1}, tmp_path / "missing" / "out.json")
    assert str(caught.value) == f"path: folder {tmp_path / 'missing'} does not exist"
    assert _tree(tmp_path) == {}


def test_write_json_refuses_a_looped_file_and_writes_through_a_linked_folder(
    tmp_path: Path,
) -> None:
    (tmp_path / "real").mkdir()
    (tmp_path / "link").symlink_to("real")
    looped = tmp_path / "link" / "loop.json"
    looped.symlink_to("loop.json")
    with pytest.raises(ValueError, match=rf"^{looped} is a loop of symbolic links"):
        write_json({"a": 1}, looped)
    assert write_json({"a": 1}, tmp_path / "link" / "out.json") == tmp_path / "link" / "out.json"
    assert json.loads((tmp_path / "real" / "out.json").read_text()) == {"a": 1}
    assert sorted(_tree(tmp_path)) == ["link", "real", "real/loop.json", "real/out.json"]


@pytest.mark.parametrize(("option", "suffix"), _OPTIONS)
@pytest.mark.parametrize("below", [(), ("b",)])
def test_the_command_names_a_looped_folder_in_one_line(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    option: str,
    suffix: str,
    below: tuple[str, ...],
) -> None:
    # Before: "--json: .../a/out.json is a loop of symbolic links", the file blamed.
    loop = _loop(tmp_path)
    folder = loop.joinpath(*below)
    before = _tree(tmp_path)
    assert main(["demo", "--quiet", option, str(folder / f"out{suffix}")]) == 1
    out, err = capsys.readouterr()
    expected = f"{option}: folder {folder} does not exist ({loop} is a loop of symbolic links)"
    assert (out, err) == ("", f"navkit: error: {expected}\n")
    assert _tree(tmp_path) == before


@pytest.mark.parametrize(("option", "suffix"), _OPTIONS)
def test_the_command_still_names_a_looped_file_as_one(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], option: str, suffix: str
) -> None:
    looped = tmp_path / f"out{suffix}"
    looped.symlink_to(looped.name)
    assert main(["demo", "--quiet", option, str(looped)]) == 1
    out, err = capsys.readouterr()
    assert (out, err) == ("", f"navkit: error: {option}: {looped} is a loop of symbolic links\n")
    assert _tree(tmp_path) == {looped.name: f"-> {looped.name}"}


def test_the_command_writes_every_output_through_a_linked_folder(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "real").mkdir()
    (tmp_path / "link").symlink_to("real")
    argv = ["run", "demo", "--quiet", "--trials", "1", "--seed", "3", "--workers", "1"]
    for option, suffix in _OPTIONS:
        argv += [option, str(tmp_path / "link" / f"r{suffix}")]
    assert main(argv) == 0
    assert "navkit: error" not in capsys.readouterr().err
    tree = _tree(tmp_path)
    assert sorted(tree) == ["link", "real", "real/r.gif", "real/r.json", "real/r.png"]
    assert all(tree[f"real/r{suffix}"] for _, suffix in _OPTIONS)  # written, not empty
