"""atomic_paths when every random name it tries beside a target is taken.

The last lines of ``_backup`` and ``_new_temporary`` (after ``_ATTEMPTS`` names
in use) were marked ``# pragma: no cover``; a fixed ``token_hex`` reaches them.
"""

from __future__ import annotations

import os
import secrets
from pathlib import Path
from typing import Any

import pytest

from navkit._shared.files import atomic_paths

TAG = "0badc0de"


def _fixed_tags(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(secrets, "token_hex", lambda nbytes: TAG)


def _failing_second_replace() -> Any:
    real = os.replace
    calls = [0]

    def replace(src: Any, dst: Any) -> None:
        calls[0] += 1
        if calls[0] == 2:
            raise PermissionError(f"refused rename to {dst}")
        real(src, dst)

    return replace


def test_no_free_temporary_name_refuses_and_removes_nothing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    target = tmp_path / "a.txt"
    target.write_text("old")
    taken = tmp_path / f".a.{TAG}.tmp.txt"
    taken.write_text("someone else's")
    _fixed_tags(monkeypatch)
    with (
        pytest.raises(FileExistsError, match="cannot create a temporary file beside"),
        atomic_paths([target]),
    ):
        pytest.fail("the block must not run")
    assert target.read_text() == "old"
    assert taken.read_text() == "someone else's"
    assert sorted(p.name for p in tmp_path.iterdir()) == [taken.name, "a.txt"]


def test_no_free_backup_name_still_saves(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_text("old a")
    b.write_text("old b")
    taken = tmp_path / f".{TAG}.tmp"  # every hard link's name for these short stems
    taken.write_text("someone else's")
    _fixed_tags(monkeypatch)
    with atomic_paths([a, b]) as (ta, tb):
        ta.write_text("new a")
        tb.write_text("new b")
    assert (a.read_text(), b.read_text()) == ("new a", "new b")
    assert taken.read_text() == "someone else's"
    assert sorted(p.name for p in tmp_path.iterdir()) == [taken.name, "a.txt", "b.txt"]


def test_no_free_backup_name_leaves_an_old_target_new_not_removed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Without a hard link the first target cannot be put back after the second
    # rename fails; removing it would lose both of its versions.
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_text("old a")
    b.write_text("old b")
    taken = tmp_path / f".{TAG}.tmp"
    taken.write_text("someone else's")
    _fixed_tags(monkeypatch)
    monkeypatch.setattr(os, "replace", _failing_second_replace())
    with pytest.raises(PermissionError), atomic_paths([a, b]) as (ta, tb):
        ta.write_text("new a")
        tb.write_text("new b")
    assert (a.read_text(), b.read_text()) == ("new a", "old b")
    assert taken.read_text() == "someone else's"
    assert sorted(p.name for p in tmp_path.iterdir()) == [taken.name, "a.txt", "b.txt"]
