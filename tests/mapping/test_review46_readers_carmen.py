"""``read_carmen`` on damaged and unusual copies of the real Radish logs (review 46).

A UTF-8 byte-order mark before a first FLASER line was read as part of the
line's kind ("\\ufffd\\ufffd\\ufffdFLASER"), an unknown kind, so that scan was
dropped without a word; the mark is now skipped. Truncations anywhere give the
log up to the last whole line or a ``ValueError`` naming the file, compressed
copies cut or with a flipped bit a ``ValueError`` naming the file, and the real
logs read as an independent split of their lines says they hold.
"""

from __future__ import annotations

import bisect
import bz2
import gzip
import lzma
import random
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import CarmenLog, read_carmen
from reader_outcomes import outcome

LOGS = "carmen-logs"
BOM = b"\xef\xbb\xbf"
COMPRESSORS: dict[str, Callable[[bytes], bytes]] = {
    "plain": lambda data: data,
    "gzip": gzip.compress,
    "bzip2": bz2.compress,
    "xz": lzma.compress,
}


def _text(shared_data: Path, name: str = "aces") -> bytes:
    with gzip.open(shared_data / LOGS / f"{name}-corrected.log.gz", "rb") as fh:
        return fh.read()


def _excerpt(shared_data: Path, size: int = 60_000) -> bytes:
    """The first whole lines of the aces log, about ``size`` bytes (some 30 scans)."""
    text = _text(shared_data)
    return text[: text.rindex(b"\n", 0, size) + 1]


def _content(log: CarmenLog) -> tuple[bytes, ...]:
    """Everything a log holds, as bytes to compare exactly."""
    return (
        np.array([s.ranges for s in log.scans]).tobytes(),
        np.array([(s.angle_min, s.angle_increment, s.range_max) for s in log.scans]).tobytes(),
        np.array([p.as_array() for p in log.laser_poses]).tobytes(),
        np.array([p.as_array() for p in log.robot_poses]).tobytes(),
        log.times.tobytes(),
        log.odometry.tobytes(),
    )


# ------------------------------------------------------------------ byte-order mark
@pytest.mark.parametrize("compression", list(COMPRESSORS))
def test_a_byte_order_mark_before_a_first_flaser_line_is_skipped(
    tmp_path: Path, compression: str
) -> None:
    text = (
        b"FLASER 3 1.0 2.0 5.0 0.5 0 0 0.5 0 0 12.5 host 12.6\n"
        b"FLASER 3 1.5 2.5 5.0 0.6 0 0 0.6 0 0 13.5 host 13.6\n"
    )
    compress = COMPRESSORS[compression]
    plain, marked = tmp_path / "plain.log", tmp_path / "marked.log"
    plain.write_bytes(compress(text))
    marked.write_bytes(compress(BOM + text))
    log = read_carmen(marked)
    assert log.times.tolist() == [12.5, 13.5]  # the first scan was dropped
    assert _content(log) == _content(read_carmen(plain))


@pytest.mark.parametrize("compression", ["plain", "gzip"])
def test_the_real_log_with_a_byte_order_mark_and_other_line_ends_reads_the_same(
    shared_data: Path, tmp_path: Path, compression: str
) -> None:
    text = _text(shared_data)
    # The first scan's line first: what the mark would hide.
    first = text.index(b"\nFLASER ") + 1
    text = text[first:]
    expected = _content(read_carmen(shared_data / LOGS / "aces-corrected.log.gz"))
    compress = COMPRESSORS[compression]
    for variant in (BOM + text, text.replace(b"\n", b"\r\n"), BOM + text.replace(b"\n", b"\r")):
        path = tmp_path / "aces.log"
        path.write_bytes(compress(variant))
        got = _content(read_carmen(path))
        # The lines cut off above hold ODOM records only.
        assert got[:5] == expected[:5]
        assert len(got[5]) < len(expected[5]) and expected[5].endswith(got[5])


# ------------------------------------------------------------------ truncation
def _check_cuts(tmp_path: Path, text: bytes, offsets: list[int]) -> None:
    """A log cut at each offset reads as the lines before the cut, or with the cut line
    whole (cut in its host or logger time, after the fields read), or is refused."""
    lines = text.splitlines(keepends=True)
    ends = np.cumsum([0] + [len(line) for line in lines]).tolist()
    path = tmp_path / "cut.log"
    cache: dict[int, tuple[bytes, ...] | None] = {}

    def upto(end: int) -> tuple[bytes, ...] | None:
        if end not in cache:
            cache[end] = outcome(read_carmen, _content, path, text[:end])
        return cache[end]

    for offset in offsets:
        got = outcome(read_carmen, _content, path, text[:offset])
        if got is None:
            continue
        i = bisect.bisect_right(ends, offset) - 1
        if ends[i] == offset:
            continue  # a cut at a line end: a shorter log, nothing tells
        allowed = [upto(ends[i]), upto(ends[i + 1])]
        assert got in allowed, (offset, lines[i][:40], text[ends[i] : offset][-40:])


def test_cuts_at_sampled_offsets_give_whole_lines_or_an_error(
    shared_data: Path, tmp_path: Path
) -> None:
    text = _excerpt(shared_data)
    rng = random.Random(46)
    _check_cuts(tmp_path, text, sorted(rng.sample(range(1, len(text)), 120)))


@pytest.mark.slow
def test_cuts_at_every_offset_of_several_lines_give_whole_lines_or_an_error(
    shared_data: Path, tmp_path: Path
) -> None:
    text = _excerpt(shared_data, 200_000)
    lines = text.splitlines(keepends=True)
    starts = np.cumsum([0] + [len(line) for line in lines]).tolist()
    rng = random.Random(4646)
    offsets: list[int] = []
    # Every byte of one line of each kind near the end (FLASER, NEFF, ODOM), and
    # every line end.
    for kind in (b"FLASER", b"NEFF", b"ODOM"):
        i = max(j for j, line in enumerate(lines) if line.startswith(kind))
        offsets.extend(range(starts[i], starts[i + 1] + 1))
    offsets.extend(starts[1:])
    offsets.extend(rng.sample(range(1, len(text)), 400))
    _check_cuts(tmp_path, text, sorted(set(offsets)))


@pytest.mark.parametrize("compression", ["gzip", "bzip2", "xz"])
def test_compressed_logs_cut_or_with_a_flipped_bit_are_refused_naming_the_file(
    shared_data: Path, tmp_path: Path, compression: str
) -> None:
    data = COMPRESSORS[compression](_excerpt(shared_data))
    rng = random.Random(f"46{compression}")
    path = tmp_path / "damaged.log"
    for _ in range(25):
        offset = rng.randrange(len(data))
        flipped = bytearray(data)
        flipped[offset] ^= 1 << rng.randrange(8)
        for damaged in (data[:offset], bytes(flipped)):
            assert outcome(read_carmen, _content, path, damaged) is None, offset


# ------------------------------------------------------------------ the real logs
def _independent(text: bytes) -> dict[str, np.ndarray]:
    """The FLASER and ODOM records of a log by splitting its lines (no checks)."""
    ranges, laser, robot, times, odometry = [], [], [], [], []
    for line in text.decode("ascii").splitlines():
        words = line.split()
        if words[:1] == ["FLASER"]:
            n = int(words[1])
            values = [float(w) for w in words[2 : n + 9]]
            ranges.append(values[:n])
            laser.append(values[n : n + 3])
            robot.append(values[n + 3 : n + 6])
            times.append(values[n + 6])
        elif words[:1] == ["ODOM"]:
            x, y, theta, _, _, _, t = (float(w) for w in words[1:8])
            odometry.append([x, y, theta, t])
    return {
        "ranges": np.array(ranges),
        "laser": np.array(laser),
        "robot": np.array(robot),
        "times": np.array(times),
        "odometry": np.array(odometry),
    }


@pytest.mark.parametrize("name", ["intel", "aces", "csail"])
def test_the_real_logs_hold_what_their_lines_say(shared_data: Path, name: str) -> None:
    log = read_carmen(shared_data / LOGS / f"{name}-corrected.log.gz")
    want = _independent(_text(shared_data, name))
    np.testing.assert_array_equal(np.array([s.ranges for s in log.scans]), want["ranges"])
    for poses, key in ((log.laser_poses, "laser"), (log.robot_poses, "robot")):
        got = np.array([p.as_array() for p in poses])
        np.testing.assert_array_equal(got[:, :2], want[key][:, :2])
        # Pose2D wraps the headings (csail's reach 3.85 rad): the same angle.
        turn = got[:, 2] - want[key][:, 2]
        np.testing.assert_allclose(np.arctan2(np.sin(turn), np.cos(turn)), 0.0, rtol=0, atol=1e-12)
        assert np.all((got[:, 2] > -np.pi) & (got[:, 2] <= np.pi))
    np.testing.assert_array_equal(log.times, want["times"])
    np.testing.assert_array_equal(log.odometry[:, [0, 1, 3]], want["odometry"][:, [0, 1, 3]])
    turn = log.odometry[:, 2] - want["odometry"][:, 2]
    np.testing.assert_allclose(np.arctan2(np.sin(turn), np.cos(turn)), 0.0, rtol=0, atol=1e-12)
    # "No return" is the log's largest reading (the README's maximum range).
    assert {s.range_max for s in log.scans} == {float(want["ranges"].max())}
