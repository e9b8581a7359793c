"""Atomic writes on Windows and macOS, simulated on Linux (the portability review).

Windows refuses to rename over a file that is read-only or that another
program holds open (``PermissionError``), and to remove a read-only file; on
macOS ``fsync`` leaves the data in the drive's cache (``F_FULLFSYNC`` flushes
it). The tests pretend to be there (``sys.platform`` and fakes of ``os``
calls that behave as those systems' do) and check what the saves leave.
"""

from __future__ import annotations

import errno
import os
import stat
import sys
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import navkit._shared.files as files
from fake_clock import fake_clock_for
from navkit._shared.cores import usable_cores
from navkit._shared.files import atomic_path, atomic_paths


def _read_only(path: Any) -> bool:
    return os.path.exists(path) and not os.stat(path).st_mode & stat.S_IWUSR


def _pretend_windows(
    monkeypatch: pytest.MonkeyPatch, holds: dict[str, int] | None = None
) -> list[str]:
    """Windows' renames and removals; ``holds[name]``: renames over ``name`` refused first.

    Returns the list of renamed-to names, one entry per attempt.
    """
    real_replace, real_unlink = os.replace, os.unlink
    attempts: list[str] = []
    left = dict(holds or {})

    def replace(src: Any, dst: Any) -> None:
        name = os.path.basename(dst)
        attempts.append(name)
        if _read_only(dst):  # MoveFileEx over a read-only file: access denied
            raise PermissionError(errno.EACCES, "Access is denied", str(dst))
        if left.get(name, 0) > 0:  # another program has it open
            left[name] -= 1
            raise PermissionError(errno.EACCES, "Access is denied", str(dst))
        real_replace(src, dst)

    def unlink(path: Any, *, dir_fd: Any = None) -> None:
        if _read_only(path):  # DeleteFile of a read-only file: access denied
            raise PermissionError(errno.EACCES, "Access is denied", str(path))
        real_unlink(path, dir_fd=dir_fd)

    monkeypatch.setattr(sys, "platform", "win32")
    monkeypatch.setattr(os, "replace", replace)
    monkeypatch.setattr(os, "unlink", unlink)
    monkeypatch.setattr(files, "_WINDOWS_RETRY_SECONDS", 0.2, raising=False)
    # The retries' 0.2 s on a clock that moves only as they sleep: on the real one a
    # loaded machine's pause of the process can outlast it before a brief hold ends.
    fake_clock_for(monkeypatch, files)
    return attempts


def test_windows_read_only_target_is_refused_without_leftovers(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    target = tmp_path / "map.yaml"
    target.write_text("old")
    target.chmod(0o444)
    _pretend_windows(monkeypatch)
    with pytest.raises(PermissionError) as raised, atomic_path(target) as temporary:
        temporary.write_text("new")
    # The error is the target's (not a failed clean-up's), and nothing is left behind:
    # a temporary file given the target's read-only flag could not be removed.
    assert raised.value.filename == str(target)
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["map.yaml"]


@pytest.mark.parametrize("holds", [1, 3])
def test_windows_rename_waits_for_a_brief_hold(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, holds: int
) -> None:
    image, yaml = tmp_path / "map.pgm", tmp_path / "map.yaml"
    image.write_text("old image")
    yaml.write_text("old yaml")
    attempts = _pretend_windows(monkeypatch, {"map.yaml": holds})
    with atomic_paths([image, yaml]) as (ti, ty):
        ti.write_text("new image")
        ty.write_text("new yaml")
    assert (image.read_text(), yaml.read_text()) == ("new image", "new yaml")
    assert attempts.count("map.yaml") == holds + 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.pgm", "map.yaml"]


def test_windows_lasting_hold_fails_and_puts_the_pair_back(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    image, yaml = tmp_path / "map.pgm", tmp_path / "map.yaml"
    image.write_text("old image")
    yaml.write_text("old yaml")
    attempts = _pretend_windows(monkeypatch, {"map.yaml": 10**9})
    with pytest.raises(PermissionError), atomic_paths([image, yaml]) as (ti, ty):
        ti.write_text("new image")
        ty.write_text("new yaml")
    assert (image.read_text(), yaml.read_text()) == ("old image", "old yaml")
    assert attempts.count("map.yaml") > 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.pgm", "map.yaml"]


def test_linux_rename_is_not_tried_again(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    target = tmp_path / "out.json"
    calls = []

    def replace(src: Any, dst: Any) -> None:
        calls.append(dst)
        raise PermissionError(errno.EACCES, "refused", str(dst))

    monkeypatch.setattr(os, "replace", replace)
    with pytest.raises(PermissionError), atomic_path(target) as temporary:
        temporary.write_text("{}")
    assert len(calls) == 1
    assert list(tmp_path.iterdir()) == []


class _FakeFcntl:
    """``fcntl`` of macOS: ``F_FULLFSYNC`` records the content it flushes."""

    F_FULLFSYNC = 51

    def __init__(self, fails: bool) -> None:
        self.fails = fails
        self.flushed: list[bytes] = []

    def fcntl(self, fd: int, command: int, *args: Any) -> int:
        assert command == self.F_FULLFSYNC
        if self.fails:  # as on a network share
            raise OSError(errno.ENOTSUP, "Operation not supported")
        if stat.S_ISREG(os.fstat(fd).st_mode):
            self.flushed.append(os.pread(fd, 1 << 10, 0))
        return 0


@given(content=st.binary(min_size=1, max_size=64), fails=st.booleans())
@settings(max_examples=20, deadline=None)
def test_macos_flushes_the_drive_cache(tmp_path_factory: pytest.TempPathFactory,
                                       content: bytes, fails: bool) -> None:  # fmt: skip
    folder = tmp_path_factory.mktemp("fullfsync")
    fake = _FakeFcntl(fails)
    synced: list[bytes] = []
    real_fsync = os.fsync

    def fsync(fd: int) -> None:
        if stat.S_ISREG(os.fstat(fd).st_mode):
            synced.append(os.pread(fd, 1 << 10, 0))
        real_fsync(fd)

    with pytest.MonkeyPatch.context() as monkeypatch:
        monkeypatch.setattr(sys, "platform", "darwin")
        monkeypatch.setattr(files, "fcntl", fake, raising=False)
        monkeypatch.setattr(os, "fsync", fsync)
        with atomic_path(folder / "map.pgm") as temporary:
            temporary.write_bytes(content)
    assert (folder / "map.pgm").read_bytes() == content
    # F_FULLFSYNC where it works, else fsync: the content flushed once either way.
    assert (fake.flushed, synced) == (([], [content]) if fails else ([content], []))


def test_cores_without_affinity(monkeypatch: pytest.MonkeyPatch) -> None:
    # macOS and Windows have no sched_getaffinity: every core counts.
    monkeypatch.delattr(os, "sched_getaffinity", raising=False)
    monkeypatch.setattr(os, "cpu_count", lambda: 6)
    assert usable_cores() == 6
    monkeypatch.setattr(os, "cpu_count", lambda: None)
    assert usable_cores() == 1


def _short_paths(monkeypatch: pytest.MonkeyPatch) -> None:
    """``os.open`` refuses paths of 260 characters or more, as Windows' without long paths."""
    real = os.open

    def fake(path: Any, flags: int, mode: int = 0o777, *, dir_fd: Any = None) -> int:
        if len(os.fspath(path)) >= 260:
            exc = FileNotFoundError(errno.ENOENT, "The system cannot find the path specified",
                                    os.fspath(path))  # fmt: skip
            exc.winerror = 3  # type: ignore[attr-defined]
            raise exc
        return real(path, flags, mode, dir_fd=dir_fd)

    monkeypatch.setattr(os, "open", fake)


@pytest.mark.parametrize("length", [240, 246, 252, 259])
def test_windows_target_just_short_of_max_path(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, length: int
) -> None:
    # A target a plain write reaches, whose usual temporary name (14 characters
    # longer) Windows would not: the short name is used instead.
    stem_length = length - len(str(tmp_path)) - len("/.json")
    assert stem_length > 14
    target = tmp_path / ("m" * stem_length + ".json")
    assert len(str(target)) == length
    monkeypatch.setattr(sys, "platform", "win32")
    _short_paths(monkeypatch)
    with atomic_path(target) as temporary:
        assert len(str(temporary)) < 260
        assert temporary.suffix == ".json"
        temporary.write_text("{}")
    assert target.read_text() == "{}"
    assert [p.name for p in tmp_path.iterdir()] == [target.name]


def test_linux_missing_folder_is_not_taken_for_a_long_path(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    _short_paths(monkeypatch)
    target = tmp_path / ("m" * (260 - len(str(tmp_path))) + ".json")
    with pytest.raises(FileNotFoundError), atomic_path(target) as temporary:
        temporary.write_text("{}")
    assert list(tmp_path.iterdir()) == []
