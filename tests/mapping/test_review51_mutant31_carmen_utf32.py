"""Review 51 (MUTANT31): a UTF-32-BE copy of a CARMEN log is named as UTF-16 and UTF-32-LE are.

PORTFILES' 8dfa2d1 names a UTF-16 or UTF-32 copy of a log (with its
byte-order mark) instead of reporting "no FLASER or ROBOTLASER1 lines". It
tells them by the mark's first two bytes, UTF-16's, which UTF-32-LE's mark
starts with too; UTF-32-BE's (``00 00 fe ff``) does not, and such a copy still
read as "no FLASER or ROBOTLASER1 lines". Found by a mutation review: dropping
UTF-16-LE's mark from the check left only the UTF-32-BE case unseen by the
tests, and it failed at HEAD already.
"""

from __future__ import annotations

import codecs
import gzip
from pathlib import Path

import pytest

from navkit.mapping.io import read_carmen

_LOG = Path("carmen-logs") / "intel-corrected.log.gz"


def _head(shared_data: Path, scans: int = 3) -> str:
    """The real log's lines up to its ``scans``-th FLASER line, as text."""
    kept: list[bytes] = []
    for line in gzip.decompress((shared_data / _LOG).read_bytes()).split(b"\n"):
        kept.append(line)
        scans -= line.startswith(b"FLASER ")
        if scans == 0:
            break
    return (b"\n".join(kept) + b"\n").decode("ascii")


@pytest.mark.parametrize(
    ("encoding", "mark"),
    [("utf-32-be", codecs.BOM_UTF32_BE), ("utf-32-le", codecs.BOM_UTF32_LE)],
    ids=["big-endian", "little-endian"],
)
def test_utf32_copies_of_either_byte_order_are_named(
    shared_data: Path, tmp_path: Path, encoding: str, mark: bytes
) -> None:
    data = mark + _head(shared_data).encode(encoding)
    for name, content in [("log.txt", data), ("log.txt.gz", gzip.compress(data))]:
        (tmp_path / name).write_bytes(content)
        with pytest.raises(ValueError, match=r"UTF-16 text \(or UTF-32\), not a CARMEN log"):
            read_carmen(tmp_path / name)


def test_a_log_starting_with_two_nuls_and_no_mark_is_not_named_utf32(tmp_path: Path) -> None:
    # Two NULs without fe next are no byte-order mark: reported as before.
    (tmp_path / "log.txt").write_bytes(b"\x00\x00FLASER 0\n")
    with pytest.raises(ValueError) as info:
        read_carmen(tmp_path / "log.txt")
    assert "UTF-16 text" not in str(info.value)
