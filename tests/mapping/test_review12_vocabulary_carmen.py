"""One vocabulary for arrays of times: ``CarmenLog.times`` (was ``timestamps``).

Every other reader and record of navkit names its array of times ``times``
(``BagScans``, ``BagOdometry``, ``BagImu``, ``MeasurementLog``, ``FusionResult``,
``sim.Trace``); ``CarmenLog`` said ``timestamps``. The old keyword and property
still work for a release, with a DeprecationWarning; positional construction,
copies and pickles (also those made before the rename) are unchanged.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import pickle
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit._shared.frozen import rebuild_record
from navkit.geometry import Pose2D
from navkit.mapping import LaserScan
from navkit.mapping.io import BagOdometry, BagScans, CarmenLog, read_carmen

SCAN = LaserScan([1.0, 2.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=5.0)
POSES = (Pose2D(0.5, 0.0, 0.0),)
ODOM = np.array([[0.5, 0.0, 0.0, 12.7]])


def _log_file(tmp_path: Path) -> Path:
    path = tmp_path / "log.txt"
    path.write_text(
        "FLASER 2 1.0 2.0 0.5 0 0 0.5 0 0 12.5 host 12.6\n"
        "ODOM 0.5 0 0 0 0 0 12.7 host 12.7\n"
        "FLASER 2 1.5 2.5 0.6 0 0 0.6 0 0 12.75 host 12.8\n"
    )
    return path


def test_read_carmen_gives_times_as_the_bag_readers_do(tmp_path: Path) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        log = read_carmen(_log_file(tmp_path))
        assert log.times.tolist() == [12.5, 12.75]
        assert not log.times.flags.writeable
        assert "times=array([12.5 , 12.75])" in repr(log)
        made = CarmenLog((SCAN,), POSES, POSES, times=[3.0], odometry=ODOM)
        assert made.times.tolist() == [3.0]
    # The same word as the other records that hold an array of times.
    for record in (CarmenLog, BagScans, BagOdometry):
        assert "times" in {f.name for f in dataclasses.fields(record)}
    assert "timestamps" not in {f.name for f in dataclasses.fields(CarmenLog)}


def test_old_keyword_and_property_warn_and_give_the_same_times(tmp_path: Path) -> None:
    new = CarmenLog((SCAN,), POSES, POSES, [3.0], ODOM)
    with pytest.warns(DeprecationWarning, match="timestamps is deprecated.*use times") as rec:
        old = CarmenLog((SCAN,), POSES, POSES, timestamps=[3.0], odometry=ODOM)
    assert rec[0].filename == __file__
    np.testing.assert_array_equal(old.times, new.times)
    assert not old.times.flags.writeable
    log = read_carmen(_log_file(tmp_path))
    with pytest.warns(DeprecationWarning, match=r"CarmenLog\.timestamps is deprecated") as rec:
        stamps = log.timestamps
    assert rec[0].filename == __file__
    assert stamps is log.times


def test_both_names_missing_times_and_errors_naming_times() -> None:
    with pytest.raises(TypeError, match="both times and its old name timestamps"):
        CarmenLog((SCAN,), POSES, POSES, [3.0], ODOM, timestamps=[3.0])
    with pytest.raises(TypeError, match="missing the argument times"):
        CarmenLog((SCAN,), POSES, POSES, odometry=ODOM)
    with pytest.raises(TypeError, match="missing the argument odometry"):
        CarmenLog((SCAN,), POSES, POSES, [3.0])
    with pytest.raises(ValueError, match="times must contain only finite values"):
        CarmenLog((SCAN,), POSES, POSES, [math.nan], ODOM)
    with pytest.raises(ValueError, match="robot_poses and times must have the same length"):
        CarmenLog((SCAN,), POSES, POSES, [1.0, 2.0], ODOM)


def test_copies_replace_and_pickles_keep_times() -> None:
    log = CarmenLog((SCAN,), POSES, POSES, [3.0], ODOM)
    for other in (copy.copy(log), copy.deepcopy(log), pickle.loads(pickle.dumps(log))):
        assert other.times.tolist() == [3.0] and not other.times.flags.writeable
    assert dataclasses.replace(log, times=[4.0]).times.tolist() == [4.0]


class _OldPickle:
    """Pickles as a CarmenLog of the release before the rename did (``reduce_record``)."""

    def __reduce__(self) -> tuple[Any, ...]:
        values = {
            "scans": (SCAN,),
            "laser_poses": POSES,
            "robot_poses": POSES,
            "timestamps": np.array([3.0]),
            "odometry": ODOM.copy(),
        }
        return rebuild_record, (CarmenLog, values, ("timestamps", "odometry"), None, {})


def test_a_pickle_from_before_the_rename_loads_into_times() -> None:
    log = pickle.loads(pickle.dumps(_OldPickle()))
    assert type(log) is CarmenLog
    assert log.times.tolist() == [3.0] and not log.times.flags.writeable
    assert not log.odometry.flags.writeable
    # The oldest pickles: the field values as a list, in field order.
    older = object.__new__(CarmenLog)
    older.__setstate__([(SCAN,), POSES, POSES, np.array([3.0]), ODOM.copy()])
    assert older.times.tolist() == [3.0] and not older.times.flags.writeable
