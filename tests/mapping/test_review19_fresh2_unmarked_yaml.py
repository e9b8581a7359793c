"""Review 19 (FRESH2): a map YAML in UTF-16 / UTF-32 without its byte-order mark is named.

YAML's own encoding detection (spec 1.2, section 5.2) reads NUL bytes among the
first four as UTF-16 or UTF-32 without a mark; the YAML reader, handed such
text decoded as UTF-8, reported an "unacceptable character #x0000" instead.
"""

from __future__ import annotations

import codecs
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.mapping.io._map_files import _unmarked_unicode, read_map_yaml

TEXT = (
    "image: m.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
    "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
)


@pytest.mark.parametrize(
    ("encoding", "bits"),
    [("utf-16-le", 16), ("utf-16-be", 16), ("utf-32-le", 32), ("utf-32-be", 32)],
)
def test_unmarked_utf16_and_utf32_are_named(tmp_path: Path, encoding: str, bits: int) -> None:
    (tmp_path / "m.yaml").write_bytes(TEXT.encode(encoding))
    with pytest.raises(ValueError, match=rf"not a map YAML: UTF-{bits} text without a byte-order"):
        read_map_yaml(tmp_path / "m.yaml")


@pytest.mark.parametrize(
    "data", [b"\x00", b"\x00\x00\x00\x00", b"ab\x00\x00\x00\x00cd", b"\x00\x01\x02\x03"]
)
def test_other_nul_bytes_are_not_called_unicode(tmp_path: Path, data: bytes) -> None:
    (tmp_path / "m.yaml").write_bytes(data)
    with pytest.raises(ValueError, match=r"m\.yaml: ") as info:
        read_map_yaml(tmp_path / "m.yaml")
    assert "without a byte-order mark" not in str(info.value)
    assert _unmarked_unicode(data) == 0


def test_marked_utf16_still_reads(tmp_path: Path) -> None:
    (tmp_path / "m.pgm").write_bytes(b"P5\n2 2\n255\n" + bytes([0, 255, 255, 0]))
    (tmp_path / "a.yaml").write_bytes(codecs.BOM_UTF16_LE + TEXT.encode("utf-16-le"))
    (tmp_path / "b.yaml").write_text(TEXT, encoding="utf-8")
    assert read_map_yaml(tmp_path / "a.yaml") == read_map_yaml(tmp_path / "b.yaml")


@settings(max_examples=200, deadline=None)
@given(
    st.text(min_size=1, max_size=40).filter(lambda s: 0x20 <= ord(s[0]) < 0x7F and "\x00" not in s),
    st.sampled_from(["utf-16-le", "utf-16-be", "utf-32-le", "utf-32-be"]),
)
def test_unicode_text_with_an_ascii_start_is_named_by_its_width(text: str, encoding: str) -> None:
    data = text.encode(encoding, errors="surrogatepass")[:64]
    assert _unmarked_unicode(data) == int(encoding[4:6])
