"""Two threads saving one map at once in the two modes (a PGM and a PNG save).

A save in one mode removes the other mode's image that the map's YAML named
(``_superseded_image``, decided before the renames; ``_remove_superseded``
after them). Review 15 made the renames of threads take turns, but the decision
and the removal stayed outside that lock. Two overlapping saves in different
modes then both decided before either renamed: neither image was superseded
for the other, and the map was left with a stale image of the other mode
beside it. Every later save in that mode raised ValueError ("already exists
and is not the image of the map"), until someone removed the file by hand.
The removal also ran outside the lock: between its check (the file is still
the one chosen) and its unlink, another thread's save could rename a new
image there, which the unlink then removed, leaving a YAML naming a missing
image. The decision, the renames and the removal now run as one step under
the renames' lock.

The overlap is forced: each save's decision waits (up to a timeout) until the
other save has reached its decision too.
"""

from __future__ import annotations

import contextlib
import threading
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import _map_files, read_map, write_map

A = OccupancyGrid.from_occupancy(np.eye(4, 6, dtype=bool), resolution=0.5)
B = OccupancyGrid.from_occupancy(~np.eye(5, 3, dtype=bool), resolution=0.25, origin=(1.0, 2.0, 0.0))


def _images(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.suffix in (".pgm", ".png"))


def _save_both_at_once(path: Path, monkeypatch: pytest.MonkeyPatch) -> list[BaseException]:
    """A trinary (PGM) and a scale (PNG) save of ``path`` whose decisions overlap if they can."""
    real = _map_files._superseded_image
    both_deciding = threading.Barrier(2)

    def superseded(yaml_path: Path, image: Path) -> Any:
        # Both saves decide together where nothing orders them; where the
        # decision is made under the renames' lock, the first waits in vain.
        with contextlib.suppress(threading.BrokenBarrierError):
            both_deciding.wait(timeout=0.5)
        return real(yaml_path, image)

    monkeypatch.setattr(_map_files, "_superseded_image", superseded)
    errors: list[BaseException] = []

    def save(grid: OccupancyGrid, mode: str) -> None:
        try:
            write_map(grid, path, mode=mode)
        except BaseException as exc:  # reported by the test
            errors.append(exc)

    threads = [
        threading.Thread(target=save, args=(A, "trinary"), daemon=True),
        threading.Thread(target=save, args=(B, "scale"), daemon=True),
    ]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(30)
        assert not thread.is_alive()  # a save waiting for ever: a lock taken twice
    monkeypatch.setattr(_map_files, "_superseded_image", real)
    return errors


@pytest.mark.parametrize("first", [None, "trinary", "scale"])
def test_overlapping_saves_in_two_modes_leave_one_image_and_later_saves_work(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, first: str | None
) -> None:
    path = tmp_path / "map.yaml"
    if first is not None:
        write_map(A, path, mode=first)
    assert _save_both_at_once(path, monkeypatch) == []
    # One whole map, and only its own image beside it.
    grid = read_map(path)
    assert grid.shape in (A.shape, B.shape)
    assert len(_images(tmp_path)) == 1, _images(tmp_path)
    # Later saves in either mode still work (a stale image used to refuse them).
    for mode in ("trinary", "scale", "trinary"):
        write_map(A, path, mode=mode)
        assert len(_images(tmp_path)) == 1
        assert read_map(path).shape == A.shape


def test_many_overlapping_saves_in_two_modes(tmp_path: Path) -> None:
    # Unforced: 4 threads, alternating modes, then one save of each mode must work.
    path = tmp_path / "map.yaml"
    errors: list[BaseException] = []

    def saves(index: int) -> None:
        try:
            for k in range(6):
                mode = "trinary" if (index + k) % 2 else "scale"
                write_map(A if index % 2 else B, path, mode=mode)
        except BaseException as exc:  # reported by the test
            errors.append(exc)

    threads = [threading.Thread(target=saves, args=(i,), daemon=True) for i in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(60)
        assert not thread.is_alive()
    assert errors == []
    assert len(_images(tmp_path)) == 1, _images(tmp_path)
    assert read_map(path).shape in (A.shape, B.shape)
    write_map(A, path, mode="trinary")
    write_map(A, path, mode="scale")
    assert _images(tmp_path) == ["map.png"]
