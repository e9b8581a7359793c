"""Atomic writes: four documented guarantees no test held (review 42, MUTANT13).

A mutation review of ``navkit._shared.files`` found these mutants passing every
test: a new file created with mode ``0o667`` (the tests' umask, ``0o027``,
hid the extra bit), the second
folder check before the renames deleted (with no hard links, a target before a
folder made during the block was replaced), and the folders' ``fsync`` after
the renames deleted. Each test here fails with one of them. The rollback of a
symbolic link (its hard link made with ``follow_symlinks=False``, so that it
comes back a link) had no test either; its mutant (``True``) is equivalent on
Linux, where CPython's ``os.link`` calls ``link(2)``, which does not follow links,
but the test holds the documented result wherever it runs.
"""

from __future__ import annotations

import errno
import os
import stat
import sys
from pathlib import Path
from typing import Any

import pytest

from navkit._shared.files import atomic_path, atomic_paths

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX modes, links and fsync")


def _failing_replace(call: int) -> Any:
    """``os.replace`` whose ``call``-th call fails with ``EIO``."""
    real = os.replace
    calls = [0]

    def replace(*args: Any, **kwargs: Any) -> None:
        calls[0] += 1
        if calls[0] == call:
            raise OSError(errno.EIO, "Input/output error")
        real(*args, **kwargs)

    return replace


@pytest.mark.parametrize("umask", [0o000, 0o022, 0o077])
def test_a_new_file_has_mode_0o666_less_the_umask(tmp_path: Path, umask: int) -> None:
    target = tmp_path / "new.json"
    old = os.umask(umask)
    try:
        with atomic_path(target) as temporary:
            temporary.write_text("{}")
    finally:
        os.umask(old)
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~umask


def test_a_symbolic_link_put_back_after_a_failed_rename_is_a_link_again(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    pointee = tmp_path / "pointee.txt"
    pointee.write_text("keep")
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.symlink_to(pointee)
    b.write_text("old b")
    monkeypatch.setattr(os, "replace", _failing_replace(2))
    with pytest.raises(OSError, match="Input/output"), atomic_paths([a, b]) as (ta, tb):
        ta.write_text("new a")
        tb.write_text("new b")
    monkeypatch.undo()
    assert a.is_symlink() and os.readlink(a) == str(pointee)
    assert a.read_text() == "keep" and pointee.read_text() == "keep" and b.read_text() == "old b"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt", "b.txt", "pointee.txt"]


def test_a_folder_made_during_the_block_stops_every_rename_even_without_hard_links(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Without hard links a replaced target cannot be put back: only the check made
    # before the renames keeps the first target old.
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_text("old a")

    def no_link(*args: Any, **kwargs: Any) -> None:
        raise PermissionError("no hard links here")

    monkeypatch.setattr(os, "link", no_link)
    with (
        pytest.raises(IsADirectoryError, match="a folder cannot be written as a file"),
        atomic_paths([a, b]) as (ta, tb),
    ):
        ta.write_text("new a")
        tb.write_text("new b")
        b.mkdir()
    assert a.read_text() == "old a" and b.is_dir()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt", "b.txt"]


def test_the_folders_are_synced_after_the_renames(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "one").mkdir()
    (tmp_path / "two").mkdir()
    targets = [tmp_path / "one" / "m.pgm", tmp_path / "two" / "m.yaml", tmp_path / "one" / "x"]
    opened: dict[int, tuple[str, int]] = {}
    synced: list[tuple[str, int, bool]] = []
    real_open, real_fsync = os.open, os.fsync

    def watched_open(path: Any, flags: int, *args: Any, **kwargs: Any) -> int:
        fd = real_open(path, flags, *args, **kwargs)
        opened[fd] = (os.fspath(path), flags)
        return fd

    def watched_fsync(fd: int) -> None:
        path, flags = opened[fd]
        synced.append((path, flags, all(t.exists() for t in targets)))
        real_fsync(fd)

    monkeypatch.setattr(os, "open", watched_open)
    monkeypatch.setattr(os, "fsync", watched_fsync)
    with atomic_paths(targets) as temporaries:
        for t in temporaries:
            t.write_text("new")
    monkeypatch.undo()
    folders = [(path, renamed) for path, flags, renamed in synced if Path(path).is_dir()]
    # Each folder once, after every rename (the files' own syncs come before them).
    assert folders == [(str(tmp_path / "one"), True), (str(tmp_path / "two"), True)]
    assert len(synced) == len(targets) + 2
