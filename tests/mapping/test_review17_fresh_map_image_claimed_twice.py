"""Two threads saving two different maps whose images have the same name.

``write_map(grid, "map.yaml")`` and ``write_map(grid, "map")`` (or ``"map.yml"``)
both write ``map.pgm``. A save refuses to write over an image that the
existing YAML at its path does not name ("another map's image"), but it looked
only once, before encoding the image and outside the renames' lock. Two such
saves in threads could both look before either saved: both then saved, and
one map's YAML named the image of the other, which it read without complaint
(the wrong grid). Unforced, with 400 × 600 and 500 × 300 maps, 9 of 30 runs
ended so. The check is now made again under the renames' lock, right before the
renames: one of the two saves raises ``ValueError`` and writes nothing.

The overlap is forced: each save waits after its first check (in the image
encoding) until the other has passed its own.
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


def _both_at_once(
    saves: list[tuple[OccupancyGrid, Path, str]], monkeypatch: pytest.MonkeyPatch
) -> list[BaseException | None]:
    """Run the saves in threads, each past its first image check before any goes on."""
    real = _map_files._map_image
    all_checked = threading.Barrier(len(saves))

    def encode(grid: OccupancyGrid, mode: str) -> Any:
        with contextlib.suppress(threading.BrokenBarrierError):
            all_checked.wait(timeout=2.0)
        return real(grid, mode)

    monkeypatch.setattr(_map_files, "_map_image", encode)
    outcome: list[BaseException | None] = [None] * len(saves)

    def save(k: int) -> None:
        grid, path, mode = saves[k]
        try:
            write_map(grid, path, mode=mode)
        except BaseException as exc:  # reported by the test
            outcome[k] = exc

    threads = [threading.Thread(target=save, args=(k,), daemon=True) for k in range(len(saves))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(30)
        assert not thread.is_alive()
    monkeypatch.setattr(_map_files, "_map_image", real)
    return outcome


@pytest.mark.parametrize("other", ["map", "map.yml", "map.txt"])
@pytest.mark.parametrize("mode", ["trinary", "scale"])
def test_one_of_two_maps_claiming_one_image_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, other: str, mode: str
) -> None:
    first, second = tmp_path / "map.yaml", tmp_path / other
    outcome = _both_at_once([(A, first, mode), (B, second, mode)], monkeypatch)
    refused = [exc for exc in outcome if exc is not None]
    assert len(refused) == 1, outcome
    assert isinstance(refused[0], ValueError)
    assert "is not the image of the map" in str(refused[0])
    # The save that went through left its map, reading its own grid; the other
    # left no YAML (nothing is written when a save is refused).
    saved, grid = (first, A) if outcome[0] is None else (second, B)
    unsaved = second if saved == first else first
    assert not unsaved.exists()
    again = read_map(saved)
    assert again.shape == grid.shape
    np.testing.assert_array_equal(again.occupied(), grid.occupied())


def test_saves_of_one_map_from_two_threads_still_both_go_through(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # The second check must not refuse a save of the same map (its own image).
    path = tmp_path / "map.yaml"
    write_map(A, path)
    outcome = _both_at_once([(A, path, "trinary"), (B, path, "trinary")], monkeypatch)
    assert outcome == [None, None]
    assert read_map(path).shape in (A.shape, B.shape)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.pgm", "map.yaml"]
