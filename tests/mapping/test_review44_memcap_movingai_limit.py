"""A MovingAI map holds at most 2**26 cells (review 44).

The limit was the grid planners' 2**31 - 1 cells, where a map's terrain alone
(``<U1``, 4 bytes a cell) takes 8 GiB, reading its file about 13 bytes a cell
at the peak (26 GiB from a 2 GiB file) and ``costs`` 8 more. At 2**26 cells
(8192 x 8192, larger than any map of the benchmark) they take 256 MiB, 832 MiB
and 512 MiB. Scenarios still name maps of up to 2**31 - 1 cells (they allocate
nothing of a map's size).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import MovingAIMap, read_movingai_map, read_movingai_scenarios
from subprocess_probe import probe_outcome


def test_a_map_file_of_more_than_2_26_cells_is_refused_from_its_header(tmp_path: Path) -> None:
    path = tmp_path / "big.map"
    path.write_text("type octile\nheight 8193\nwidth 8192\nmap\n..@\n")
    with pytest.raises(
        ValueError, match=r"8193 x 8192 cells, more than 2\*\*26 = 67108864 \(256 MiB of <U1"
    ):
        read_movingai_map(path)


def test_a_terrain_of_more_than_2_26_cells_is_refused_before_it_is_copied() -> None:
    # A broadcast view: 4 bytes, 67,117,056 cells.
    terrain = np.broadcast_to(np.array("."), (8193, 8192))
    with pytest.raises(
        ValueError, match=r"terrain must have at most 2\*\*26 = 67108864 cells .*got 67117056"
    ):
        MovingAIMap(terrain)


def test_scenarios_may_still_name_maps_the_planners_take(tmp_path: Path) -> None:
    path = tmp_path / "a.scen"
    path.write_text("version 1\n0\tbig.map\t65536\t32767\t0\t0\t1\t1\t1.41421356\n")
    scenarios = read_movingai_scenarios(path)
    assert len(scenarios) == 1


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs Linux's /proc")
def test_the_largest_map_is_read_and_costed_within_one_and_a_half_gib(tmp_path: Path) -> None:
    path = tmp_path / "largest.map"
    row = b"." * 8191 + b"@\n"
    with path.open("wb") as f:
        f.write(b"type octile\nheight 8192\nwidth 8192\nmap\n")
        for _ in range(8192):
            f.write(row)
    outcome = probe_outcome(
        """
import json, resource, sys
from navkit.mapping.io import MovingAIMap
MovingAIMap(["..@"]).costs
with open("/proc/self/status") as f:
    size = next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmSize"))
resource.setrlimit(resource.RLIMIT_AS, (size + (3 << 29), resource.RLIM_INFINITY))
from navkit.mapping.io import read_movingai_map
grid = read_movingai_map(sys.argv[1])
costs = grid.costs
print(json.dumps([*grid.shape, int((costs == float("inf")).sum())]))
""",
        str(path),
        timeout=600,
    )
    assert outcome == [8192, 8192, 8192]
