"""Log, bag and MovingAI readers given paths that are not files, and what they leave behind
(review 46).

A loop of symbolic links gave the MovingAI readers (and ``read_map``'s YAML) the
system's bare ``OSError`` "Too many levels of symbolic links", naming no loop,
and the CARMEN and bag readers "does not exist" alone; every reader now raises
``FileNotFoundError`` naming the loop. A folder, a FIFO or a device is a
``ValueError`` naming the path (a FIFO never blocks). The real files are left
as they were, and no reader leaves a file open, on success or on error.
"""

from __future__ import annotations

import gc
import hashlib
import os
import sys
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from fifo_guard import unblocked
from navkit.mapping.io import (
    bag_topics,
    read_bag_odometry,
    read_bag_scans,
    read_carmen,
    read_map,
    read_movingai_map,
    read_movingai_scenarios,
)

READERS: dict[str, Callable[[Any], Any]] = {
    "read_carmen": read_carmen,
    "read_movingai_map": read_movingai_map,
    "read_movingai_scenarios": read_movingai_scenarios,
    "read_bag_scans": read_bag_scans,
    "bag_topics": bag_topics,
    "read_map": read_map,
}
NEEDS_ROSBAGS = {"read_bag_scans", "bag_topics"}


def _reader(name: str) -> Callable[[Any], Any]:
    if name in NEEDS_ROSBAGS:
        pytest.importorskip("rosbags")
    return READERS[name]


@pytest.mark.parametrize("name", list(READERS))
def test_a_loop_of_symbolic_links_is_a_missing_file_naming_the_loop(
    tmp_path: Path, name: str
) -> None:
    read = _reader(name)
    looped = tmp_path / "a.file"
    looped.symlink_to(tmp_path / "b.file")
    (tmp_path / "b.file").symlink_to(looped)
    for path in (looped, looped / "inside.file"):
        with pytest.raises(FileNotFoundError, match="does not exist") as info:
            read(path)
        assert str(path) in str(info.value)
        assert str(info.value).endswith(f"({looped} is a loop of symbolic links)")


@pytest.mark.parametrize("name", list(READERS))
def test_dangling_links_folders_fifos_and_devices_are_refused_naming_them(
    tmp_path: Path, name: str
) -> None:
    read = _reader(name)
    dangling = tmp_path / "dangling.file"
    dangling.symlink_to(tmp_path / "nowhere")
    with pytest.raises(FileNotFoundError, match="does not exist"):
        read(dangling)
    folder = tmp_path / "folder"
    folder.mkdir()
    others = [folder, Path(os.devnull)]
    if hasattr(os, "mkfifo"):
        os.mkfifo(tmp_path / "fifo")
        others.append(tmp_path / "fifo")
    for path in others:

        def call(path: Path = path) -> None:
            with pytest.raises(ValueError) as info:
                read(path)
            assert str(path) in str(info.value)

        unblocked(call, path)


def _real_files(shared_data: Path) -> list[tuple[str, Path]]:
    return [
        ("read_carmen", shared_data / "carmen-logs/aces-corrected.log.gz"),
        ("read_movingai_map", shared_data / "movingai-grid-benchmarks/dao/arena.map"),
        ("read_movingai_scenarios", shared_data / "movingai-grid-benchmarks/dao/arena.map.scen"),
        ("read_bag_scans", shared_data / "rosbag-hokuyo-laserscan-demo/demo.bag"),
        ("read_bag_odometry", shared_data / "robot-localization-odom-imu-bags/test2.bag"),
    ]


def test_the_real_files_are_left_as_they_were(shared_data: Path) -> None:
    pytest.importorskip("rosbags")
    readers = {**READERS, "read_bag_odometry": read_bag_odometry}

    def state(path: Path) -> tuple[Any, ...]:
        listing = sorted((p.name, p.stat().st_mtime_ns) for p in path.parent.iterdir())
        return hashlib.sha256(path.read_bytes()).hexdigest(), path.stat().st_mode, listing

    for name, path in _real_files(shared_data):
        before = state(path)
        readers[name](path)
        assert state(path) == before, name


def test_no_reader_leaves_a_file_open(shared_data: Path, tmp_path: Path) -> None:
    """ResourceWarnings, as errors, after reads that succeed and reads that fail half-way
    (a malformed line after good ones, a bag cut in its chunks)."""
    pytest.importorskip("rosbags")
    readers = {**READERS, "read_bag_odometry": read_bag_odometry}
    cases = []
    for name, path in _real_files(shared_data):
        data = path.read_bytes()
        cases.append((name, path))
        cut = tmp_path / f"cut-{path.name}"
        cut.write_bytes(data[: len(data) // 2])
        cases.append((name, cut))
    aces = tmp_path / "aces.log"
    aces.write_bytes(b"FLASER 1 1.0 0 0 0 0 0 0 1.0 h 1.0\n" * 50 + b"FLASER 3 x\n" + b"ODOM 0\n")
    cases.append(("read_carmen", aces))
    with warnings.catch_warnings():
        warnings.simplefilter("error", ResourceWarning)
        for name, path in cases:
            try:
                readers[name](path)
            except ValueError as exc:
                assert str(path) in str(exc)
            gc.collect()  # an unclosed file's warning comes when it is collected
