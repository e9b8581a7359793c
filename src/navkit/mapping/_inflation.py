"""Obstacle inflation: Euclidean masks and Nav2 inflation-layer costs (private)."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray
from scipy import ndimage

__all__ = [
    "FREE_SPACE",
    "INSCRIBED_INFLATED_OBSTACLE",
    "LETHAL_OBSTACLE",
    "NO_INFORMATION",
    "inflation_costs",
    "obstacle_distance",
]

# Cost values of ROS 2 Nav2 (nav2_costmap_2d/cost_values.hpp).
NO_INFORMATION = 255
LETHAL_OBSTACLE = 254
INSCRIBED_INFLATED_OBSTACLE = 253
FREE_SPACE = 0


def obstacle_distance(occupied: NDArray[np.bool_]) -> NDArray[np.float64]:
    """Distance in cells from each cell centre to the nearest occupied cell centre.

    Exact Euclidean distance transform; ``inf`` everywhere when nothing is occupied.
    """
    if not occupied.any():
        return np.full(occupied.shape, np.inf)
    return np.asarray(ndimage.distance_transform_edt(~occupied), dtype=np.float64)


def inflation_costs(
    occupied: NDArray[np.bool_],
    unknown: NDArray[np.bool_],
    resolution: float,
    inscribed_radius: float,
    inflation_radius: float,
    cost_scaling_factor: float,
    inflate_unknown: bool,
) -> NDArray[np.uint8]:
    """Nav2 inflation-layer costs for a static layer of occupied/unknown cells.

    Reproduces ``nav2_costmap_2d::InflationLayer``: occupied cells get 254; cells
    whose centre lies within ``inscribed_radius`` of an occupied centre get 253;
    farther cells up to ``ceil(inflation_radius / resolution)`` cells away get
    ``int(252 * exp(-cost_scaling_factor * (d - inscribed_radius)))``; the rest 0.
    Unknown cells keep 255 unless the inflated cost is >= 253 (or > 0 with
    ``inflate_unknown``). Distances use an exact Euclidean distance transform
    where Nav2 propagates distances by a breadth-first wave, which can only
    overestimate them.
    """
    dist_cells = obstacle_distance(occupied)
    max_cells = math.ceil(inflation_radius / resolution)
    dist_m = dist_cells * resolution
    cost = np.zeros(occupied.shape, dtype=np.uint8)
    band = (dist_cells > 0) & (dist_cells <= max_cells)
    cost[band & (dist_m <= inscribed_radius)] = INSCRIBED_INFLATED_OBSTACLE
    decaying = band & (dist_m > inscribed_radius)
    factor = np.exp(-cost_scaling_factor * (dist_m[decaying] - inscribed_radius))
    # Nav2 truncates: (unsigned char)((INSCRIBED_INFLATED_OBSTACLE - 1) * factor).
    cost[decaying] = ((INSCRIBED_INFLATED_OBSTACLE - 1) * factor).astype(np.uint8)
    cost[occupied] = LETHAL_OBSTACLE
    keep_unknown = unknown & ~occupied
    if inflate_unknown:
        keep_unknown &= cost == FREE_SPACE
    else:
        keep_unknown &= cost < INSCRIBED_INFLATED_OBSTACLE
    cost[keep_unknown] = NO_INFORMATION
    return cost
