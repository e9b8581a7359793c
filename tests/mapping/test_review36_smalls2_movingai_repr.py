"""``MovingAIMap``'s repr stays short for a benchmark-sized map (review 36, a guard).

An item left open by earlier reviews asked what the repr shows for a 1024 x
1024 map: it is short since the class was added (the class name, the terrain's
shape and its passable cells, as navkit's other large objects show theirs),
not the million cells. Pinned here on the real benchmark map and a made one.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from navkit.mapping.io import MovingAIMap, read_movingai_map


def test_a_megacell_map_prints_in_one_short_line() -> None:
    terrain = np.full((1024, 1024), ".", dtype="U1")
    terrain[::2, ::3] = "@"
    grid = MovingAIMap(terrain)
    passable = int(grid.passable.sum())
    assert repr(grid) == f"MovingAIMap(<1024 x 1024 terrain, {passable} passable>)"
    assert str(grid) == repr(grid)


def test_the_berlin_benchmark_map_prints_in_one_short_line(shared_data: Path) -> None:
    grid = read_movingai_map(shared_data / "movingai-grid-benchmarks/street/Berlin_0_1024.map")
    text = repr(grid)
    assert text.startswith("MovingAIMap(<1024 x 1024 terrain, ")
    assert len(text) < 80 and "\n" not in text


def test_a_subclass_is_named() -> None:
    class Level(MovingAIMap):
        pass

    assert repr(Level(["..@"])) == "Level(<1 x 3 terrain, 2 passable>)"
