"""The checked path handed to rosbags: its two documented limits (mutation testing, review 10).

``_CheckedPath`` opens reads with ``open_regular`` and leaves "opens for writing"
to :class:`pathlib.Path` (appending is writing too); ``read_text`` reads at most
``METADATA_MAX`` bytes: a file of exactly that size is read, one byte more refused.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from navkit.mapping.io import _bags
from navkit.mapping.io._bags import _CheckedPath


@pytest.mark.parametrize("mode", ["a", "at", "ab"])
def test_opening_to_append_is_left_to_path(tmp_path: Path, mode: str) -> None:
    plain = tmp_path / "notes.txt"
    plain.write_text("one\n")
    data = "two\n" if "b" not in mode else b"two\n"
    with _CheckedPath(plain).open(mode) as fh:
        fh.write(data)
    assert plain.read_text() == "one\ntwo\n"


@pytest.mark.parametrize("mode", ["r", "rb"])
def test_reads_still_get_the_checked_opener(tmp_path: Path, mode: str) -> None:
    plain = tmp_path / "notes.txt"
    plain.write_text("one\n")
    with _CheckedPath(plain).open(mode) as fh:
        assert fh.read() in ("one\n", b"one\n")
        with pytest.raises(OSError):
            fh.write("x" if mode == "r" else b"x")


def test_read_text_reads_up_to_metadata_max_bytes(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    limit = 64  # the module's limit, lowered for the test (read at call time)
    monkeypatch.setattr(_bags, "METADATA_MAX", limit)
    at_limit = tmp_path / "at.yaml"
    at_limit.write_text("x" * limit)
    assert _CheckedPath(at_limit).read_text() == "x" * limit
    over = tmp_path / "over.yaml"
    over.write_text("x" * (limit + 1))
    with pytest.raises(ValueError, match=f"larger than {limit} bytes"):
        _CheckedPath(over).read_text()
