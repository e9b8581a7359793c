"""Path2D's conversions: what to_world returns, to_grid takes; subclasses convert to Path2D.

Review 54 (FOUND7; FRESH2's finding of review 53). ``to_world`` accepted grid
points up to ``2**62`` cells from cell (0, 0), whose world points (4.6e17 m on
a 0.1 m map) ``to_grid`` then refused, as do the trackers: every world input
of navkit lies within ±1e9 m. ``to_world`` now refuses such a path, naming the
range. Conversions return a plain :class:`Path2D`, a subclass's too (its own
attributes may be quantities of its frame): documented and pinned here, as
copies and pickles keep the subclass whole.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.control import RegulatedPurePursuit
from navkit.mapping import OccupancyGrid
from navkit.planning import Path2D


def _grid(
    resolution: float = 0.1, origin: tuple[float, float, float] = (0.0, 0.0, 0.0)
) -> OccupancyGrid:
    return OccupancyGrid.empty(
        width=resolution, height=resolution, resolution=resolution, origin=origin
    )


@pytest.mark.parametrize("far", [2.0**40, 2.0**62, -(1e10 + 2.0)])
def test_a_grid_path_beyond_the_world_range_is_refused(far: float) -> None:
    path = Path2D([[0.0, 0.0], [0.0, far]], "grid", cost=1.0, length=1.0, expanded=0)
    with pytest.raises(ValueError, match=r"world points within ±1e\+09 m .* got a coordinate of"):
        path.to_world(_grid())


@settings(max_examples=200, deadline=None)
@given(
    st.floats(-(2.0**62), 2.0**62),
    st.floats(-(2.0**62), 2.0**62),
    st.sampled_from([1e-6, 0.05, 0.1, 1.0, 1e6]),
    st.floats(-1e9, 1e9),
    st.floats(-np.pi, np.pi),
)
def test_every_world_path_to_world_returns_converts_back(
    row: float, col: float, resolution: float, shift: float, yaw: float
) -> None:
    grid = _grid(resolution, (shift, -shift, yaw))
    path = Path2D([[0.0, 0.0], [row, col]], "grid", cost=1.0, length=1.0, expanded=2)
    try:
        world = path.to_world(grid)
    except ValueError as exc:
        assert "world points within" in str(exc)
        assert not np.abs(grid.cell_to_world(path.points)).max() <= 1e9
        return
    assert np.abs(world.points).max() <= 1e9
    back = world.to_grid(grid)  # never refused
    assert back.frame == "grid" and back.expanded == 2
    RegulatedPurePursuit().set_path(world)  # the trackers take it too


@dataclass(frozen=True, slots=True)
class _Tolerant(Path2D):
    tolerance: float = 0.0  # in the path's own unit: cells or metres


@pytest.mark.parametrize("frame", ["grid", "world"])
def test_subclasses_convert_to_plain_paths_and_copy_whole(frame: str) -> None:
    grid = _grid(0.5)
    path = _Tolerant([[0.0, 0.0], [1.0, 1.0]], frame, 1.0, 1.0, 3, tolerance=2.0)  # type: ignore[arg-type]
    converted = path.to_world(grid) if frame == "grid" else path.to_grid(grid)
    assert type(converted) is Path2D and converted.frame != frame
    plain = Path2D(path.points, frame, 1.0, 1.0, 3)  # type: ignore[arg-type]
    twin = plain.to_world(grid) if frame == "grid" else plain.to_grid(grid)
    assert converted.points.tobytes() == twin.points.tobytes()
    assert (converted.cost, converted.length, converted.expanded) == (
        twin.cost,
        twin.length,
        twin.expanded,
    )
    kept = copy.copy(path)
    assert type(kept) is _Tolerant and kept.tolerance == 2.0
