"""The scan matcher's map lookups are typed once per first use, not once per call site.

``accumulate`` reads the map through ``_interpolate``, which reads four cells
through ``_probability`` (and, in the map's outer half cell, four through
``_edge_probability``). As numba IR-level inlined helpers (``inline="always"``)
their bodies were copied, typed and lowered again at each of those sites:
``accumulate`` took 0.65-0.68 s of a first ``ScanMatcher.match`` (1.41-1.52 s of
compilation in all). Compiled once each and inlined by LLVM instead
(``njit_force_inline``) it takes 0.16 s (1.03-1.06 s in all), with the same
results bit for bit and the same speed (review 49, issue 17). Checked here in a
fresh process with an empty cache: each helper is compiled as a function of its
own, for one signature.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from kernel_signatures import compiled_signatures

_MATCH = """
import math
import numpy as np
from navkit.mapping import LaserScan, OccupancyGrid, ScanMatcher, integrate_scan

angles = np.linspace(-math.pi, math.pi, 90, endpoint=False)
with np.errstate(divide="ignore"):
    ranges = np.minimum(3.0 / np.abs(np.cos(angles)), 2.0 / np.abs(np.sin(angles)))
scan = LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / 90,
                 range_min=0.1, range_max=10.0)
room = OccupancyGrid.empty(width=8.0, height=6.0, resolution=0.1, origin=(-4.0, -3.0, 0.0))
integrate_scan(room, scan, (0.0, 0.0, 0.0), hit=2.2, miss=-0.4)
ScanMatcher().match(room, scan, (0.05, -0.05, 0.02))
ScanMatcher(search_distance=0.1, search_angle=0.05, translation_weight=1.0,
            rotation_weight=1.0).match(room, scan, (0.05, -0.05, 0.02))
"""


def test_map_lookups_compiled_once_each(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # An empty cache of its own: loaded kernels would not compile their helpers.
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    monkeypatch.delenv("NUMBA_DISABLE_JIT", raising=False)
    found = compiled_signatures(_MATCH, ["navkit.mapping._scan_matcher_kernels"])
    for helper in ("_probability", "_edge_probability", "_interpolate"):
        signatures = found.get(f"_scan_matcher_kernels.{helper}", [])
        assert len(signatures) == 1, (helper, signatures)
        assert "float32" in signatures[0]  # the map's log-odds, as accumulate passes it
    # Every kernel of the module compiled for one signature.
    assert {k: len(v) for k, v in found.items() if len(v) != 1} == {}
    assert {"accumulate", "match_level", "correlative_search_kernel"} <= {
        k.split(".")[1] for k in found
    }
