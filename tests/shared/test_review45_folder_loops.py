"""A target's folder that is a loop of symbolic links is a missing folder, everywhere (review 45).

Before, ``a -> b``, ``b -> a`` and a target ``a/out.json`` were told three ways:
``write_map`` (through ``atomic_paths``) raised ``OSError`` (``ELOOP``), ``write_json``
and ``save_figure`` said the folder does not exist, the command line that the
file was a loop. :func:`check_folder` is now the one test of every writer: a
``FileNotFoundError`` naming the folder and the loop (the highest folder of the
path that loops), before anything is written. A loop made during the write
(after the last check, before the mode lookup) is refused in the same words
instead of an ``OSError`` from ``os.stat``. The writers' own tests are in
``tests/{mapping,cli,plot}/test_review45_folder_loops_*.py``.
"""

from __future__ import annotations

import errno
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

from navkit._shared import files
from navkit._shared.files import atomic_path, atomic_paths, check_folder

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from link_trees import loop as _loop
from link_trees import tree as _tree

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="symbolic links need rights")


@pytest.mark.parametrize("below", [(), ("b",), ("b", "c")])
def test_check_folder_names_the_folder_and_the_loop(tmp_path: Path, below: tuple[str, ...]) -> None:
    loop = _loop(tmp_path)
    folder = loop.joinpath(*below)
    expected = f"--json: folder {folder} does not exist ({loop} is a loop of symbolic links)"
    with pytest.raises(FileNotFoundError) as caught:
        check_folder(folder / "out.json", "--json")
    assert str(caught.value) == expected
    with pytest.raises(FileNotFoundError) as caught:
        check_folder(folder / "out.json")
    assert caught.value.errno == errno.ENOENT
    assert caught.value.strerror == f"no such folder ({loop} is a loop of symbolic links)"
    assert caught.value.filename == str(folder)


def test_check_folder_tells_a_loop_from_a_missing_folder(tmp_path: Path) -> None:
    (tmp_path / "dangling").symlink_to("nowhere")
    for folder in (tmp_path / "missing", tmp_path / "dangling", tmp_path / "missing" / "deeper"):
        with pytest.raises(FileNotFoundError) as caught:
            check_folder(folder / "out.json", "path")
        assert str(caught.value) == f"path: folder {folder} does not exist"
    # A folder given through a link to it, or through links that end in one, is a folder.
    (tmp_path / "real").mkdir()
    (tmp_path / "to_real").symlink_to("real")
    (tmp_path / "to_to_real").symlink_to("to_real")
    for folder in ("real", "to_real", "to_to_real"):
        check_folder(tmp_path / folder / "out.json", "path")
        check_folder(tmp_path / folder / "out.json")


@pytest.mark.parametrize("below", [(), ("b",)])
def test_atomic_paths_refuses_a_looped_folder_before_creating_anything(
    tmp_path: Path, below: tuple[str, ...]
) -> None:
    # Before: OSError (ELOOP), not the missing folder's FileNotFoundError.
    loop = _loop(tmp_path)
    first = tmp_path / "first.json"
    first.write_text("old")
    before = _tree(tmp_path)
    ran = []
    with (
        pytest.raises(FileNotFoundError, match=rf"no such folder \({loop} is a loop") as caught,
        atomic_paths([first, loop.joinpath(*below, "out.json")]) as temporaries,
    ):
        ran.append(temporaries)
    assert ran == []
    assert caught.value.filename == str(loop.joinpath(*below))
    assert _tree(tmp_path) == before


def test_atomic_paths_writes_into_a_folder_given_through_a_link(tmp_path: Path) -> None:
    (tmp_path / "real").mkdir()
    (tmp_path / "link").symlink_to("real")
    with atomic_path(tmp_path / "link" / "out.json") as temporary:
        temporary.write_text("new")
    assert _tree(tmp_path) == {"link": "-> real", "real": "/", "real/out.json": "new"}


def _after_the_last_check(monkeypatch: pytest.MonkeyPatch, make_loop: Callable[[], None]) -> None:
    """Run ``make_loop`` just after ``atomic_paths``' second (last) check of its targets."""
    real_check = files._check_targets
    calls = []

    def check_then_loop(targets: tuple[Path, ...]) -> None:
        real_check(targets)
        calls.append(targets)
        if len(calls) == 2:
            make_loop()

    monkeypatch.setattr(files, "_check_targets", check_then_loop)


def test_a_target_looped_after_the_last_check_is_refused_as_one_looped_before(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Before: OSError (ELOOP) from the mode's os.stat, the temporary file written.
    target = tmp_path / "out.json"
    target.write_text("old")

    def make_loop() -> None:
        target.unlink()
        target.symlink_to("out.json")

    _after_the_last_check(monkeypatch, make_loop)
    with (
        pytest.raises(ValueError, match=rf"^{target} is a loop of symbolic links"),
        atomic_path(target) as temporary,
    ):
        temporary.write_text("new")
    assert _tree(tmp_path) == {"out.json": "-> out.json"}


def test_a_folder_looped_after_the_last_check_is_refused_as_one_looped_before(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Before: OSError (ELOOP) from the mode's os.stat, and again from the removal of
    # the temporary file, whose name now runs through the loop. The folder was moved
    # away with the temporary file in it: that file cannot be reached to remove.
    folder = tmp_path / "d"
    folder.mkdir()
    (folder / "out.json").write_text("old")

    def make_loop() -> None:
        folder.rename(tmp_path / "moved")
        folder.symlink_to("d")

    _after_the_last_check(monkeypatch, make_loop)
    with (
        pytest.raises(FileNotFoundError, match=rf"no such folder \({folder} is a loop"),
        atomic_path(folder / "out.json") as temporary,
    ):
        temporary.write_text("new")
    tree = _tree(tmp_path)
    assert tree.pop("d") == "-> d"
    assert tree.pop("moved/out.json") == "old"
    assert tree.pop("moved") == "/"
    assert [Path(name).parent.name for name in tree] == ["moved"]  # the stranded temporary
