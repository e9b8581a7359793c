"""Clamping of ray-casting updates never moves a cell against the update (sixth review)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.mapping import LaserScan, OccupancyGrid, ScanMapper, integrate_scan


def _beam(rng: float) -> LaserScan:
    return LaserScan(
        np.array([rng]), angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=10.0
    )


def test_an_agreeing_scan_keeps_a_loaded_maps_certainty() -> None:
    # A map from a file stores about ±6.9, beyond OctoMap's default clamp
    # (-1.99, 3.48). A scan confirming the map must not make it less certain:
    # clamping the free cells *up* to -1 turned them unknown.
    grid = OccupancyGrid.from_occupancy(np.array([[False, False, False, True]]), resolution=1.0)
    before = grid.logodds.copy()
    integrate_scan(grid, _beam(3.0), (0.5, 0.5, 0.0), clamp=(-1.0, 1.0))
    assert np.array_equal(grid.logodds, before)
    assert grid.free().tolist() == [[True, True, True, False]]
    assert grid.occupied().tolist() == [[False, False, False, True]]


def test_a_disagreeing_scan_moves_a_cell_by_the_increment() -> None:
    grid = OccupancyGrid.from_occupancy(np.array([[False, False, False, True]]), resolution=1.0)
    before = grid.logodds.astype(np.float64)
    # From the right, looking left: hit in the free cell 2, miss in the occupied cell 3.
    integrate_scan(
        grid, _beam(1.0), (3.5, 0.5, math.pi), hit=0.8, miss=-0.3, clamp=(-1.0, 1.0)
    )
    after = grid.logodds.astype(np.float64)
    assert np.allclose(after[0, 2] - before[0, 2], 0.8, atol=1e-5)
    assert np.allclose(after[0, 3] - before[0, 3], -0.3, atol=1e-5)
    assert np.array_equal(after[0, :2], before[0, :2])


def _expected(value: float, update: float, low: float, high: float, hit: bool) -> float:
    """The documented rule: stop at the bound passed, never against the update's sign."""
    if hit:
        return value if value >= high else min(value + update, high)
    return value if value <= low else max(value + update, low)


@settings(max_examples=50, deadline=None)
@given(
    st.floats(-20.0, 20.0),
    st.floats(-20.0, 20.0),
    st.floats(0.0, 5.0),
    st.floats(-5.0, 0.0),
    st.floats(-8.0, 8.0),
    st.floats(0.01, 8.0),
)
def test_updates_follow_their_sign_and_respect_the_clamp(
    end_value: float, crossed_value: float, hit: float, miss: float, low: float, span: float
) -> None:
    high = low + span
    logodds = np.array([[crossed_value, end_value]], dtype=np.float32)
    grid = OccupancyGrid(logodds, resolution=1.0)
    integrate_scan(grid, _beam(1.0), (0.5, 0.5, 0.0), hit=hit, miss=miss, clamp=(low, high))
    old = logodds.astype(np.float64)[0]
    new = grid.logodds.astype(np.float64)[0]
    # The crossed cell takes a miss, the end cell a hit (float32 storage rounds).
    for k, inc in ((0, miss), (1, hit)):
        assert new[k] == float(np.float32(_expected(float(old[k]), inc, low, high, k == 1)))
        # Never against the update, never by more than it.
        assert (new[k] - old[k]) * inc >= 0.0
        assert abs(new[k] - old[k]) <= abs(inc) + 1e-5 * (1.0 + abs(old[k]))
        # A value within the clamp stays within it, as the plain clipped update.
        if low <= old[k] <= high:
            assert abs(new[k] - min(max(old[k] + inc, low), high)) <= 1e-5 * (1.0 + abs(old[k]))


test_updates_follow_their_sign_and_respect_the_clamp_thoroughly = slow_twin(
    test_updates_follow_their_sign_and_respect_the_clamp, max_examples=200
)


def test_scan_mapper_with_a_positive_lower_clamp_keeps_crossed_cells_unknown() -> None:
    # ScanMapper's levels start at log-odds 0. With clamp[0] > 0 every crossed
    # (free) cell used to jump up to clamp[0]: seen free, stored as occupied-ish.
    mapper = ScanMapper(resolution=0.1, clamp=(0.5, 50.0))
    angles = np.linspace(-math.pi, math.pi, 90, endpoint=False)
    ranges = [2.0 / max(abs(math.cos(a)), abs(math.sin(a))) for a in angles]
    scan = LaserScan(
        np.array(ranges),
        angle_min=-math.pi,
        angle_increment=2 * math.pi / 90,
        range_min=0.1,
        range_max=10.0,
    )
    mapper.update(scan)
    grid = mapper.map
    centre = grid.world_to_cell([0.3, 0.2])
    assert grid.logodds[centre[0], centre[1]] <= 0.0
    assert not grid.occupied()[centre[0], centre[1]]
