"""ScanMapper grows its map geometrically (review 21, known defects).

The map grew by the need plus a fixed 10 m margin, so a route that keeps
leaving it (a long corridor) copied the whole map every 10 m: the time spent
growing was quadratic in the distance travelled (5 km at 5 cm: 477 growths,
6.8 s). An axis that grows now at least doubles (1 km: 6 growths instead of
96); a growth still changes no cell's content or world position.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import navkit.mapping._scan_mapper as scan_mapper
from navkit.mapping import LaserScan, ScanMapper


def _corridor_scan(half_width: float = 1.5, n: int = 180) -> LaserScan:
    """A scan between two walls ``half_width`` m to each side, along the x axis."""
    angles = -math.pi + np.arange(n) * (2 * math.pi / n)
    with np.errstate(divide="ignore"):
        ranges = half_width / np.abs(np.sin(angles))
    ranges = np.where(ranges < 8.0, ranges, 8.0)  # no echo along the corridor
    return LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / n,
                     range_min=0.1, range_max=8.0)  # fmt: skip


def _levels(mapper: ScanMapper) -> list[tuple[np.ndarray, float, float]]:
    return [(g.logodds.copy(), g.origin.x, g.origin.y) for g in mapper._levels]


def _assert_kept(before: list[tuple[np.ndarray, float, float]], mapper: ScanMapper) -> None:
    """Each old level sits in the new one bit for bit, at the same world position."""
    for (old, ox, oy), grid in zip(before, mapper._levels, strict=True):
        step = grid.resolution
        dc = (ox - grid.origin.x) / step
        dr = (oy - grid.origin.y) / step
        # Whole cells: the same lattice (to the rounding of the origin's subtraction,
        # as before: x0 = o.x - cells * step).
        assert abs(dc - round(dc)) < 1e-9 and abs(dr - round(dr)) < 1e-9
        r, c = old.shape
        block = grid.logodds[round(dr) : round(dr) + r, round(dc) : round(dc) + c]
        np.testing.assert_array_equal(block, old)
        rest = grid.logodds.copy()
        rest[round(dr) : round(dr) + r, round(dc) : round(dc) + c] = 0.0
        assert not rest.any()  # the new cells are unknown


@pytest.mark.parametrize("heading", [0.0, math.pi, -math.pi / 2])
def test_a_corridor_grows_the_map_a_logarithmic_number_of_times(heading: float) -> None:
    # 300 m at 10 cm: growing by 10 m each time took 29 growths, each copying the map.
    scan = _corridor_scan()
    mapper = ScanMapper(resolution=0.1, pose=(0.0, 0.0, heading))
    shapes = []
    for i in range(601):
        # Odometry in its own frame: only increments count, 0.5 m straight ahead.
        mapper.update(scan, odometry=(0.5 * i, 0.0, 0.0))
        shapes.append(mapper.map.shape)
    assert len(set(shapes)) <= 6, len(set(shapes))  # 5 growths: 20 m doubled to 320 and more
    grid = mapper.map
    along_x = abs(math.cos(heading)) > 0.5
    along = grid.width if along_x else grid.height
    assert 300.0 < along <= 2 * 300.0 + 40.0  # at most about twice what is needed
    assert (grid.height if along_x else grid.width) == 20.0  # the other axis kept its ±10 m
    end = mapper.pose
    assert grid.contains([[end.x, end.y]]).all()


@pytest.mark.parametrize("target", [(25.0, 0.0), (-25.0, 0.0), (0.0, 25.0), (-25.0, -25.0),
                                    (0.0, -60.0)])  # fmt: skip
def test_a_growth_keeps_every_cell_and_its_world_position(target: tuple[float, float]) -> None:
    scan = _corridor_scan()
    mapper = ScanMapper(resolution=0.1)
    for x in (0.0, 0.5, 1.0):
        mapper.update(scan, odometry=(x, 0.0, 0.0))
    before = _levels(mapper)
    shape = mapper.map.shape
    # The growth alone, as update() makes it for a pose there (nothing written yet).
    pose = scan_mapper.Pose2D(*target, 0.0)
    mapper._ensure_covers(pose, scan_mapper.scan_points(scan, None))
    grid = mapper.map
    corners = [[target[0] - 8.0, target[1] - 8.0], [target[0] + 8.0, target[1] + 8.0]]
    assert grid.contains(corners).all()
    _assert_kept(before, mapper)
    rows, cols = grid.shape
    # An axis that grew at least doubled; one that did not is as it was.
    assert cols >= 2 * shape[1] if target[0] else cols == shape[1]
    assert rows >= 2 * shape[0] if target[1] else rows == shape[0]


def test_near_the_cell_limit_the_map_grows_by_less(monkeypatch: pytest.MonkeyPatch) -> None:
    # With room for 2**18 cells (a 20 m wide map up to 131 m long at 10 cm) the
    # length cannot double past 65 m: it grows by a half, a quarter or an eighth,
    # then by the need (the scan plus 10 m) alone, and no further once that no
    # longer fits (as before: returns beyond the map are clipped).
    monkeypatch.setattr(scan_mapper, "MAX_CELLS", 2**18)
    scan = _corridor_scan()
    mapper = ScanMapper(resolution=0.1)
    widths = []
    for i in range(260):
        mapper.update(scan, odometry=(0.5 * i, 0.0, 0.0))
        grid = mapper.map
        assert grid.shape[0] * grid.shape[1] <= 2**18
        x = mapper.pose.x  # the matched pose: along a corridor it lags the odometry
        # The map may span -10 m to 121 m; the need is the scan's reach plus a metre,
        # the 10 m margin and two coarse cells.
        if x + 8.0 + 1.0 + 10.0 + 1.0 <= 121.0:  # the need fits: the scan is inside
            assert grid.contains([[x + 7.5, 0.0]]).all()
        widths.append(grid.shape[1])
    assert len(set(widths)) <= 10
    # It stops where the need no longer fits, 12.5 m (125 columns) short of the
    # limit's 1310 columns or closer, as growing by the need alone did.
    assert 1310 - 125 <= widths[-1] <= 1310


@given(
    low=st.one_of(st.just(0.0), st.floats(1e-3, 1e6)),
    high=st.one_of(st.just(0.0), st.floats(1e-3, 1e6)),
    extent=st.floats(0.0, 1e6),
)
def test_at_least_adds_the_need_and_reaches_the_extent(
    low: float, high: float, extent: float
) -> None:
    new_low, new_high = scan_mapper._at_least(low, high, extent)
    assert new_low >= low and new_high >= high
    if not (low or high):
        assert (new_low, new_high) == (0.0, 0.0)  # an axis that needs nothing stays
        return
    assert not (new_low and not low) and not (new_high and not high)  # only needy sides
    assert new_low + new_high >= extent * (1 - 1e-12)
    assert new_low + new_high <= max(low + high, extent) * (1 + 1e-12)
