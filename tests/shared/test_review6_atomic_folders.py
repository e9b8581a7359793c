"""A target that is a folder fails the write before any target is replaced."""

from __future__ import annotations

from pathlib import Path

import pytest

from navkit._shared.files import atomic_paths


def _names(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir())


def test_a_folder_among_the_targets_leaves_the_others_untouched(tmp_path: Path) -> None:
    first, second = tmp_path / "m.yaml", tmp_path / "m.png"
    first.write_text("old")
    second.mkdir()
    entered = False
    with pytest.raises(IsADirectoryError), atomic_paths([first, second]):
        entered = True
    assert not entered  # refused before the caller writes anything
    assert first.read_text() == "old"
    assert _names(tmp_path) == ["m.png", "m.yaml"]


def test_a_folder_made_during_the_block_leaves_the_others_untouched(tmp_path: Path) -> None:
    first, second = tmp_path / "m.yaml", tmp_path / "m.png"
    first.write_text("old")
    with pytest.raises(IsADirectoryError), atomic_paths([first, second]) as temporaries:
        for temporary in temporaries:
            temporary.write_text("new")
        second.mkdir()  # another program, meanwhile
    assert first.read_text() == "old"
    assert _names(tmp_path) == ["m.png", "m.yaml"] and second.is_dir()
