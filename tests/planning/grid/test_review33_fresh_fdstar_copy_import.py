"""Review 33 (FRESH): an unpickled ``FieldDStar`` told its obstacles imports scipy.ndimage.

Review 32 imported ``scipy.ndimage`` when such a planner is built (only it
escapes the inflation, ``start_tolerance``), so that the first escape in a
control loop does not pay the import (0.05-0.5 s). A planner unpickled in a
fresh process (a worker of a sweep, a planner saved with its scenario) is built
by ``__setstate__``, not ``__init__``: it paid the import at its first escape
again. Checked: against ``_field_dstar.py`` of HEAD the first test reads False.
"""

from __future__ import annotations

import pickle

import numpy as np

from navkit.planning import FieldDStar
from subprocess_probe import probe_outcome

_LOAD = """
import json, pickle, sys
planner = pickle.loads(bytes.fromhex(sys.argv[1]))
print(json.dumps([type(planner).__name__, "scipy.ndimage" in sys.modules]))
"""


def _planner(with_obstacles: bool) -> FieldDStar:
    costs = np.ones((6, 6))
    costs[2:4, 2:4] = np.inf
    obstacles = np.zeros((6, 6), dtype=bool)
    obstacles[2, 2] = True
    return FieldDStar(costs, obstacles=obstacles if with_obstacles else None)


def test_an_unpickled_planner_with_obstacles_imports_ndimage_when_loaded() -> None:
    data = pickle.dumps(_planner(True)).hex()
    assert probe_outcome(_LOAD, data, timeout=120) == ["FieldDStar", True]


def test_an_unpickled_planner_without_obstacles_does_not() -> None:
    data = pickle.dumps(_planner(False)).hex()
    assert probe_outcome(_LOAD, data, timeout=120) == ["FieldDStar", False]
