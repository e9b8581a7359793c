"""A plain CARMEN log cut inside its last line: an error naming the file and line, never a
silently wrong timestamp."""

from __future__ import annotations

import gzip
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import read_carmen

FLASER = "FLASER 3 1.0 2.0 5.0 0.5 0 0 0.5 0 0 12.25 host 12.3\n"
ODOM = "ODOM -13.5122 -38.258 2.97255 0 0 0 480.86 pippo 480.86\n"
RL1 = (
    "ROBOTLASER1 0 -1.5 3.0 1.0 8.0 0.01 0 4 1.0 2.0 3.0 4.0 0 "
    "1.0 2.0 0.1 0.9 2.0 0.1 0 0 0 0 0 123.5 host 123.6\n"
)


@pytest.mark.parametrize(
    ("text", "line"),
    [
        (FLASER + ODOM[: ODOM.index("480.86") + 3], 2),  # ODOM's timestamp read 480, not 480.86
        (FLASER + FLASER[: FLASER.index("12.25") + 2], 2),  # FLASER's read 12, not 12.25
        (FLASER + RL1[: RL1.index("123.5") + 3], 2),  # ROBOTLASER1's read 123, not 123.5
    ],
    ids=["ODOM", "FLASER", "ROBOTLASER1"],
)
def test_a_last_line_cut_inside_its_timestamp_raises(tmp_path: Path, text: str, line: int) -> None:
    for name, data in (("log.txt", text.encode()), ("log.gz", gzip.compress(text.encode()))):
        path = tmp_path / name
        path.write_bytes(data)
        with pytest.raises(ValueError, match=rf"{name}:{line}: malformed .*truncated"):
            read_carmen(path)
        # The same line whole (with its newline) reads.
        path.write_bytes(text.encode() + b"\n")
        assert len(read_carmen(path)) >= 1


def test_last_lines_that_are_whole_read_with_or_without_a_newline(tmp_path: Path) -> None:
    path = tmp_path / "log.txt"
    for tail in (ODOM, ODOM.rstrip("\n"), ODOM[: ODOM.rindex(" ")], ODOM[: ODOM.rindex(" ") - 2]):
        # With the host after it, the timestamp is whole even if the rest was cut.
        path.write_text(FLASER + tail)
        log = read_carmen(path)
        np.testing.assert_array_equal(log.odometry[:, 3], [480.86])
        assert log.times.tolist() == [12.25]
    path.write_text(FLASER.rstrip("\n"))
    assert read_carmen(path).times.tolist() == [12.25]
    path.write_text(FLASER + "O")  # an unknown record kind, cut or not, is skipped
    assert len(read_carmen(path)) == 1
    path.write_text(FLASER.replace(" host 12.3", "") + "ODOM 1 2 0.5 0 0 0 9.0\r\n")
    assert read_carmen(path).odometry[:, 3].tolist() == [9.0]


def test_cuts_of_a_real_log_raise_or_read_a_prefix(shared_data: Path, tmp_path: Path) -> None:
    full = gzip.decompress((shared_data / "carmen-logs" / "aces-corrected.log.gz").read_bytes())
    whole = read_carmen(shared_data / "carmen-logs" / "aces-corrected.log.gz")
    path = tmp_path / "cut.log"
    rng = np.random.default_rng(7)
    for cut in rng.integers(len(full) // 2, len(full), 25):
        path.write_bytes(full[:cut])
        try:
            log = read_carmen(path)
        except ValueError as exc:
            assert str(path) in str(exc)
            continue
        # What reads is exactly the records of the whole file up to the cut.
        n, m = len(log), log.odometry.shape[0]
        np.testing.assert_array_equal(log.times, whole.times[:n])
        np.testing.assert_array_equal(log.odometry, whole.odometry[:m])
        np.testing.assert_array_equal(log.scans[-1].ranges, whole.scans[n - 1].ranges)
