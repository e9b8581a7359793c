"""Weak references to navkit's long-lived objects (review 36).

Users keep weak references to planners, grids, filters and controllers:
``weakref.finalize`` callbacks, ``WeakValueDictionary`` caches, a ROS node's
callbacks that must not keep an object alive. Every public class with
``__slots__`` refused them ("cannot create weak reference to 'OccupancyGrid'
object"). Decided per class: the stateful, long-lived objects take weak
references (a ``__weakref__`` slot: one pointer each, pickles unchanged byte for
byte); the small frozen records (``Pose2D``, ``Twist2D``, readings, results,
``Path2D``, ``LaserScan``, ...) stay without, as values compared and hashed by
value (a user's subclass of one, without ``__slots__``, takes weak references).
"""

from __future__ import annotations

import copy
import gc
import pickle
import weakref
from typing import Any

import pytest

from navkit.geometry import Pose2D
from test_review21_pickle_public_classes import _INSTANCES

#: The long-lived objects that take weak references.
WEAK = [
    "DiffDrive",
    "OmniDrive",
    "OccupancyGrid",
    "ScanMapper",
    "ScanMatcher",
    "DiffOdometry",
    "ExtendedKalmanFilter",
    "OmniOdometry",
    "PlanarFusion",
    "MapPlanner",
    "MapPlanner(field_dstar)",
    "FollowTheCarrot",
    "OnOffTracker",
    "RegulatedPurePursuit",
    "PotentialFieldController",
    "TrackerController",
    "World",
    "FieldDStar",
    "Simulation",
    "CompassCalibration",
    "AStarPlanner",
    "AStarPlanner(jps)",
]



@pytest.mark.parametrize("name", WEAK)
def test_long_lived_objects_take_weak_references(name: str) -> None:
    obj = _INSTANCES[name]()
    ref = weakref.ref(obj)
    assert ref() is obj
    cache: weakref.WeakValueDictionary[str, Any] = weakref.WeakValueDictionary()
    cache["key"] = obj
    fired: list[str] = []
    weakref.finalize(obj, fired.append, "gone")
    # A live weak reference changes no copy or pickle.
    assert type(copy.deepcopy(obj)) is type(obj)
    assert type(pickle.loads(pickle.dumps(obj))) is type(obj)
    del obj
    gc.collect()
    assert ref() is None
    assert "key" not in cache
    assert fired == ["gone"]


def test_the_lists_are_public_classes() -> None:
    assert set(WEAK) <= set(_INSTANCES)


def test_a_subclass_of_a_record_takes_weak_references() -> None:
    with pytest.raises(TypeError, match="cannot create weak reference"):
        weakref.ref(Pose2D(0.0, 0.0))  # a value: deliberately without

    class Waypoint(Pose2D):
        pass

    point = Waypoint(1.0, 2.0)
    assert weakref.ref(point)() is point
