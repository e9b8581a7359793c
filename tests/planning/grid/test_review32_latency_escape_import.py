"""A ``FieldDStar`` told its obstacles imports scipy.ndimage when built (review 32, latency).

Only such a planner escapes the inflation (``start_tolerance``), and the escape
imported ``scipy.ndimage`` on first use: the first ``replan_world`` after the
robot drifted into the inflation took 0.17-0.22 s instead of under 1 ms, in the
control loop (costs built by ``OccupancyGrid.traversal_costs`` had imported it
already; hand-made costs had not). It is now imported at construction.
"""

from __future__ import annotations

import subprocess
import sys

_SETUP = (
    "import sys\n"
    "import numpy as np\n"
    "from navkit.planning import FieldDStar\n"
    "costs = np.ones((6, 6))\n"
    "costs[2:4, 2:4] = np.inf\n"
    "obstacles = np.zeros((6, 6), dtype=bool)\n"
    "obstacles[2, 2] = True\n"
)


def _ndimage_loaded_after(code: str) -> str:
    out = subprocess.run(
        [sys.executable, "-c", _SETUP + code + "\nprint('scipy.ndimage' in sys.modules)"],
        capture_output=True,
        text=True,
        check=True,
        timeout=120,
    )
    return out.stdout.strip().splitlines()[-1]


def test_a_planner_without_obstacles_does_not_import_ndimage() -> None:
    # It never escapes (start_tolerance refuses), so it does not pay the import.
    assert _ndimage_loaded_after("FieldDStar(costs)") == "False"


def test_a_planner_with_obstacles_imports_ndimage_when_built() -> None:
    assert _ndimage_loaded_after("FieldDStar(costs, obstacles=obstacles)") == "True"


def test_a_ring_marked_later_imports_ndimage_then() -> None:
    # update_costs(obstacles=False) gives a planner built without obstacles its
    # escapes: the import comes with it.
    code = "FieldDStar(costs).update_costs([[0, 5]], [np.inf], obstacles=False)"
    assert _ndimage_loaded_after(code) == "True"
