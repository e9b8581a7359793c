"""Review 34 (integrator lens): the order of a CARMEN log's ODOM records.

Looking the odometry up at each scan's time (``np.searchsorted`` on
``CarmenLog.odometry[:, 3]``) gave poses tens of metres off on Radish's logs:
the records are kept in file order, and those logs put an ODOM line stamped 0
after scans (repeating the scan's corrected pose), with intel's other times
stepping back as well. ``CarmenLog``'s docstring now gives these figures;
these tests hold it to them and check the recipe it gives.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import read_carmen

FIGURES = {"aces": (440, 0), "csail": (406, 0), "intel": (841, 696)}


@pytest.mark.parametrize("name", sorted(FIGURES))
def test_records_stamped_zero_and_steps_back(shared_data: Path, name: str) -> None:
    log = read_carmen(shared_data / "carmen-logs" / f"{name}-corrected.log.gz")
    odometry = log.odometry
    stamped_zero = odometry[:, 3] == 0.0
    rest = odometry[~stamped_zero, 3]
    assert (int(stamped_zero.sum()), int(np.sum(np.diff(rest) < 0))) == FIGURES[name]


def test_the_recipe_finds_the_corrected_poses_on_aces(shared_data: Path) -> None:
    log = read_carmen(shared_data / "carmen-logs" / "aces-corrected.log.gz")
    odometry = log.odometry
    laser = np.array([p.as_array() for p in log.laser_poses])
    # Each scan's ODOM line stamped 0 repeats its corrected pose exactly.
    assert np.array_equal(odometry[odometry[:, 3] == 0.0, :3], laser)
    # The naive look-up on the file order finds the wrong records ...
    naive = np.clip(np.searchsorted(odometry[:, 3], log.times), 0, len(odometry) - 1)
    naive_error = np.hypot(*(odometry[naive, :2] - laser[:, :2]).T)
    # ... the docstring's recipe (drop the zeros, sort) the nearest in time.
    kept = odometry[odometry[:, 3] != 0.0]
    kept = kept[np.argsort(kept[:, 3], kind="stable")]
    after = np.clip(np.searchsorted(kept[:, 3], log.times), 1, len(kept) - 1)
    later_is_nearer = np.abs(kept[after, 3] - log.times) < np.abs(kept[after - 1, 3] - log.times)
    nearer = np.where(later_is_nearer, after, after - 1)
    error = np.hypot(*(kept[nearer, :2] - laser[:, :2]).T)
    assert np.median(naive_error) > 5.0
    assert np.median(error) < 0.1
