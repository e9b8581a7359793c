"""Review 51 (MUTANT31): the correlative search looks a point up in the cell it truncates to.

PLANCOLD's 39e2790 wrote the search's cell lookup with ``np.int64`` instead of
``int`` (the same truncation). No test read which cell the search picks for a
point: rounding instead of truncating (``np.int64(row + 0.5)``) passed every
scan-matcher test. Checked here with the search held at its input pose
(no steps), whose cost is then the mean ``(1 - p)^2`` of the cells the points
fall in: points in the upper half of a cell, a hair below the next cell's
edge, and in the last half cell of the map (where rounding reads past it).
"""

from __future__ import annotations

import numpy as np

from navkit.mapping._scan_matcher_kernels import correlative_search


def _expected(logodds: np.ndarray, points: np.ndarray) -> float:
    """Mean ``(1 - p)^2`` of the cells ``int()`` gives (1/4 off the map), float64."""
    rows, cols = logodds.shape
    total = 0.0
    for x, y in points:
        if 0.0 <= y < rows and 0.0 <= x < cols:
            p = 1.0 / (1.0 + np.exp(-float(logodds[int(y), int(x)])))
            total += (1.0 - p) ** 2
        else:
            total += 0.25
    return float(total / points.shape[0])


def test_the_search_reads_the_cell_a_point_truncates_to() -> None:
    rng = np.random.default_rng(5131)
    logodds = rng.normal(0.0, 3.0, (5, 6)).astype(np.float32)
    # Unit cells, the map's origin at the world's: a point (x, y) is in cell (int(y), int(x)).
    below = np.nextafter(np.arange(1.0, 5.0), 0.0)  # a hair below each cell edge
    xs = [0.0, 0.75, *below, 5.6, 5.999]
    ys = [0.0, 0.6, *below, 4.5, 4.999]
    points = np.array([[x, y] for x in xs for y in ys])
    for point in points:
        pose = np.zeros(3)
        cost = correlative_search(
            logodds, 0.0, 0.0, 0.0, 1.0, point[None, :].copy(), pose, 0, 0.1, 0, 0.01, 0.0, 0.0
        )
        # exp runs in float32 in the kernel: about 1e-7; neighbouring cells differ by far more.
        assert abs(cost - _expected(logodds, point[None, :])) < 1e-6, point
        np.testing.assert_array_equal(pose, np.zeros(3))
    cost = correlative_search(
        logodds, 0.0, 0.0, 0.0, 1.0, points.copy(), np.zeros(3), 0, 0.1, 0, 0.01, 0.0, 0.0
    )
    assert abs(cost - _expected(logodds, points)) < 1e-6
