"""A map YAML's refused byte that is not UTF-8 is the one in the refused value (review 51, FRESH).

Since 3b24558 ``read_map`` reads a YAML holding bytes that are not UTF-8 (a
Latin-1 editor's) as map_server's yaml-cpp does: skipped in comments, looked up
as written in the image name, refused in a number, list or ``mode``. The
refusal named the file's first such byte, which may be one read without
complaint (in a comment or the image name), not the refused value's: a user
looking at that offset found nothing wrong there. It names the refused
value's first byte now, at its offset in the file (bytes, not characters).
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from navkit.mapping.io import read_map

_REST = b"negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"


def _refusal(tmp_path: Path, data: bytes) -> str:
    (tmp_path / "map.yaml").write_bytes(data)
    with pytest.raises(ValueError, match=r"map\.yaml: not a map YAML: not UTF-8 text") as info:
        read_map(tmp_path / "map.yaml")
    return str(info.value)


def _named(data: bytes, marker: bytes) -> str:
    """The refusal's text for the byte just after ``marker`` in ``data``."""
    offset = data.index(marker) + len(marker)
    return f"(byte 0x{data[offset]:02x} at offset {offset})"


@pytest.mark.parametrize(
    "data",
    [
        # A Latin-1 image name (read) before a Latin-1 mode (refused).
        b"image: b\xfcro.pgm\nmode: tri\xe4r\nresolution: 0.05\norigin: [0, 0, 0]\n" + _REST,
        # A Latin-1 comment (skipped) before a Latin-1 number.
        b"# Karte B\xfcro\nimage: m.pgm\nresolution: 0.05\xb5\norigin: [0, 0, 0]\n" + _REST,
    ],
)
def test_the_refused_values_byte_is_named_not_an_earlier_read_one(
    tmp_path: Path, data: bytes
) -> None:
    refused = max(i for i, byte in enumerate(data) if byte >= 0x80)
    message = _refusal(tmp_path, data)
    assert f"(byte 0x{data[refused]:02x} at offset {refused})" in message, message


def test_the_offset_counts_bytes_past_utf8_characters(tmp_path: Path) -> None:
    # Two-byte UTF-8 letters in the comment: the offset is the file's byte's, not
    # the text's character's.
    data = (
        "# Büro über Küche\n".encode()
        + b"image: m.pgm\nresolution: 0.05\norigin: [0, 0\xb0, 0]\n"
        + _REST
    )
    assert _named(data, b"[0, 0") in _refusal(tmp_path, data)


def test_of_two_refused_values_the_first_in_the_file_is_named(tmp_path: Path) -> None:
    data = b"image: m.pgm\nresolution: 0.05\xb5\norigin: [0, 0, 0]\nmode: tri\xe4r\n" + _REST
    for _ in range(3):  # whatever the order the keys are checked in
        assert _named(data, b"0.05") in _refusal(tmp_path, data)


def test_a_yaml_with_tabs_between_tokens_is_still_refused(tmp_path: Path) -> None:
    # Read by the tab-tolerant path, whose nodes are not at hand: the file's first
    # such byte is named, as before.
    data = b"image:\tb\xfcro.pgm\nmode:\ttri\xe4r\nresolution: 0.05\norigin: [0, 0, 0]\n" + _REST
    message = _refusal(tmp_path, data)
    assert re.search(r"\(byte 0x(fc|e4) at offset \d+\)", message), message


def test_a_yaml_error_below_a_latin1_comment_is_told_as_in_utf8(tmp_path: Path) -> None:
    # A list left open: the YAML's own error, at its line, as for the same file with
    # its comment in UTF-8 (it blamed the comment's accepted byte instead).
    body = b"image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: [0\n" + _REST[10:]
    messages = []
    for comment in ("# Karte Büro\n".encode("latin-1"), "# Karte Büro\n".encode()):
        (tmp_path / "map.yaml").write_bytes(comment + body)
        with pytest.raises(ValueError) as info:
            read_map(tmp_path / "map.yaml")
        messages.append(str(info.value))
    assert messages[0] == messages[1], messages
    assert re.search(r"map\.yaml:5: expected 'key: value' lines", messages[0]), messages[0]
