"""Python's data model across every public class (review 32, OBJECTS).

For one instance of each public class (``test_review21_pickle_public_classes``'s,
which fails when a class is added to an ``__all__`` without one), this pins
what users meet in notebooks, dicts, sets, sorted lists and assertion messages:

* ``==`` against a foreign object is False and never raises; ``<`` is refused
  with ``TypeError`` (the ``FusionStatus`` codes, an ``IntEnum``, excepted);
* a hashable object hashes like its deep copy whenever they compare equal;
* ``repr`` names the class, is never Python's default ``<... object at 0x...>``
  and never shows a NumPy 2 scalar (``np.float64(1.0)``); ``format(x, "")``
  is ``str(x)``;
* every object is true, except the collections below, false when empty: a
  ``ScanMapper`` (which counts its scans with ``len``) read as false until its
  first scan;
* a frozen record holds only read-only arrays, and ``dataclasses.replace``
  (which ``copy.replace`` calls on Python 3.13) rebuilds it through its checks;
* big maps, scans and planners print in a line (NumPy summarises the arrays).
"""

from __future__ import annotations

import copy
import dataclasses
import enum
import math
import re
from typing import Any

import numpy as np
import pytest

import test_review21_pickle_public_classes as review21
from navkit.errors import NavkitError
from navkit.mapping import LaserScan, LocalGrid, OccupancyGrid
from navkit.planning import AStarPlanner

# Collections of samples, rows or beams: false when they hold none (as lists).
COLLECTIONS = {
    "BagImu", "BagOdometry", "BagScans", "CarmenLog", "LaserScan", "MeasurementLog",
    "MovingAIScenarios", "Trace",
}  # fmt: skip

_NUMPY_REPR = re.compile(r"\bnp\.\w+\(")
_NAMES = [name for name in review21._INSTANCES if name not in ("NavkitError", "KernelCacheWarning")]
_RECORDS = [
    name for name, cls in review21._public_classes().items()
    if dataclasses.is_dataclass(cls) and name in _NAMES
]  # fmt: skip


class _Foreign:
    """An object of no navkit type."""


def _instance(name: str) -> Any:
    return review21._INSTANCES[name]()


@pytest.mark.parametrize("name", _NAMES)
def test_equality_ordering_and_hashing(name: str) -> None:
    obj = _instance(name)
    assert (obj == _Foreign()) is False and (obj != _Foreign()) is True
    assert obj == obj
    if isinstance(obj, enum.IntEnum):
        return  # codes are integers: ordered as integers
    with pytest.raises(TypeError):
        _ = obj < obj
    if type(obj).__hash__ is not None:
        twin = copy.deepcopy(obj)
        if obj == twin:
            assert hash(obj) == hash(twin)


@pytest.mark.parametrize("name", _NAMES)
def test_repr_str_and_format(name: str) -> None:
    obj = _instance(name)
    text = repr(obj)
    assert "object at 0x" not in text, text[:200]
    assert not _NUMPY_REPR.search(text), text[:400]
    if not isinstance(obj, (enum.Enum, BaseException)):
        assert text.startswith(f"{type(obj).__name__}("), text[:200]
    assert format(obj, "") == str(obj)


@pytest.mark.parametrize("name", _NAMES)
def test_truth(name: str) -> None:
    obj = _instance(name)
    if isinstance(obj, NavkitError):
        return
    cls = type(obj)
    if cls.__name__ in COLLECTIONS:
        assert hasattr(cls, "__len__") and bool(obj) is (len(obj) > 0)
    elif name != "UpdateResult":  # true when the measurement was applied, as documented
        assert bool(obj) is True, f"{cls.__name__} is false"


def test_the_collections_are_the_classes_with_a_length() -> None:
    # A class that gains __len__ is false when it holds nothing: it belongs above,
    # or needs __bool__ (as ScanMapper has).
    classes = review21._public_classes().values()
    with_length = {
        c.__name__ for c in classes if hasattr(c, "__len__") and not hasattr(c, "__bool__")
    }
    assert with_length == COLLECTIONS


def _arrays(value: Any) -> list[Any]:
    if isinstance(value, np.ndarray):
        return [value]
    if isinstance(value, tuple):
        return [a for item in value for a in _arrays(item)]
    return []


@pytest.mark.parametrize("name", _RECORDS)
def test_records_hold_read_only_arrays_and_replace_rebuilds(name: str) -> None:
    obj = _instance(name)
    for field in dataclasses.fields(obj):
        for array in _arrays(getattr(obj, field.name)):
            assert not array.flags.writeable, f"{name}.{field.name} is writeable"
    twin = dataclasses.replace(obj)
    assert type(twin) is type(obj)
    assert repr(twin) == repr(obj)


def test_big_objects_print_short() -> None:
    big = {
        "a 4096 x 4096 map": OccupancyGrid(np.zeros((4096, 4096), np.float32), resolution=0.05),
        "a 4001 x 4001 local grid": LocalGrid.from_points(
            [[0.5, -0.2]], half_width=20.0, resolution=0.01
        ),
        "a scan of 100000 beams": LaserScan(
            np.ones(100_000), angle_min=-math.pi, angle_increment=2 * math.pi / 100_000,
            range_min=0.1, range_max=10.0,
        ),
        "a planner on 2048 x 2048 costs": AStarPlanner(np.ones((2048, 2048))),
    }  # fmt: skip
    for what, obj in big.items():
        assert len(repr(obj)) < 1000, what
