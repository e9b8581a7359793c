"""Review 31 (scaling): rasterize_polygons asks GEOS for validity only where it is used.

GEOS's validity check of a degenerate single polygon (a zero-area zigzag that
doubles back along one line) grows faster than quadratically with its vertices
(200,000 took 2.5 s of the call's 2.9), yet a single part is kept whatever its
validity: only multi-part geometries are split on it. Counted, not timed.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
import shapely
from shapely.geometry import LineString, MultiPolygon, Polygon, box

from navkit.mapping import rasterize_polygons


def _count_is_valid(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    calls = [0]
    real = shapely.is_valid

    def spy(geometry: Any, **kwargs: Any) -> Any:
        calls[0] += 1
        return real(geometry, **kwargs)

    monkeypatch.setattr(shapely, "is_valid", spy)
    return calls


def test_a_degenerate_single_polygon_is_not_checked_for_validity(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # A polygon that doubles back 500 times along y = 5 (zero area, invalid).
    zigzag = Polygon(np.c_[np.tile([1.0, 9.0], 500), np.full(1000, 5.0)])
    calls = _count_is_valid(monkeypatch)
    grid = rasterize_polygons(
        [zigzag, box(0.2, 0.2, 0.6, 0.6), LineString([(0, 9), (9, 9)])],
        bounds=(0, 0, 10, 10),
        resolution=0.5,
    )
    assert calls[0] == 0
    occupied = grid.occupied()
    # The zigzag's line is occupied (cells on both sides of y = 5), as before.
    assert occupied[9:11, 2:18].all()
    assert occupied[0:2, 0:2].all()


def test_a_multi_part_geometry_is_still_split_when_invalid(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Overlapping parts: read by parity, their overlap would come out free.
    overlapping = MultiPolygon([box(1, 1, 3, 3), box(2, 2, 4, 4)])
    calls = _count_is_valid(monkeypatch)
    grid = rasterize_polygons(overlapping, bounds=(0, 0, 5, 5), resolution=0.5)
    assert calls[0] >= 1
    occupied = grid.occupied()
    assert occupied[5, 5]  # the overlap, (2.5, 2.5)
    assert occupied[2:9, 2:9][np.ix_([0, 6], [0, 6])].tolist() == [[True, False], [False, True]]
