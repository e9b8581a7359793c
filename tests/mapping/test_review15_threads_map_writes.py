"""Two threads saving the same map at once (an autosave timer and a save service).

``write_map`` writes the image and the YAML to temporary files, then renames
them over the targets one after the other. Two saves in threads of one
process used to interleave those renames: save A renamed its image, save B
renamed its image and its YAML, then A renamed its YAML, leaving A's YAML
with B's image (another size, resolution and origin). The interleaving is
forced here: A's first rename waits (up to a timeout) until B has finished.
Every navkit save now renames its files while holding one lock, so B waits
for A instead, and the map on disk is all of one save.
"""

from __future__ import annotations

import os
import sys
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map

A = OccupancyGrid.from_occupancy(np.eye(4, 6, dtype=bool), resolution=0.5)
B = OccupancyGrid.from_occupancy(~np.eye(5, 3, dtype=bool), resolution=0.25, origin=(1.0, 2.0, 0.0))


def _same(grid: OccupancyGrid, expected: OccupancyGrid) -> bool:
    return (
        grid.shape == expected.shape
        and grid.resolution == expected.resolution
        and grid.origin == expected.origin
        and np.array_equal(grid.occupied(), expected.occupied())
    )


def test_a_save_finishing_between_the_renames_of_another_leaves_one_whole_map(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = tmp_path / "map.yaml"
    write_map(A, path)
    real_replace: Callable[..., Any] = os.replace
    a_renamed_one = threading.Event()
    b_done = threading.Event()
    a_thread: list[threading.Thread] = []
    waited: list[bool] = []

    def replace(src: Any, dst: Any) -> None:
        real_replace(src, dst)
        if threading.current_thread() is a_thread[0] and not a_renamed_one.is_set():
            a_renamed_one.set()  # A's image is in place, its YAML not yet: let B save
            waited.append(b_done.wait(timeout=0.5))

    monkeypatch.setattr(os, "replace", replace)
    errors: list[BaseException] = []

    def save(grid: OccupancyGrid, done: threading.Event | None = None) -> None:
        try:
            write_map(grid, path)
        except BaseException as exc:  # pragma: no cover - reported below
            errors.append(exc)
        finally:
            if done is not None:
                done.set()

    a = threading.Thread(target=save, args=(A,))
    b = threading.Thread(target=save, args=(B, b_done))
    a_thread.append(a)
    a.start()
    assert a_renamed_one.wait(timeout=10.0)
    b.start()
    a.join(timeout=10.0)
    b.join(timeout=10.0)
    assert not a.is_alive() and not b.is_alive()
    assert not errors, errors
    got = read_map(path)
    assert _same(got, B), (got.shape, got.resolution, got.origin)
    # B could not finish while A was between its renames: it waited for A's lock.
    assert waited == [False]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.pgm", "map.yaml"]


def test_saves_of_one_map_in_many_threads_leave_one_whole_map(tmp_path: Path) -> None:
    path = tmp_path / "map.yaml"
    grids = [A, B] * 4
    barrier = threading.Barrier(len(grids))
    errors: list[BaseException] = []

    def save(grid: OccupancyGrid) -> None:
        try:
            barrier.wait()
            for _ in range(3):
                write_map(grid, path)
        except BaseException as exc:  # pragma: no cover - reported below
            errors.append(exc)

    threads = [threading.Thread(target=save, args=(g,)) for g in grids]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert not errors, errors
    got = read_map(path)
    assert _same(got, A) or _same(got, B)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.pgm", "map.yaml"]


def _first_saves(path: Path, grids: list[OccupancyGrid]) -> list[BaseException]:
    """Save ``grids`` to a new ``path`` from one thread each, three times; the errors."""
    barrier = threading.Barrier(len(grids))
    errors: list[BaseException] = []

    def save(grid: OccupancyGrid) -> None:
        try:
            barrier.wait()
            for _ in range(3):  # a thread that lags finds others' first saves under way
                write_map(grid, path)
        except BaseException as exc:  # pragma: no cover - reported below
            errors.append(exc)

    threads = [threading.Thread(target=save, args=(g,)) for g in grids]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    return errors


def test_first_saves_of_one_map_in_threads_never_see_each_other_half_renamed(
    tmp_path: Path,
) -> None:
    # A first save renames its image, then its YAML: in between, another thread's
    # check "is the image there the map's?" read the image as a foreign one and
    # refused to save (6 of 40 rounds like these before the check took the lock).
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # threads switch often: the window is hit
    try:
        for round_ in range(20):
            path = tmp_path / str(round_) / "map.yaml"
            path.parent.mkdir()
            errors = _first_saves(path, [A, B] * 4)
            assert not errors, errors
            got = read_map(path)
            assert _same(got, A) or _same(got, B)
    finally:
        sys.setswitchinterval(interval)
