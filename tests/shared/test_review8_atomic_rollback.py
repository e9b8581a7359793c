"""atomic_paths puts back the targets it renamed when a later rename fails."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest

from navkit._shared.files import atomic_paths


def _failing_replace(fail_at: int) -> Any:
    """``os.replace`` that raises PermissionError on its ``fail_at``-th call (from 1)."""
    real = os.replace
    calls = [0]

    def replace(src: Any, dst: Any) -> None:
        calls[0] += 1
        if calls[0] == fail_at:
            raise PermissionError(f"refused rename to {dst}")
        real(src, dst)

    return replace


@pytest.mark.parametrize("fail_at", [2, 3])
def test_a_failed_rename_puts_back_the_earlier_targets(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, fail_at: int
) -> None:
    image, fresh, yaml = tmp_path / "map.pgm", tmp_path / "new.txt", tmp_path / "map.yaml"
    image.write_text("old image")
    yaml.write_text("old yaml")
    os.chmod(image, 0o640)
    monkeypatch.setattr(os, "replace", _failing_replace(fail_at))
    with pytest.raises(PermissionError), atomic_paths([image, fresh, yaml]) as temps:
        for temp, text in zip(temps, ("new image", "new", "new yaml"), strict=True):
            temp.write_text(text)
    # The old pair, not the new image with the old YAML; a target that did not
    # exist is gone again; nothing else is left in the folder.
    assert image.read_text() == "old image"
    assert yaml.read_text() == "old yaml"
    assert not fresh.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.pgm", "map.yaml"]
    assert os.stat(image).st_mode & 0o777 == 0o640


def test_success_leaves_no_backup(tmp_path: Path) -> None:
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_text("old")
    with atomic_paths([a, b]) as (ta, tb):
        ta.write_text("A")
        tb.write_text("B")
    assert (a.read_text(), b.read_text()) == ("A", "B")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt", "b.txt"]
    assert os.stat(a).st_nlink == 1


def test_a_symbolic_link_target_is_put_back_as_a_link(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    real = tmp_path / "real.txt"
    real.write_text("pointed to")
    link, other = tmp_path / "link.txt", tmp_path / "other.txt"
    link.symlink_to(real)
    monkeypatch.setattr(os, "replace", _failing_replace(2))
    with pytest.raises(PermissionError), atomic_paths([link, other]) as (tl, to):
        tl.write_text("new")
        to.write_text("new")
    assert link.is_symlink() and link.read_text() == "pointed to"


def test_a_target_that_cannot_be_linked_is_not_removed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Without hard links (os.link refused) the rollback took an existing target
    # for one that did not exist, and deleted it: neither version was left.
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_text("old a")
    b.write_text("old b")

    def no_link(*args: Any, **kwargs: Any) -> None:
        raise PermissionError("no hard links here")

    monkeypatch.setattr(os, "link", no_link)
    monkeypatch.setattr(os, "replace", _failing_replace(2))
    with pytest.raises(PermissionError), atomic_paths([a, b]) as (ta, tb):
        ta.write_text("new a")
        tb.write_text("new b")
    # As documented: a target before the failed rename that could not be linked stays new.
    assert a.read_text() == "new a"
    assert b.read_text() == "old b"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt", "b.txt"]
