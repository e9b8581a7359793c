"""Public calls work with numba's JIT disabled (kernels run as Python), as compiled."""

from __future__ import annotations

import sys

import pytest

from subprocess_probe import jit_outcome

_CALLS = r"""
import json
import numpy as np
import navkit.estimation as E
import navkit.mapping as M
import navkit.planning as P

grid = np.ones((6, 7))
grid[2, 1:5] = np.inf
scan = M.LaserScan(np.array([0.5, 1.0, 0.3]), angle_min=0.0, angle_increment=0.5,
                   range_min=0.1, range_max=3.0)
ekf = E.ExtendedKalmanFilter(np.zeros(2), np.eye(2), angle_states=(1,))
ekf.predict(lambda x: x + 0.5, np.eye(2), 0.1 * np.eye(2))
result = ekf.update(np.array([4.0]), lambda x: x[:1], np.array([[1.0, 0.0]]), np.eye(1))
fusion = E.PlanarFusion(t0=0.0)
fusion.update_odometry(0.1, 1.0, 0.2, v_variance=0.01, omega_variance=0.01)
out = {
    "jps": P.astar(grid, (0, 0), (5, 6), method="jps").cost,
    "auto": P.astar(grid, (5, 0), (0, 6), method="auto").cost,
    "astar": P.astar(grid, (0, 0), (5, 6)).cost,
    "ekf": ekf.x.tolist() + [result.nis],
    "fusion": list(fusion.x),
    "khatib": P.repulsive_force_from_scan(scan).tolist(),
    "cells": M.OccupancyGrid(np.zeros((3, 3)), resolution=1.0)
    .world_to_cell(np.array([[0.5, 1.5], [2.5, 0.2]])).tolist(),
}
print(json.dumps(out))
"""


def _run(disable_jit: bool) -> dict[str, object]:
    result: dict[str, object] = jit_outcome(
        _CALLS, disable_jit=disable_jit, warnings_as_errors=False, timeout=300
    )
    return result


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX subprocess environment")
def test_public_calls_run_with_the_jit_disabled() -> None:
    # JPS called numba intrinsics (not callable from Python) and subtracted numpy
    # booleans; the EKF and the small-call fast paths asked the dispatcher to
    # compile or freeze, which a plain function cannot.
    interpreted = _run(disable_jit=True)
    compiled = _run(disable_jit=False)
    assert interpreted.keys() == compiled.keys()
    assert interpreted.pop("cells") == compiled.pop("cells")
    for name, value in compiled.items():
        assert interpreted[name] == pytest.approx(value, rel=1e-12, abs=1e-12), name
