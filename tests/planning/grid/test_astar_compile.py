"""The grid searches compile each kernel once: one type signature per numba dispatcher.

A kernel compiled for two argument type sets (a literal ``0`` next to an
``int64``, an ``int32`` slot next to an ``int64`` one, read-only next to
writable arrays) pays its compilation twice on first use (issue 17). These
tests call every public entry point of A*, JPS and the distance fields with
every option that selects another code path, in a fresh process, and check
that no kernel of theirs was specialised twice.
"""

from __future__ import annotations

from kernel_signatures import compiled_signatures

SCRIPT = """
import numpy as np
from navkit.planning import AStarPlanner, astar, distance_field
costs = np.ones((12, 12))
costs[2:9, 5] = np.inf
ro = costs.copy()
ro.flags.writeable = False
ints = np.ones((12, 12), dtype=np.int32)
astar(costs, (0, 0), (11, 11))
astar(ro, (0, 0), (11, 11), corner_cutting=True)
astar(ints, (0, 0), (11, 11), connectivity=4, heuristic_weight=1.5)
astar(costs, (0, 0), (11, 11), method="jps")
astar(ro, (0, 0), (11, 11), method="auto")
astar(costs, (0, 0), (11, 11), method="jps", corner_cutting=True)
astar(ro, (0, 0), (11, 11), method="auto", corner_cutting=True)
AStarPlanner(ints, method="jps", corner_cutting=True).plan((0, 0), (11, 11))
planner = AStarPlanner(costs + np.eye(12))
planner.plan((0, 0), (11, 11))
planner.distance_field((0, 0))
wide = costs.copy()
wide[0, 0] = 1e6
AStarPlanner(wide).distance_field((0, 0))  # the heap path
distance_field(costs, (0, 0))
distance_field(ro, (0, 0), corner_cutting=True, connectivity=4)
distance_field(costs + np.eye(12), (0, 0))
"""


def test_every_search_kernel_is_compiled_for_one_signature() -> None:
    signatures = compiled_signatures(SCRIPT, [f"navkit.planning.grid.{name}" for name in (
        "_astar_kernels", "_distance_field_kernels", "_jps_kernels", "_jps_cut_kernels",
        "_limits", "_search_heap"
    )])  # fmt: skip
    # The kernels the public layer calls (their callees are not loaded when cached).
    for kernel in (
        "_astar_kernels.grid_search",
        "_jps_kernels.jps_search",
        "_jps_cut_kernels.jps_cut_search",
        "_distance_field_kernels.bucket_field",
        "_jps_kernels._build_tables",
    ):
        assert kernel in signatures
    repeated = {name: sigs for name, sigs in signatures.items() if len(sigs) > 1}
    assert not repeated
