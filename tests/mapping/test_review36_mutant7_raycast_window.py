"""The ray-cast kernel stays inside its buffers near the map's edges (mutation review, session 40).

``integrate_beams`` clears and marks a scratch window of the cells the scan can
reach, clipped to the map, in a caller's buffer of exactly the map's size, and
writes no bounds checks (numba has none by default). A mutant that clipped the
window's top row one row too high (``rows + 1`` for ``rows - 1`` in the test of
the clip) survived the ray-casting tests: it only overran the scratch buffer, by a few bytes,
when the scan's reach ended between one and two rows above the map.

Here the kernel writes into views of larger buffers whose guard bands hold known
bytes, for random scans from sensors in and around a rotated map whose reach
ends anywhere near its edges, and the result is checked against outside
oracles: the guard bands unchanged; the count returned equal to the number of
cells that changed; the cells holding the hit increment exactly the end cells
of the real returns that end inside the map (computed here); with ``exact`` every
cell a beam passes through (points sampled along it) updated, and every updated
cell touching some beam (shapely's distance from the cell's square).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from shapely.geometry import LineString

from navkit.mapping._raycast_kernels import integrate_beams

ROWS, COLS = 7, 9
RES = 0.5
ORIGIN = (-1.3, 0.7, 0.3)  # x, y, yaw of the map's corner
HIT = 0.75
MISS = -0.25
GUARD = 3  # guard rows of the log-odds buffer, and 3 * COLS guard bytes of the scratch
SENTINEL = np.float32(9.5)


def _to_world(u: float, v: float) -> tuple[float, float]:
    """Map coordinates (cells) to world coordinates (m)."""
    x0, y0, yaw = ORIGIN
    c, s = math.cos(yaw), math.sin(yaw)
    return x0 + RES * (c * u - s * v), y0 + RES * (s * u + c * v)


def _cast(
    su: float, sv: float, ranges: np.ndarray, heading: float, exact: bool
) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
    big = np.full((ROWS + 2 * GUARD, COLS), SENTINEL, dtype=np.float32)
    big[GUARD : GUARD + ROWS] = 0.0
    grid = big[GUARD : GUARD + ROWS]  # a C-contiguous view between two guard bands
    raw = np.full(ROWS * COLS + 2 * GUARD * COLS, 0xA5, dtype=np.uint8)
    scratch = raw[GUARD * COLS : GUARD * COLS + ROWS * COLS]
    sx, sy = _to_world(su, sv)
    n = integrate_beams(
        grid, ORIGIN[0], ORIGIN[1], ORIGIN[2], RES, sx, sy, heading + ORIGIN[2], ranges,
        0.0, 2.0 * math.pi / ranges.shape[0], 0.05, 4.0, HIT, MISS, -50.0, 50.0, exact, scratch,
    )  # fmt: skip
    return int(n), big, raw, grid


def _scan(rng: np.random.Generator) -> tuple[float, float, np.ndarray, float]:
    """A sensor in or near the map and ranges whose reach ends near an edge."""
    su = float(rng.uniform(-2.0, COLS + 2.0))
    sv = float(rng.uniform(-2.0, ROWS + 2.0))
    # The window reaches longest / RES + 2 cells from the sensor: pick the longest
    # return so that the window ends within two cells of one of the map's edges.
    edge = [
        -su, COLS - su, -sv, ROWS - sv,
    ][int(rng.integers(4))]  # fmt: skip
    reach_cells = abs(edge) + float(rng.uniform(-3.5, -0.5))
    longest = max(reach_cells, 0.3) * RES
    n_beams = int(rng.integers(3, 12))
    ranges = rng.uniform(0.1, 1.0, n_beams) * longest
    ranges[int(rng.integers(n_beams))] = longest
    if rng.random() < 0.3:
        ranges[int(rng.integers(n_beams))] = math.inf  # clears up to range_max
    if rng.random() < 0.3:
        ranges[int(rng.integers(n_beams))] = 0.01  # below range_min: skipped
    return su, sv, ranges, float(rng.uniform(-math.pi, math.pi))


@pytest.mark.parametrize("exact", [False, True])
def test_random_scans_near_the_edges_stay_in_the_buffers_and_count_what_changed(
    exact: bool,
) -> None:
    rng = np.random.default_rng(4036)
    hits_seen = 0
    for _ in range(400):
        su, sv, ranges, heading = _scan(rng)
        n, big, raw, grid = _cast(su, sv, ranges, heading, exact)
        # Nothing outside the two buffers' views was written.
        assert (big[:GUARD] == SENTINEL).all() and (big[GUARD + ROWS :] == SENTINEL).all()
        end = GUARD * COLS + ROWS * COLS
        assert (raw[: GUARD * COLS] == 0xA5).all() and (raw[end:] == 0xA5).all()
        # One update per distinct cell: the count is the number of cells changed.
        assert n == int(np.count_nonzero(grid)), (su, sv, ranges, heading)
        # The hit cells are the end cells of the real returns that end inside the map.
        ends = set()
        step = 2.0 * math.pi / ranges.shape[0]
        for k, r in enumerate(ranges):
            if not 0.05 <= r < 4.0:
                continue
            phi = heading + k * step
            eu = su + r / RES * math.cos(phi)
            ev = sv + r / RES * math.sin(phi)
            if min(abs(eu - round(eu)), abs(ev - round(ev))) < 1e-9:
                continue  # on a grid line: its cell is a matter of rounding
            if 0.0 <= eu < COLS and 0.0 <= ev < ROWS:
                ends.add((math.floor(ev), math.floor(eu)))
        hit_rows, hit_cols = np.nonzero(grid == np.float32(HIT))
        hit_cells = {(int(r), int(c)) for r, c in zip(hit_rows, hit_cols, strict=True)}
        assert ends <= hit_cells
        hits_seen += len(ends)
    assert hits_seen > 400


def test_exact_walk_updates_the_cells_each_beam_passes_through_and_no_other() -> None:
    rng = np.random.default_rng(4037)
    rows, cols = np.mgrid[0:ROWS, 0:COLS]
    squares = shapely.box(cols.ravel(), rows.ravel(), cols.ravel() + 1.0, rows.ravel() + 1.0)
    for _ in range(150):
        su, sv, ranges, heading = _scan(rng)
        n, _, _, grid = _cast(su, sv, ranges, heading, True)
        step = 2.0 * math.pi / ranges.shape[0]
        segments = []
        crossed: set[tuple[int, int]] = set()
        for k, r in enumerate(ranges):
            if not r >= 0.05:
                continue
            length = min(r, 4.0) / RES
            phi = heading + k * step
            du, dv = length * math.cos(phi), length * math.sin(phi)
            segments.append(LineString([(su, sv), (su + du, sv + dv)]))
            # Points strictly inside the beam (its end cell excepted, which takes the
            # hit when it is a return), away from every grid line.
            for t in np.linspace(0.0, 1.0, 200)[:-1]:
                u, v = su + t * du, sv + t * dv
                if min(abs(u - round(u)), abs(v - round(v))) < 1e-6:
                    continue
                if 0.0 <= u < COLS and 0.0 <= v < ROWS:
                    crossed.add((math.floor(v), math.floor(u)))
        changed = grid.ravel() != 0.0
        for r_c in crossed:
            assert grid[r_c] != 0.0, (r_c, su, sv, ranges, heading)
        if segments:
            beams = shapely.MultiLineString(segments)
            near = shapely.distance(squares, beams) <= 1e-9
            assert not (changed & ~near).any(), (su, sv, ranges, heading)
        assert n == int(changed.sum())
