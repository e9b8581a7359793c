"""navkit's Nav2 costmap against independent oracles of Nav2's two inflation layers (review 51).

The oracles are written from Nav2's documented algorithm (``nav2_costmap_2d``,
``cost_values.hpp``, ``InflationLayer::computeCost``), not from navkit:

* the classic layer (``LegacyInflationLayer`` since 2026): a breadth-first wave
  from every lethal cell, cells taken in order of their distance to the
  obstacle whose wave reached them first, neighbours enqueued only within
  ``ceil(inflation_radius / resolution)`` cells of that obstacle;
* the refactored layer (2026): an exact float32 distance transform, the cost
  looked up at the distance rounded to 1/100 of a cell.

Both take ``computeCost(d)`` = 254 at 0, 253 where ``d * resolution <=
inscribed_radius`` (compared in float64, as written), else
``(unsigned char)(252 * exp(-cost_scaling_factor * (d * resolution - r)))``, and
write an unknown cell's cost only when it is >= 253 (> 0 with
``inflate_unknown``).
"""

from __future__ import annotations

import heapq
import inspect
import math
from pathlib import Path
from types import SimpleNamespace as NS

import numpy as np
import pytest
from scipy.ndimage import distance_transform_edt

from navkit.mapping import OccupancyGrid, costmap, traversal_costs
from navkit.mapping.io import grid_from_msg, grid_to_msg_fields

LETHAL, INSCRIBED, UNKNOWN = 254, 253, 255
LUT_PRECISION = 100


def _compute_cost(d: float, resolution: float, inscribed: float, scaling: float) -> int:
    """Nav2's ``computeCost`` of a distance in cells."""
    if d == 0:
        return LETHAL
    if d * resolution <= inscribed:
        return INSCRIBED
    return int(252 * math.exp(-scaling * (d * resolution - inscribed)))


def _combine(old: int, cost: int, inflate_unknown: bool) -> int:
    """Nav2's write of an inflated cost over the static layer's."""
    if old == UNKNOWN and (cost > 0 if inflate_unknown else cost >= INSCRIBED):
        return cost
    return max(old, cost)


def _static_layer(grid: OccupancyGrid) -> np.ndarray:
    """The static layer Nav2 builds from a trinary map: 254, 255 or 0."""
    layer = np.zeros(grid.shape, dtype=np.int64)
    layer[grid.unknown()] = UNKNOWN
    layer[grid.occupied()] = LETHAL
    return layer


def nav2_static_layer(data: np.ndarray) -> np.ndarray:
    """Nav2's ``StaticLayer::interpretValue`` of message values, with its defaults.

    ``trinary_costmap`` true, ``lethal_cost_threshold`` 100, unknown -1 kept as
    255 (``track_unknown_space``, as Nav2's bringup sets it for the global costmap).
    """
    layer = np.zeros(data.shape, dtype=np.int64)
    layer[data == -1] = UNKNOWN
    layer[data >= 100] = LETHAL
    return layer


def nav2_legacy(
    grid: OccupancyGrid,
    inscribed: float,
    inflation: float,
    scaling: float,
    *,
    inflate_unknown: bool = False,
    inflate_around_unknown: bool = False,
    static: np.ndarray | None = None,
) -> np.ndarray:
    """Costs of Nav2's classic (wave) inflation layer over a static layer.

    ``static`` defaults to the layer Nav2 builds from the grid's trinary map.
    """
    master = _static_layer(grid) if static is None else static.copy()
    rows, cols = master.shape
    res = grid.resolution
    reach = max(0, math.ceil(inflation / res))
    seen = np.zeros(master.shape, dtype=bool)
    # Nav2's bins of equal distance, first in first out within a bin: a heap keyed
    # by (distance, arrival order).
    queue: list[tuple[float, int, int, int, int, int]] = []
    order = 0
    sources = (master == LETHAL) | (inflate_around_unknown & (master == UNKNOWN))
    for r, c in np.argwhere(sources):
        queue.append((0.0, order, int(r), int(c), int(r), int(c)))
        order += 1
    heapq.heapify(queue)
    while queue:
        _, _, r, c, sr, sc = heapq.heappop(queue)
        if seen[r, c]:
            continue
        seen[r, c] = True
        cost = _compute_cost(math.hypot(r - sr, c - sc), res, inscribed, scaling)
        master[r, c] = _combine(int(master[r, c]), cost, inflate_unknown)
        for nr, nc in ((r, c - 1), (r - 1, c), (r, c + 1), (r + 1, c)):
            if 0 <= nr < rows and 0 <= nc < cols and not seen[nr, nc]:
                d = math.hypot(nr - sr, nc - sc)
                if d <= reach:
                    heapq.heappush(queue, (d, order, nr, nc, sr, sc))
                    order += 1
    return master.astype(np.uint8)


def nav2_refactored(
    grid: OccupancyGrid,
    inscribed: float,
    inflation: float,
    scaling: float,
    *,
    inflate_unknown: bool = False,
    inflate_around_unknown: bool = False,
) -> np.ndarray:
    """Costs of Nav2's refactored (distance transform) inflation layer."""
    master = _static_layer(grid)
    res = grid.resolution
    reach = max(0, math.ceil(inflation / res))
    sources = (master == LETHAL) | (inflate_around_unknown & (master == UNKNOWN))
    squared = np.rint(distance_transform_edt(~sources) ** 2)
    dist = np.sqrt(squared.astype(np.float32))
    entries = range(reach * LUT_PRECISION + 2)  # Nav2's table: one entry past the reach
    lut = [_compute_cost(k / LUT_PRECISION, res, inscribed, scaling) for k in entries]
    index = np.minimum(
        len(lut) - 1, (dist * np.float32(LUT_PRECISION) + np.float32(0.5)).astype(np.int64)
    )
    for r, c in np.argwhere(dist <= np.float32(reach)):
        cost = lut[index[r, c]]
        master[r, c] = _combine(int(master[r, c]), cost, inflate_unknown)
    return master.astype(np.uint8)


def _ros_map(shared_data: Path, folder: str, name: str) -> OccupancyGrid:
    return OccupancyGrid.load(shared_data / "ros-map-server-maps" / folder / name)


# --- crafted maps --------------------------------------------------------------


def test_one_obstacle_matches_the_classic_layer_exactly() -> None:
    # One obstacle: the wave's distances are exact, so every cost agrees.
    occ = np.zeros((25, 31), dtype=bool)
    occ[12, 15] = True
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.05)
    for inscribed, inflation, scaling in ((0.12, 0.55, 10.0), (0.105, 0.5, 3.0), (0.0, 0.3, 8.0)):
        ours = costmap(
            grid,
            robot_radius=inscribed,
            inflation_radius=inflation,
            cost_scaling_factor=scaling,
        )
        assert np.array_equal(ours, nav2_legacy(grid, inscribed, inflation, scaling))
        # The refactored layer's rounding to 1/100 cell moves a cost by at most 1 here.
        new = nav2_refactored(grid, inscribed, inflation, scaling)
        assert np.abs(ours.astype(int) - new.astype(int)).max() <= 1


def test_a_cell_exactly_robot_radius_away_is_inscribed_here_not_in_nav2() -> None:
    # 3 * 0.05 == 0.15000000000000002 > 0.15: Nav2 (both layers) gives the
    # cells three cells away 251; navkit, as inflate(), counts them inscribed.
    occ = np.zeros((1, 8), dtype=bool)
    occ[0, 0] = True
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.05)
    ours = costmap(grid, robot_radius=0.15, inflation_radius=0.4, cost_scaling_factor=5.0)
    for nav2 in (nav2_legacy, nav2_refactored):
        theirs = nav2(grid, 0.15, 0.4, 5.0)
        assert theirs[0, 3] == 251
        assert ours[0, 3] == INSCRIBED
        theirs[0, 3] = INSCRIBED
        assert np.array_equal(ours, theirs)
    assert grid.inflate(0.15)[0].tolist() == [True] * 4 + [False] * 4
    assert traversal_costs(grid, robot_radius=0.15, inflation_radius=0.4)[0, 3] == math.inf
    # The difference is stated where users read about Nav2's costs.
    notes = inspect.getdoc(costmap) or ""
    assert "0.15000000000000002" in notes
    assert "LegacyInflationLayer" in notes


def test_the_wave_leaves_cells_within_reach_unvisited() -> None:
    # Cell (6, 2) lies exactly 5 cells (the reach, ceil(0.5 / 0.1)) from the
    # obstacle at (3, 6), but the cells next to it were reached first by the
    # waves of the other two obstacles, from which it lies farther than 5: the
    # classic layer never visits it. (The smallest such map of 4000 random ones.)
    occ = np.zeros((8, 8), dtype=bool)
    occ[1, 4] = occ[3, 6] = occ[7, 7] = True
    assert distance_transform_edt(~occ)[6, 2] == 5.0
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.1)
    ours = costmap(grid, robot_radius=0.0, inflation_radius=0.5, cost_scaling_factor=1.0)
    theirs = nav2_legacy(grid, 0.0, 0.5, 1.0)
    assert theirs[6, 2] == 0
    assert ours[6, 2] == int(252 * math.exp(-0.5)) == 152
    theirs[6, 2] = ours[6, 2]
    assert np.array_equal(ours, theirs)
    assert nav2_refactored(grid, 0.0, 0.5, 1.0)[6, 2] == 152
    # The same cell unknown, under inflate_unknown: 255 there, its cost here.
    unknown = np.zeros_like(occ)
    unknown[6, 2] = True
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.1, unknown=unknown)
    ours = costmap(
        grid, robot_radius=0.0, inflation_radius=0.5, cost_scaling_factor=1.0, inflate_unknown=True
    )
    assert nav2_legacy(grid, 0.0, 0.5, 1.0, inflate_unknown=True)[6, 2] == UNKNOWN
    assert ours[6, 2] == 152


def _message(data: np.ndarray, resolution: float) -> NS:
    """A ``nav_msgs/OccupancyGrid`` look-alike of rows of values (row 0 first)."""
    rows, cols = data.shape
    origin = NS(position=NS(x=0.0, y=0.0, z=0.0), orientation=NS(x=0.0, y=0.0, z=0.0, w=1.0))
    info = NS(width=cols, height=rows, resolution=resolution, origin=origin)
    return NS(info=info, data=data.astype(np.int8).ravel().tolist())


def test_a_message_with_values_between_0_and_100_is_not_nav2s_static_layer() -> None:
    # Nav2 (trinary_costmap, lethal_cost_threshold 100) reads only 100 as lethal;
    # the grid of grid_from_msg classes values by its thresholds 0.65 / 0.196.
    values = np.array([[-1, 0, 19, 20, 50, 65, 66, 99, 100]])
    grid = grid_from_msg(_message(values, 0.05))
    ours = costmap(grid, robot_radius=0.0, inflation_radius=0.0)
    assert ours[0].tolist() == [255, 0, 0, 255, 255, 255, 254, 254, 254]
    theirs = nav2_legacy(grid, 0.0, 0.0, 10.0, static=nav2_static_layer(values))
    assert theirs[0].tolist() == [255, 0, 0, 0, 0, 0, 0, 0, 254]
    for doc in (inspect.getdoc(costmap) or "", inspect.getdoc(grid_from_msg) or ""):
        assert "only 100" in doc
        assert "20..65" in doc


# --- real maps (NAVKIT_DATA) ----------------------------------------------------


def test_a_trinary_message_gives_nav2s_costmap(shared_data: Path) -> None:
    # map_server publishes the turtlebot3 map as 0 / 100 / -1: through
    # grid_from_msg, navkit's costmap is Nav2's costmap of the message.
    fields = grid_to_msg_fields(
        _ros_map(shared_data, "turtlebot3_world", "map.yaml"), mode="trinary"
    )
    values = np.asarray(fields.data).reshape(fields.height, fields.width)
    assert set(np.unique(values).tolist()) == {-1, 0, 100}
    grid = grid_from_msg(_message(values, fields.resolution))
    ours = costmap(grid, robot_radius=0.2, inflation_radius=0.55, cost_scaling_factor=3.0)
    theirs = nav2_legacy(grid, 0.2, 0.55, 3.0, static=nav2_static_layer(values))
    assert np.array_equal(ours, theirs)


@pytest.mark.parametrize(
    ("folder", "name"),
    [("turtlebot3_world", "map.yaml"), ("lse_arena", "lse_arena.yaml")],
)
def test_real_maps_against_both_layers(shared_data: Path, folder: str, name: str) -> None:
    grid = _ros_map(shared_data, folder, name)
    # Radii away from exact multiples of the cell (the documented tie above).
    for inscribed, inflation, scaling, unknown_too in (
        (0.2, 0.55, 3.0, False),
        (0.105, 0.5, 10.0, True),
    ):
        ours = costmap(
            grid,
            robot_radius=inscribed,
            inflation_radius=inflation,
            cost_scaling_factor=scaling,
            inflate_unknown=unknown_too,
        ).astype(int)
        legacy = nav2_legacy(grid, inscribed, inflation, scaling, inflate_unknown=unknown_too)
        known = (ours != UNKNOWN) & (legacy != UNKNOWN)
        # Exact distances are never longer than the wave's: never a lower cost.
        assert np.all(ours[known] >= legacy[known])
        assert np.mean(ours == legacy) > 0.99
        new = nav2_refactored(grid, inscribed, inflation, scaling, inflate_unknown=unknown_too)
        assert np.abs(ours - new.astype(int)).max() <= 1
        for value in (LETHAL, INSCRIBED, UNKNOWN):
            assert np.array_equal(ours == value, new == value)


def test_willow_garage_unknown_cells_the_wave_never_reaches(shared_data: Path) -> None:
    # On this map (walls mostly unknown) the classic layer leaves unknown cells
    # within the inflation radius at 255 under inflate_unknown; navkit, with
    # exact distances, gives them their inflated cost (as Nav2's refactored layer).
    grid = _ros_map(shared_data, "willow_garage_2010", "willow-2010-02-18-0.10.yaml")
    kwargs = {"robot_radius": 0.105, "inflation_radius": 0.5, "inflate_unknown": True}
    ours = costmap(grid, cost_scaling_factor=10.0, **kwargs).astype(int)
    legacy = nav2_legacy(grid, 0.105, 0.5, 10.0, inflate_unknown=True).astype(int)
    unreached = (legacy == UNKNOWN) & (ours != UNKNOWN)
    assert unreached.any()
    assert np.all(ours[unreached] > 0)
    assert np.all(distance_transform_edt(~grid.occupied())[unreached] <= 5.0)
    new = nav2_refactored(grid, 0.105, 0.5, 10.0, inflate_unknown=True).astype(int)
    assert np.array_equal(ours == UNKNOWN, new == UNKNOWN)


def test_traversal_costs_are_smac_2ds_cell_costs() -> None:
    # Smac Planner 2D (Node2D::getTraversalCost) multiplies a move's length by
    # 1 + cost_travel_multiplier * c / 252; NavFn uses (uchar)(50 + 0.8 c) over
    # its neutral cost 50.
    occ = np.zeros((9, 9), dtype=bool)
    occ[4, 4] = True
    grid = OccupancyGrid.from_occupancy(occ, resolution=0.05)
    nav2 = nav2_legacy(grid, 0.06, 0.3, 5.0).astype(float)
    passable = nav2 < INSCRIBED
    assert np.unique(nav2[passable]).size > 5
    for multiplier in (2.0, 4.0, 0.5):
        ours = traversal_costs(
            grid,
            robot_radius=0.06,
            inflation_radius=0.3,
            cost_scaling_factor=5.0,
            cost_weight=multiplier,
        )
        smac = 1.0 + multiplier * nav2 / 252.0
        assert np.allclose(ours[passable], smac[passable], rtol=1e-15, atol=0.0)
        assert np.all(np.isinf(ours[~passable]))
    navfn = np.floor(50.0 + 0.8 * nav2) / 50.0
    default = traversal_costs(
        grid, robot_radius=0.06, inflation_radius=0.3, cost_scaling_factor=5.0
    )
    assert np.all(np.abs(default[passable] / navfn[passable] - 1.0) < 0.01)
    assert "cost_travel_multiplier" in (inspect.getdoc(traversal_costs) or "")


def map_server_scale_values(grey: np.ndarray, free: float, occupied: float) -> np.ndarray:
    """Nav2 map_server's published values of opaque grey pixels in ``mode: scale``."""
    occ = 1.0 - grey / 255.0
    values = np.rint((occ - free) / (occupied - free) * 100.0)
    values[occ > occupied] = 100
    values[occ < free] = 0
    return values.astype(np.int64)


def test_a_scale_mode_map_is_not_nav2s_static_layer(shared_data: Path, tmp_path: Path) -> None:
    # The turtlebot3 PGM (0 / 205 / 254) read with mode: scale: map_server
    # publishes 205 as rint((0.196078 - 0.196) / 0.454 * 100) = 0, free space in
    # Nav2's costmap; the grid of read_map holds p = 0.196078, between its
    # thresholds: unknown, 255 in navkit's costmap.
    folder = shared_data / "ros-map-server-maps" / "turtlebot3_world"
    (tmp_path / "map.pgm").write_bytes((folder / "map.pgm").read_bytes())
    text = (folder / "map.yaml").read_text()
    (tmp_path / "map.yaml").write_text(text.rstrip("\n") + "\nmode: scale\n")
    grid = OccupancyGrid.load(tmp_path / "map.yaml")
    trinary = OccupancyGrid.load(folder / "map.yaml")
    ours = costmap(grid, robot_radius=0.0, inflation_radius=0.0)
    assert np.array_equal(ours, costmap(trinary, robot_radius=0.0, inflation_radius=0.0))
    image = pytest.importorskip("PIL.Image")
    grey = np.asarray(image.open(folder / "map.pgm"), dtype=np.float64)[::-1]
    values = map_server_scale_values(grey, 0.196, 0.65)
    theirs = nav2_static_layer(values)
    differ = ours != theirs
    assert np.array_equal(differ, grey == 205)
    assert set(ours[differ].tolist()) == {UNKNOWN}
    assert set(theirs[differ].tolist()) == {0}
    assert "mode: scale" in (inspect.getdoc(costmap) or "")
