"""Jump point search's scratch after a MemoryError (review 20, scale lens).

``_jps_workspace`` grew its records and then its block bits. A MemoryError from
the second allocation left large records beside the old, smaller blocks; the
next search of a grid no larger than the records reused them and the kernels,
which do not check bounds, read and wrote past the blocks' end (a probe with
RLIMIT_AS showed records of 18e6 entries with blocks of size 0, and the
following searches writing into memory they did not own).
"""

from __future__ import annotations

import sys

import numpy as np
import pytest

from subprocess_probe import probe_outcome

_SIMULATED = r"""
import json
import numpy as np
from navkit.planning import AStarPlanner
from navkit.planning.grid import _astar


class ZerosFail:
    # numpy as _astar sees it, but np.zeros (the block bits) raises MemoryError.
    def __getattr__(self, name):
        return getattr(np, name)

    @staticmethod
    def zeros(*args, **kwargs):
        raise MemoryError("simulated: no memory for the block bits")


rng = np.random.default_rng(3)
small = np.ones((40, 40))
big = np.ones((300, 300))
big[rng.random(big.shape) < 0.2] = np.inf
big[0, 0] = big[-1, -1] = 1.0
small_jps = AStarPlanner(small, method="jps")
big_jps = AStarPlanner(big, method="jps")
expected = [AStarPlanner(small).plan((0, 0), (39, 39)).cost,
            AStarPlanner(big).plan((0, 0), (299, 299)).cost]
small_jps.plan((0, 0), (39, 39))  # the scratch sized for the small grid
_astar.np = ZerosFail()
try:
    big_jps.plan((0, 0), (299, 299))
    outcome = "planned"
except MemoryError as exc:
    outcome = str(exc)
_astar.np = np
s = _astar._jps_scratch
consistent = s.blocks.size >= 3 * ((s.records.size // 2 + 63) // 64)
costs = [small_jps.plan((0, 0), (39, 39)).cost, big_jps.plan((0, 0), (299, 299)).cost]
print(json.dumps([outcome, bool(consistent), costs, expected]))
"""


def test_a_failed_growth_leaves_the_scratch_consistent() -> None:
    # In a child process: at HEAD the searches after the failure wrote past the
    # blocks' end and the process died in free() ("invalid next size").
    outcome, consistent, costs, expected = probe_outcome(_SIMULATED, timeout=120)
    # The message says what the memory was for and how much.
    assert outcome.startswith("a grid search over 90000 cells needs 1.405 MiB of scratch")
    assert consistent
    assert costs == pytest.approx(expected, rel=1e-12)


_PROBE = r"""
import json, resource
import numpy as np
from navkit.planning import AStarPlanner
from navkit.planning.grid import _astar

def vm():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmSize"):
                return int(line.split()[1]) * 1024

n = 1500
big = AStarPlanner(np.ones((n, n)), method="jps")
small = AStarPlanner(np.ones((30, 30)), method="jps")
# Room for the records (16 bytes a cell) but not for the block bits after them.
resource.setrlimit(resource.RLIMIT_AS, (vm() + 16 * n * n + (1 << 18), resource.RLIM_INFINITY))
try:
    big.plan((0, 0), (n - 1, n - 1))
    outcome = "planned"
except MemoryError as exc:
    outcome = "MemoryError" if "scratch" in str(exc) else str(exc)
resource.setrlimit(resource.RLIMIT_AS, (resource.RLIM_INFINITY, resource.RLIM_INFINITY))
s = _astar._jps_scratch
consistent = s.blocks.size >= 3 * ((s.records.size // 2 + 63) // 64)
costs = [small.plan((0, 0), (29, 29)).cost, big.plan((0, 0), (n - 1, n - 1)).cost]
print(json.dumps([outcome, bool(consistent), costs]))
"""


@pytest.mark.skipif(sys.platform != "linux", reason="RLIMIT_AS limits allocations on Linux")
def test_an_address_space_limit_during_growth_leaves_the_scratch_consistent() -> None:
    # The real failure: RLIMIT_AS lets the records through and refuses the blocks.
    outcome, consistent, costs = probe_outcome(_PROBE, timeout=120)
    if outcome != "MemoryError":
        pytest.skip("the address-space limit did not fall between the two allocations")
    assert consistent
    assert costs == pytest.approx([29 * np.sqrt(2.0), 1499 * np.sqrt(2.0)], rel=1e-12)
