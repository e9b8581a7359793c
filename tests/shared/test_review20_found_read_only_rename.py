"""Windows: a rename over a read-only target fails at once (review 20, FOUND item 4).

Windows refuses ``MoveFileEx`` over a read-only file (``PermissionError``)
for as long as the file stays read-only; the rename-retry loop, meant for the
brief holds of virus scanners and indexers, waited its whole second before
failing. Simulated on Linux as the portability tests do: ``sys.platform`` and
a fake ``os.replace`` that refuses a target without write permission (what
Python's ``os.stat`` reports for a file with ``FILE_ATTRIBUTE_READONLY``).
"""

from __future__ import annotations

import errno
import os
import stat
import sys
from pathlib import Path
from typing import Any

import pytest

import navkit._shared.files as files
from navkit._shared.files import atomic_path, atomic_paths


def _pretend_windows(monkeypatch: pytest.MonkeyPatch, holds: int = 0) -> list[str]:
    """Windows' renames; the first ``holds`` over a writable file refused (a brief hold)."""
    real_replace = os.replace
    attempts: list[str] = []
    left = [holds]

    def replace(src: Any, dst: Any) -> None:
        attempts.append(os.path.basename(dst))
        if os.path.exists(dst) and not os.stat(dst).st_mode & stat.S_IWUSR:
            raise PermissionError(errno.EACCES, "Access is denied", str(dst))
        if left[0] > 0:
            left[0] -= 1
            raise PermissionError(errno.EACCES, "Access is denied", str(dst))
        real_replace(src, dst)

    def no_sleep(seconds: float) -> None:  # a wait for a file that stays read-only
        raise AssertionError(f"waited {seconds} s for a read-only target")

    monkeypatch.setattr(sys, "platform", "win32")
    monkeypatch.setattr(os, "replace", replace)
    monkeypatch.setattr(files.time, "sleep", no_sleep)
    monkeypatch.setattr(files, "_WINDOWS_RETRY_SECONDS", 30.0)
    return attempts


def test_a_read_only_target_fails_at_the_first_refusal(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    target = tmp_path / "map.yaml"
    target.write_text("old")
    target.chmod(0o444)
    attempts = _pretend_windows(monkeypatch)
    with pytest.raises(PermissionError) as raised, atomic_path(target) as temporary:
        temporary.write_text("new")
    assert raised.value.filename == str(target)
    assert attempts == ["map.yaml"]
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["map.yaml"]


def test_a_read_only_yaml_puts_the_image_back_at_once(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    image, yaml = tmp_path / "map.pgm", tmp_path / "map.yaml"
    image.write_text("old image")
    yaml.write_text("old yaml")
    yaml.chmod(0o444)
    attempts = _pretend_windows(monkeypatch)
    with pytest.raises(PermissionError), atomic_paths([image, yaml]) as (ti, ty):
        ti.write_text("new image")
        ty.write_text("new yaml")
    assert (image.read_text(), yaml.read_text()) == ("old image", "old yaml")
    assert attempts.count("map.yaml") == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.pgm", "map.yaml"]


def test_a_writable_target_held_briefly_is_still_waited_for(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    target = tmp_path / "map.yaml"
    target.write_text("old")
    attempts = _pretend_windows(monkeypatch, holds=2)
    slept: list[float] = []
    monkeypatch.setattr(files.time, "sleep", slept.append)
    with atomic_path(target) as temporary:
        temporary.write_text("new")
    assert target.read_text() == "new"
    assert attempts == ["map.yaml"] * 3 and len(slept) == 2


def test_read_only_reads_the_windows_attribute_where_there_is_one(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = tmp_path / "f"
    path.write_text("x")
    assert not files._read_only(path)
    assert not files._read_only(tmp_path / "missing")  # gone: no reason to stop waiting
    real_lstat = os.lstat

    class WindowsStat:
        def __init__(self, info: os.stat_result, attributes: int) -> None:
            self.st_mode = info.st_mode  # writable: the attribute decides
            self.st_file_attributes = attributes

    for attributes, want in ((stat.FILE_ATTRIBUTE_READONLY | 0x20, True), (0x20, False)):
        monkeypatch.setattr(os, "lstat", lambda p, a=attributes: WindowsStat(real_lstat(p), a))
        assert files._read_only(path) is want
