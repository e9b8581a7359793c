"""A world's edge index is built a block at a time (review 44).

``build_cell_lists`` made every entry of the index at once, with some twenty
int64 and float64 temporaries each, then sorted them all: about 80 bytes an
entry at its peak (8 GB at ``World``'s documented limit of 10**8 entries),
and for a circle every cell of its bounding box (one circle across a 2048 x
2048 index: 4 million candidates, 612 MB, for 8,188 entries). It now counts
each cell's entries in a first pass and files them in a second, both over
blocks of at most 2**16 segments, row spans, entries or candidate cells: the
peak is the result and a block's temporaries. The index is the same: the
blocks are made in segment order and each is filed stably after the earlier
ones (``tests/sim/test_sim_edge_index.py`` checks it against plain Python).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import navkit.sim._edge_grid_kernels as kernels
from memory_peak import peak_bytes
from subprocess_probe import probe_outcome


def test_a_circle_across_the_index_is_filed_without_all_its_candidates_at_once() -> None:
    n = 1024
    circles = np.array([[0.0, 0.0, 1000.0]])
    args = (np.empty((0, 4)), circles, -1000.0, -1000.0, 2000.0 / n, n, n, 10**8)
    peak, (start, items) = peak_bytes(lambda: kernels.build_cell_lists(*args))
    assert items.shape == (int(start[-1]),) and 4 * n - 8 < items.shape[0] < 8 * n
    # start and its running copy (8 bytes a cell each) and a block of 2**16 candidates;
    # 153 MB before (every candidate's temporaries at once), 20 MB now.
    assert peak < 16 * (n * n + 1) + (16 << 20), f"{peak / 1e6:.0f} MB"


def test_long_segments_take_the_result_and_a_block() -> None:
    rng = np.random.default_rng(44)
    segs = rng.uniform(-100.0, 100.0, (20_000, 4))
    n = 256
    args = (segs, np.empty((0, 3)), -100.0, -100.0, 200.0 / n, n, n, 10**8)
    peak, (start, items) = peak_bytes(lambda: kernels.build_cell_lists(*args))
    entries = items.shape[0]
    assert entries == int(start[-1]) > 3_000_000
    # The result (8 an entry), start (8 a cell, twice), the blocks the first pass keeps
    # for the second (16 an entry, at most 64 MiB) and a block's temporaries (about
    # 10 MiB): 25 bytes an entry here, 74 before.
    assert peak < 24 * entries + 16 * n * n + (16 << 20), f"{peak / entries:.1f} bytes an entry"


_coordinate = st.floats(-20.0, 20.0, allow_nan=False).map(lambda v: round(v * 4.0) / 4.0)


@settings(max_examples=60, deadline=None)
@given(
    segs=st.lists(st.tuples(*[_coordinate] * 4), max_size=12),
    circles=st.lists(
        st.tuples(_coordinate, _coordinate, st.floats(0.0, 15.0, allow_nan=False)), max_size=4
    ),
    nx=st.integers(1, 12),
    ny=st.integers(1, 12),
    h=st.sampled_from([0.5, 1.0, 2.5, 4.0]),
)
@example(segs=[(-20.0, -20.0, 20.0, 20.0)], circles=[(0.0, 0.0, 15.0)], nx=12, ny=12, h=4.0)
def test_any_blocks_give_the_same_index(
    segs: list[tuple[float, ...]],
    circles: list[tuple[float, ...]],
    nx: int,
    ny: int,
    h: float,
) -> None:
    s = np.array(segs, dtype=np.float64).reshape(-1, 4)
    c = np.array(circles, dtype=np.float64).reshape(-1, 3)
    args = (s, c, -21.0, -21.0, h, nx, ny, 10**6)
    whole = kernels.build_cell_lists(*args)
    with pytest.MonkeyPatch.context() as mp:
        # Blocks of three segments, spans, entries or candidates, one circle, nothing kept.
        mp.setattr(kernels, "_BLOCK", 3)
        mp.setattr(kernels, "_CIRCLE_BLOCK", 1)
        mp.setattr(kernels, "_KEPT", 0)
        small = kernels.build_cell_lists(*args)
        over = kernels.build_cell_lists(*args[:-1], max(int(whole[0][-1]) - 1, 0))
    assert np.array_equal(whole[0], small[0]) and np.array_equal(whole[1], small[1])
    assert whole[1].dtype == small[1].dtype == np.int64
    if whole[1].size:  # too many entries: nothing filed, the number needed in start[-1]
        assert not over[1].size and not over[0][:-1].any() and over[0][-1] == whole[0][-1]


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs Linux's /proc")
def test_a_world_of_large_circles_among_many_edges_fits_the_fuzzs_address_space() -> None:
    # Two million short edges make the index about 2000 x 2000 cells of 1 m; each of
    # the ten circles across it has 3.2 million candidate cells: 5 GB at once before.
    outcome = probe_outcome(
        """
import json, resource
import numpy as np
import shapely
from navkit.sim import Circle, World
World([Circle((0.0, 0.0), 1.0)])
rng = np.random.default_rng(0)
starts = rng.uniform(-1000.0, 1000.0, (2_000_000, 2))
edges = shapely.multilinestrings(
    shapely.linestrings(np.stack((starts, starts + 0.01), axis=1))
)
circles = [Circle((0.0, 0.0), 900.0 + k) for k in range(10)]
with open("/proc/self/status") as f:
    size = next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmSize"))
resource.setrlimit(resource.RLIMIT_AS, (size + (3 << 30), resource.RLIM_INFINITY))
world = World([edges, *circles])
print(json.dumps([world._index[3], world._index[4], int(world._cell_items.shape[0])]))
""",
        timeout=900,
    )
    assert min(outcome[:2]) >= 2000 and outcome[2] > 2_000_000
