"""Temporary names of navkit._shared.files on file systems whose name limit
pathconf does not state in bytes, or states as "none"."""

from __future__ import annotations

import errno
import os
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit._shared import files
from navkit._shared.files import atomic_path


def capture_temporary(target: Path) -> tuple[str, str]:
    """Write ``target`` through atomic_path; (the temporary's name, the written text)."""
    with atomic_path(target) as temporary:
        temporary.write_text("data")
        name = temporary.name
    return name, target.read_text()


@pytest.mark.parametrize("answer", [-1, 0])
def test_no_stated_limit_keeps_the_suffix(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, answer: int
) -> None:
    # pathconf answers -1 for "no limit"; taken as the limit it cut every name
    # to ".{tag}.tmp", dropping the suffix a writer (matplotlib) picks its format from.
    monkeypatch.setattr(os, "pathconf", lambda *_: answer)
    name, text = capture_temporary(tmp_path / "plot.png")
    assert name.startswith(".plot.") and name.endswith(".tmp.png")
    assert text == "data"


def limited_in_characters(limit: int) -> Any:
    """os.open of a file system that counts characters (vfat) and reports ``6 * limit`` bytes."""
    real_open = os.open

    def fake_open(path: Any, flags: int, *args: Any) -> int:
        if len(Path(path).name) > limit:
            raise OSError(errno.ENAMETOOLONG, os.strerror(errno.ENAMETOOLONG), str(path))
        return real_open(path, flags, *args)

    return fake_open


@pytest.mark.parametrize("stem", ["a" * 240, "é" * 5 + "a" * 236])
def test_a_limit_in_characters_is_met(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, stem: str
) -> None:
    # vfat: 255 characters, pathconf 1530 "bytes". A legal 244-character name's
    # temporary (258 characters, fewer bytes than 1530) was refused: ENAMETOOLONG.
    target = tmp_path / f"{stem}.png"
    assert len(target.name) <= 255 and len(os.fsencode(target.name)) <= 255
    monkeypatch.setattr(os, "pathconf", lambda *_: 6 * 255)
    monkeypatch.setattr(os, "open", limited_in_characters(255))
    name, text = capture_temporary(target)
    assert len(name) <= 255 and name.endswith(".tmp.png")
    assert text == "data"
    assert sorted(p.name for p in tmp_path.iterdir()) == [target.name]


def test_a_name_the_file_system_refuses_anyway_is_an_error(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(os, "open", limited_in_characters(10))
    with pytest.raises(OSError) as info, atomic_path(tmp_path / "a-long-name.txt"):
        pass  # pragma: no cover
    assert info.value.errno == errno.ENAMETOOLONG
    assert list(tmp_path.iterdir()) == []


@given(
    stem=st.text(
        st.characters(codec="utf-8", exclude_characters="/\x00."),
        min_size=1,
        max_size=120,
    ),
    suffix=st.sampled_from(["", ".png", ".yaml", ".é"]),
)
def test_the_compact_name_is_never_longer_than_the_target(stem: str, suffix: str) -> None:
    # Whatever the file system counts: UTF-8 bytes, characters or UTF-16 units.
    target = Path(stem + suffix)
    name = files._compact_name(target, "0123abcd")

    def measures(text: str) -> tuple[int, int, int]:
        return len(text.encode()), len(text), len(text.encode("utf-16-le")) // 2

    if len(target.stem) > 14:
        assert name.endswith(f".0123abcd.tmp{target.suffix}")
        assert all(m <= t for m, t in zip(measures(name), measures(target.name), strict=True))
    else:
        assert name == ".0123abcd.tmp"
