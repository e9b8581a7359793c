"""Readers read the files they checked: a FIFO or a folder put in their place is refused.

Before, read_map checked the YAML and the image by name (``is_file``) and then opened
them by name again: a FIFO swapped in between made the read block for ever (no
writer), a folder raised ``IsADirectoryError``; ``read_pgm`` and ``read_image`` had no
check at all. A ROS 2 bag's metadata.yaml was checked by name and read by rosbags.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from fifo_guard import unblocked
from file_swaps import swap_after_stats, to_fifo, to_folder
from navkit.mapping.io import _map_files, _paths, read_map
from navkit.mapping.io._map_files import read_image, read_pgm

pytestmark = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs (POSIX)")

_YAML = (
    "image: m.pgm\nresolution: 0.5\norigin: [0, 0, 0]\nnegate: 0\n"
    "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
)


def _map(folder: Path) -> Path:
    (folder / "m.pgm").write_bytes(b"P5 2 1 255 \x00\xfe")
    (folder / "m.yaml").write_text(_YAML)
    return folder / "m.yaml"


@pytest.mark.parametrize("after", [1])
def test_image_swapped_for_a_fifo_after_its_check_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, after: int
) -> None:
    path = _map(tmp_path)
    image = tmp_path / "m.pgm"
    # read_map_yaml checks the image with one stat (it was exists() then is_file():
    # after the second, older code opened the FIFO and blocked).
    swap_after_stats(monkeypatch, image, after, to_fifo(image))
    with pytest.raises(ValueError, match=f"{path}: map image {image} is not a regular file"):
        unblocked(lambda: read_map(path), image)


def test_image_swapped_for_a_folder_after_its_check_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = _map(tmp_path)
    image = tmp_path / "m.pgm"
    swap_after_stats(monkeypatch, image, 1, to_folder(image))
    # Was IsADirectoryError (an OSError: "the operating system refuses to read").
    with pytest.raises(ValueError, match=f"{path}: map image {image} is a directory"):
        read_map(path)


@pytest.mark.parametrize("after", [1, 2, 3])
def test_yaml_swapped_for_a_fifo_is_read_as_it_was_or_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, after: int
) -> None:
    # Whenever the YAML becomes a FIFO, read_map either read the file before (its
    # one open) or refuses the FIFO; the old code blocked when the swap came after
    # its is_file() check (the stat of its size then read_bytes opened the FIFO).
    path = _map(tmp_path)
    swap_after_stats(monkeypatch, path, after, to_fifo(path))
    try:
        grid = unblocked(lambda: read_map(path), path)
    except ValueError as exc:
        assert str(exc) == f"map YAML file {path} is not a regular file"
    else:
        assert grid.occupied().tolist() == [[True, False]]


@pytest.mark.parametrize("reader", [read_pgm, read_image])
def test_image_readers_refuse_a_fifo_and_a_folder(tmp_path: Path, reader: Any) -> None:
    fifo = tmp_path / "f.pgm"
    os.mkfifo(fifo)
    with pytest.raises(ValueError, match=f"{fifo} is not a regular file"):
        unblocked(lambda: reader(fifo), fifo)
    folder = tmp_path / "d.pgm"
    folder.mkdir()
    with pytest.raises(ValueError, match=f"{folder} is a directory"):
        reader(folder)
    with pytest.raises(FileNotFoundError, match=f"{tmp_path / 'no.pgm'} does not exist"):
        reader(tmp_path / "no.pgm")


@pytest.mark.parametrize("suffix", ["pgm", "png"])
def test_the_image_is_read_through_the_descriptor_it_was_checked_on(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, suffix: str
) -> None:
    # Once the image is open, replacing it by name changes nothing: the pixels
    # come from the file that was checked (PGM read by numpy, PNG by Pillow).
    image = tmp_path / f"m.{suffix}"
    if suffix == "png":
        pytest.importorskip("PIL.Image")
        pixels = np.array([[[0, 0, 0, 255], [254, 254, 254, 255]]], np.uint8)
        image.write_bytes(_map_files.png_bytes(pixels))
    else:
        image.write_bytes(b"P5 2 1 255 \x00\xfe")
    (tmp_path / "m.yaml").write_text(_YAML.replace("m.pgm", image.name))
    real_open = _paths.open_regular

    def opened_then_replaced(path: Path, what: str) -> Any:
        fh = real_open(path, what)
        if path == image:
            image.unlink()
            os.mkfifo(image)
        return fh

    monkeypatch.setattr(_map_files, "open_regular", opened_then_replaced)
    grid = unblocked(lambda: read_map(tmp_path / "m.yaml"), image)
    assert grid.occupied().tolist() == [[True, False]]
    assert grid.free().tolist() == [[False, True]]


def test_ros2_bag_metadata_swapped_for_a_fifo_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # The readers checked metadata.yaml with is_file(), then rosbags opened it by
    # name and read it whole: a FIFO put there in between blocked for ever.
    rosbag2 = pytest.importorskip("rosbags.rosbag2")
    from navkit.mapping.io import bag_topics

    folder = tmp_path / "bag"
    with rosbag2.Writer(folder, version=9):
        pass
    assert bag_topics(folder) == {}
    meta = folder / "metadata.yaml"
    swap_after_stats(monkeypatch, meta, 1, to_fifo(meta))
    with pytest.raises(ValueError, match=f"ROS 2 bag metadata {meta} is not a regular file"):
        unblocked(lambda: bag_topics(folder), meta)


@pytest.mark.parametrize("gzipped", [False, True])
@pytest.mark.parametrize("after", [1, 2])
def test_carmen_log_swapped_for_a_fifo_after_its_check_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, after: int, gzipped: bool
) -> None:
    # read_carmen checks the log with exists() then is_file(), and used to open it
    # by name twice (magic bytes, then the lines): a FIFO put there blocked.
    import gzip

    from navkit.mapping.io import read_carmen

    log = tmp_path / "log.txt"
    line = b"FLASER 3 1.0 2.0 5.0 0 0 0 0 0 0 1.0 host 1.0\n"
    log.write_bytes(gzip.compress(line) if gzipped else line)
    assert read_carmen(log).scans[0].range_max == 5.0
    swap_after_stats(monkeypatch, log, after, to_fifo(log))
    with pytest.raises(ValueError, match=f"CARMEN log {log} is not a regular file"):
        unblocked(lambda: read_carmen(log), log)
