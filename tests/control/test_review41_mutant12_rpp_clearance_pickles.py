"""A regulated pure pursuit with a clearance map pickles under every protocol (MUTANT12).

Mutation review 41: deleting ``_GridClearance.__getstate__`` (the slots state)
survived, as no test pickled a tracker that holds a grid under protocol 0 or 1,
which refuse a slotted class without its own ``__getstate__``. The twin must
also regulate its speed by the same map: it slows by the same amount near the wall.
"""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from navkit.control import RegulatedPurePursuit
from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid


def _walled_tracker() -> RegulatedPurePursuit:
    # A wall one row of cells along y = 0.45 m, the path along y = 0 from x = 0 to 3 m.
    occupancy = np.zeros((20, 40), dtype=bool)
    occupancy[14, :] = True
    grid = OccupancyGrid.from_occupancy(occupancy, resolution=0.1, origin=(-0.5, -1.0, 0.0))
    tracker = RegulatedPurePursuit(clearance=grid, clearance_distance=0.6, clearance_gain=1.0)
    tracker.set_path([[0.0, 0.0], [3.0, 0.0]])
    return tracker


@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
def test_a_tracker_with_a_clearance_map_pickles_and_regulates_the_same(protocol: int) -> None:
    tracker = _walled_tracker()
    twin = pickle.loads(pickle.dumps(tracker, protocol=protocol))
    pose = Pose2D(0.2, 0.0, 0.0)
    free = RegulatedPurePursuit(clearance_distance=0.6, clearance_gain=1.0)
    free.set_path([[0.0, 0.0], [3.0, 0.0]])
    commands = [t.step(pose, 0.05) for t in (tracker, twin, free)]
    assert commands[0] == commands[1]
    # The map is used: the wall 0.45 m away slows the robot below the free one's speed.
    assert 0.0 < commands[0].vx < commands[2].vx
