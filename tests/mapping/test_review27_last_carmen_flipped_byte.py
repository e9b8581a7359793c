"""A compressed CARMEN log with a damaged byte is named damaged, not malformed (review 27).

Review 26's bullet: "a damaged compressed file names its compression". But gzip
checks its CRC at the end of the file and bzip2 at the end of each block, after
the damaged data has come out: most single flipped bits were reported as a
malformed line in the middle ("log:4: malformed ODOM line: 34 fields ..."),
which sends the user looking for a bad line that the file never had (of 40
random flips of the Intel log, 34 in its gzip file, 33 in bzip2, 12 in xz).
A malformed line of a compressed log is now checked against the rest of the
file, whose failed check is reported instead.
"""

from __future__ import annotations

import bz2
import gzip
import lzma
import random
from collections.abc import Callable
from pathlib import Path

import pytest

from navkit.mapping.io import read_carmen

BODY = (
    "ODOM 0.5 0 0 0 0 0 0.5 h 0.5\n"
    "FLASER 3 1.0 2.0 5.0 0.5 0 0 0.5 0 0 1.0 host 1.0\n"
    "ROBOTLASER1 0 -0.5 1.0 0.25 8.0 0.01 0 5 1.5 1.5 1.5 1.5 1.5 0 "
    "1.0 2.0 0.1 0.9 2.0 0.1 0 0 0 0 0 2.0 host 2.1\n"
)
CODECS: dict[str, Callable[[bytes], bytes]] = {
    "gzip": gzip.compress, "bzip2": bz2.compress, "xz": lzma.compress,
}  # fmt: skip


def _numbered(n: int) -> bytes:
    # Lines that differ, so that the compressed data is not one repeated match.
    return "".join(
        f"ODOM {k * 0.01:.2f} {k % 7} 0 0 0 0 {k * 0.5} h {k * 0.5}\n" + BODY for k in range(n)
    ).encode()


@pytest.mark.parametrize("name", sorted(CODECS))
def test_a_flipped_bit_is_reported_as_damage(tmp_path: Path, name: str) -> None:
    good = CODECS[name](_numbered(400))
    rng = random.Random(27)
    path = tmp_path / "log"
    messages = []
    for _ in range(12):
        damaged = bytearray(good)
        damaged[rng.randrange(32, len(good) - 16)] ^= 1 << rng.randrange(8)
        path.write_bytes(bytes(damaged))
        try:
            read_carmen(path)
        except ValueError as exc:
            messages.append(str(exc))
        else:  # pragma: no cover - a flip that leaves valid numbers and a valid check
            pytest.fail("a damaged file was read")
    assert [m for m in messages if f"corrupt or truncated {name} file" not in m] == []


def test_a_malformed_line_of_an_intact_compressed_log_is_still_named(tmp_path: Path) -> None:
    path = tmp_path / "log.gz"
    path.write_bytes(gzip.compress((BODY + "ODOM 1 2\n" + BODY).encode()))
    with pytest.raises(ValueError, match=r"log\.gz:4: malformed ODOM line"):
        read_carmen(path)
