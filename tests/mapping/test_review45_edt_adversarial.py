"""The exact banded distance transform, reviewed adversarially (review 45).

``inflate``, ``costmap`` and ``traversal_costs`` now transform the grid with
navkit's own Meijster kernel (``navkit.mapping._edt_kernels``), a band of rows
(or, for a grid much wider than tall, of columns) at a time, carrying the
nearest occupied cell above and below each column from band to band, and
claim SciPy's distances bit for bit and a band's memory at any radius.
test_review45_memory_limits.py checks random grids; these try where such a
kernel breaks: every mask of a small grid with every band size (the integer
``Sep`` of parabolas whose floor division meets negative numerators and
ties), equidistant obstacles (lattices), obstacles only at the corners, the
largest distances a band carries (a single obstacle 2**21 cells away, across
a band edge), the real paths either side of the bands-of-columns threshold,
threads transforming at once, numba's bounds checks, the warm-up's
signatures, and the peak memory ``costmap`` documents. Oracle:
:func:`scipy.ndimage.distance_transform_edt` of the whole grid, compared as
float64 bits.
"""

from __future__ import annotations

import itertools
import textwrap
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from test_review45_memory_limits import assert_bands_change_nothing

import navkit.mapping._obstacle_distance as distance_module
from edt_oracle import float_bits, scipy_distances
from memory_peak import peak_bytes
from navkit.mapping import OccupancyGrid, costmap, traversal_costs
from subprocess_probe import bounds_checked, probe_outcome
from thread_runs import concurrent_results


def _banded(
    occupied: np.ndarray, band: int | None = None, *, wide: bool = False, whole: bool = False
) -> np.ndarray:
    """obstacle_distance_bands put together, each cell written exactly once (checked).

    With ``whole``, obstacle_distance itself (its bands written in place in the result).
    """
    out = np.full(occupied.shape, np.nan)
    seen = np.zeros(occupied.shape, dtype=np.int64)
    with pytest.MonkeyPatch.context() as mp:
        if band is not None:
            mp.setattr(distance_module, "_band_rows", lambda rows, cols: band)
        if wide:  # a band budget of no cell: any grid wider than tall goes by columns
            mp.setattr(distance_module, "_BAND_CELLS", 0)
        if whole:
            return distance_module.obstacle_distance(occupied)
        for where, dist in distance_module.obstacle_distance_bands(occupied):
            assert dist.dtype == np.float64
            out[where] = dist
            seen[where] += 1
    assert (seen == 1).all()
    return out


def test_every_mask_of_a_3_by_4_grid_is_scipys_with_every_band() -> None:
    # 4096 masks x 4 band sizes, by rows and (its transpose, 4 x 3) by columns.
    for bits in range(1 << 12):
        occupied = np.array([(bits >> k) & 1 for k in range(12)], dtype=bool).reshape(3, 4)
        want = float_bits(scipy_distances(occupied))
        for band, wide in itertools.product(range(1, 5), (False, True)):
            got = float_bits(_banded(occupied, band, wide=wide))
            assert np.array_equal(got, want), (occupied.astype(int).tolist(), band, wide)


_SIZES = st.sampled_from([1, 2, 3, 5, 7, 13, 31, 37, 64, 65])


@st.composite
def _adversarial_masks(draw: st.DrawFn) -> np.ndarray:
    """Masks with many equidistant obstacles, or obstacles at corners and edges only."""
    rows, cols = draw(_SIZES), draw(_SIZES)
    occupied = np.zeros((rows, cols), dtype=bool)
    kind = draw(st.sampled_from(["lattice", "corners", "one", "full", "diagonal"]))
    if kind == "lattice":  # every free cell equidistant from several obstacles
        step_r, step_c = draw(st.integers(1, 12)), draw(st.integers(1, 12))
        occupied[
            draw(st.integers(0, step_r - 1)) :: step_r, draw(st.integers(0, step_c - 1)) :: step_c
        ] = True
    elif kind == "corners":
        for at in draw(st.sets(st.sampled_from([(0, 0), (0, -1), (-1, 0), (-1, -1)]), min_size=1)):
            occupied[at] = True
    elif kind == "one":
        occupied[draw(st.integers(0, rows - 1)), draw(st.integers(0, cols - 1))] = True
    elif kind == "full":
        occupied[:] = True
    else:
        np.fill_diagonal(occupied, True)
    return occupied


@settings(max_examples=400, deadline=None)
@given(occupied=_adversarial_masks(), band=st.integers(1, 70), wide=st.booleans())
@example(
    occupied=np.eye(65, 2, dtype=bool), band=64, wide=False
)  # obstacles above the last band only
def test_ties_corners_and_lone_obstacles_are_scipys(
    occupied: np.ndarray, band: int, wide: bool
) -> None:
    kept = occupied.copy()
    want = float_bits(scipy_distances(occupied))
    assert np.array_equal(float_bits(_banded(occupied, band, wide=wide)), want)
    assert np.array_equal(float_bits(_banded(occupied, band, wide=wide, whole=True)), want)
    assert np.array_equal(occupied, kept)


@pytest.mark.parametrize(
    ("shape", "cells"),
    [
        # One obstacle 2**21 cells away across the edge of two real bands: the largest
        # distance and column gap a band carries, by rows and (the transpose) by columns.
        ((1, (1 << 21) + 1), [(0, 1 << 21)]),
        (((1 << 21) + 1, 1), [(0, 0)]),
        # Either side of the bands-of-columns threshold (isqrt(rows) * cols > 2**21).
        ((4, (1 << 20) + 1), [(3, 0), (0, 1 << 20)]),
        ((4, 1 << 20), [(3, 0), (0, (1 << 20) - 1)]),
    ],
)
def test_the_real_bands_at_their_limits_are_scipys(
    shape: tuple[int, int], cells: list[tuple[int, int]]
) -> None:
    occupied = np.zeros(shape, dtype=bool)
    for at in cells:
        occupied[at] = True
    assert len(list(distance_module.obstacle_distance_bands(occupied))) >= 2
    got = distance_module.obstacle_distance(occupied)
    assert np.array_equal(float_bits(got), float_bits(scipy_distances(occupied)))
    assert np.array_equal(float_bits(_banded(occupied)), float_bits(got))


@settings(max_examples=60, deadline=None)
@given(
    occupied=_adversarial_masks(),
    band=st.integers(1, 20),
    resolution=st.sampled_from([0.05, 0.1, 1.0]),
    robot=st.sampled_from([0.0, 0.5, 1.0, 200.0]),  # 200 m: beyond every grid's diagonal
    extra=st.sampled_from([0.0, 0.05, 2.5, 500.0]),
)
def test_costs_of_ties_and_far_radii_are_the_whole_grids(
    occupied: np.ndarray, band: int, resolution: float, robot: float, extra: float
) -> None:
    unknown = np.zeros_like(occupied)
    unknown[::3, 1::4] = True
    unknown &= ~occupied
    grid = OccupancyGrid.from_occupancy(occupied, resolution=resolution, unknown=unknown)

    def calls() -> list[np.ndarray]:
        return [
            grid.inflate(robot),
            costmap(grid, robot_radius=robot, inflation_radius=robot + extra),
            costmap(grid, robot_radius=robot, inflation_radius=robot + extra, inflate_unknown=True),
            traversal_costs(grid, robot_radius=robot, inflation_radius=robot + extra),
        ]

    assert_bands_change_nothing(calls, band)


def test_masks_of_any_layout_give_the_same_costs_and_stay_as_they_were() -> None:
    rng = np.random.default_rng(45)
    occupied = rng.random((37, 53)) < 0.05
    probabilities = np.where(occupied, 0.9, 0.1)
    want = costmap(
        OccupancyGrid.from_probabilities(probabilities, resolution=0.05),
        robot_radius=0.1,
        inflation_radius=0.5,
    )
    fortran = np.asfortranarray(probabilities)
    strided = np.repeat(probabilities, 2, axis=1)[:, ::2]
    frozen = probabilities.copy()
    frozen.flags.writeable = False
    swapped = probabilities.astype(">f8")
    for given_probabilities in (fortran, strided, frozen, swapped):
        kept = given_probabilities.copy()
        grid = OccupancyGrid.from_probabilities(given_probabilities, resolution=0.05)
        assert np.array_equal(costmap(grid, robot_radius=0.1, inflation_radius=0.5), want)
        assert np.array_equal(given_probabilities, kept)


def test_threads_transforming_at_once_get_the_lone_calls_bits() -> None:
    # Two real bands of rows, and three of columns; the kernels release the GIL.
    rng = np.random.default_rng(7)
    tall = OccupancyGrid.from_occupancy(rng.random((1500, 1500)) < 0.001, resolution=0.05)
    wide = OccupancyGrid.from_occupancy(rng.random((4, 1_100_000)) < 0.0005, resolution=0.05)
    calls = [
        lambda: tall.inflate(0.3),
        lambda: tall.inflate(0.3),
        lambda: costmap(tall, robot_radius=0.2, inflation_radius=30.0),
        lambda: wide.inflate(1.0),
    ]
    serial = [call() for call in calls]
    for results in concurrent_results(calls, rounds=2):
        for got, want in zip(results, serial, strict=True):
            assert np.array_equal(got, want)


_BOUNDS = textwrap.dedent(
    """
    import numpy as np
    from scipy import ndimage
    import navkit.mapping._obstacle_distance as dm

    rng = np.random.default_rng(45)
    for rows, cols, band, by_cols in [(1, 1, 1, 0), (1, 9, 1, 1), (9, 1, 2, 0), (7, 13, 3, 0),
                                      (13, 7, 5, 1), (40, 3, 7, 0), (3, 40, 2, 1), (31, 31, 31, 0)]:
        dm._band_rows = lambda r, c, band=band: band
        dm._BAND_CELLS = 0 if by_cols else 1 << 21
        for density in (0.0, 0.02, 0.3, 1.0):
            occ = rng.random((rows, cols)) < density
            occ[rng.integers(rows), rng.integers(cols)] = density > 0
            out = np.full(occ.shape, np.nan)
            for where, dist in dm.obstacle_distance_bands(occ):
                out[where] = dist
            want = ndimage.distance_transform_edt(~occ) if occ.any() else np.full(occ.shape, np.inf)
            assert np.array_equal(out, want), (rows, cols, band, by_cols, density)
    print("checked")
    """
)


def test_the_kernels_stay_inside_their_arrays(tmp_path: Path) -> None:
    assert bounds_checked(_BOUNDS, tmp_path / "nbc")[-1] == "checked"


# The warm-up's mapping step in a fresh process (from the suite's cache, or compiled),
# then every public caller of the kernels, wide grids and unknown sources included.
_WARMED = textwrap.dedent(
    """
    import json
    import numpy as np
    from navkit.mapping import OccupancyGrid, costmap, traversal_costs
    from navkit.mapping import _edt_kernels as kernels
    from navkit.sim import _warmup

    def signatures():
        # Every kernel of the module: one since review 46 (the checkpoints' sweep
        # is part of band_distances), each compiled for one signature.
        return {f"{name}{s}" for name, k in vars(kernels).items()
                if hasattr(k, "signatures") for s in k.signatures}

    _warmup._STEPS["mapping"][0]()
    warmed = signatures()
    occupied = np.zeros((4, 1_100_000), dtype=bool)  # by bands of columns
    occupied[2, 7] = True
    for grid in (OccupancyGrid.from_occupancy(occupied, resolution=0.05,
                                              unknown=np.roll(occupied, 3)),
                 OccupancyGrid.from_occupancy(occupied[:, :50].T.copy(), resolution=0.1)):
        grid.inflate(0.3)
        costmap(grid, robot_radius=0.1, inflation_radius=0.4, inflate_around_unknown=True)
        traversal_costs(grid, robot_radius=0.1, unknown_cost=2.0)
    print(json.dumps([len(warmed), sorted(signatures() - warmed)]))
    """
)


def test_the_warm_up_compiles_every_signature_the_callers_use() -> None:
    warmed, extra = probe_outcome(_WARMED)
    assert warmed == 1 and extra == []


def _peak_grid(rows: int, cols: int) -> OccupancyGrid:
    kind = np.random.default_rng(45).choice(3, size=(rows, cols), p=[0.98, 0.01, 0.01])
    return OccupancyGrid.from_occupancy(kind == 1, resolution=0.05, unknown=kind == 2)


@pytest.mark.parametrize(
    ("rows", "cols"),
    [
        (1448, 1448),  # one band, the whole grid (just under 2**21 cells)
        (4096, 4096),  # eight bands: costmap's docstring measured its peak here
    ],
)
def test_costmap_keeps_to_its_documented_peak(rows: int, cols: int) -> None:
    # "Peak memory about 3 bytes a cell and 40 MiB whatever the radius", for a
    # radius whose costs decay over every free cell. Before: 51.0 MiB (25.5 bytes a
    # cell; 21 before review 45) and 96.3 MiB; now 42.0 and 84.3.
    grid = _peak_grid(rows, cols)
    peak, _ = peak_bytes(lambda: costmap(grid, robot_radius=0.2, inflation_radius=150.0))
    assert peak <= 3 * rows * cols + (40 << 20), f"{peak / 2**20:.1f} MiB"


def test_inflate_holds_one_band_of_distances_at_a_time() -> None:
    # The mask and the result (2 bytes a cell) and one band of 2**21 cells (its
    # int64 column distances and float64 distances: 32 MiB). Before: 80.3 MiB; now 64.3.
    rows = cols = 4096
    grid = _peak_grid(rows, cols)
    peak, _ = peak_bytes(lambda: grid.inflate(40.0))
    assert peak <= 2 * rows * cols + (33 << 20), f"{peak / 2**20:.1f} MiB"


def test_obstacle_distance_of_a_wide_grid_holds_one_band_at_a_time() -> None:
    # By bands of columns: the float64 result, the transposed mask (1 byte a cell)
    # and one band of 2**21 cells (32 MiB). Before: 192.0 MiB (12 bytes a cell); now 176.
    rows, cols = 16, 1 << 20
    occupied = np.random.default_rng(45).random((rows, cols)) < 0.01
    peak, _ = peak_bytes(lambda: distance_module.obstacle_distance(occupied))
    assert peak <= 9 * rows * cols + (34 << 20), f"{peak / 2**20:.1f} MiB"


# 707 / m over a 1 m radius: exp(707) is finite, 252 times it is not; 1e-300 / m
# (the smallest rates allowed are any above 0) underflows the exponent itself.
@pytest.mark.parametrize("scale", [1e-300, 1e-310, 1.0, 707.0, 1e12])
def test_costs_are_the_same_when_numpy_raises_on_every_float_error(scale: float) -> None:
    # Obstacle cells and cells next to one at a huge decay rate: exp(scale *
    # robot_radius) overflows and exp(-scale * d) underflows if they are computed.
    occupied = np.zeros((9, 40), dtype=bool)
    occupied[4, [0, 20]] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    calls = [
        lambda: costmap(grid, robot_radius=1.0, inflation_radius=3.0, cost_scaling_factor=scale),
        lambda: traversal_costs(
            grid, robot_radius=0.0, inflation_radius=3.0, cost_scaling_factor=scale
        ),
    ]
    want = [call() for call in calls]
    with np.errstate(all="raise"):
        got = [call() for call in calls]
    for a, b in zip(got, want, strict=True):
        assert np.array_equal(a, b)
