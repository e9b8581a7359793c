"""PotentialFieldController pickles from when its options were plain attributes."""

from __future__ import annotations

import copy
import pickle
from typing import Any

import pytest

from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D

_OPTIONS = (
    "attraction", "drive", "goal_tolerance", "influence_radius", "k_rep", "max_accel",
    "max_decel", "max_omega", "max_speed", "stall_radius", "stall_timeout",
)  # fmt: skip


class _OldLayout:
    """Pickles as the controller did before its options became read-only properties.

    Python's default reduction of a slotted object, (None, slots), with the
    options under their public names (they were slots of those names).
    """

    def __init__(self, ctl: PotentialFieldController) -> None:
        self._ctl = ctl

    def __reduce__(self) -> tuple[Any, ...]:
        slots = {}
        for name in PotentialFieldController.__slots__:
            public = name.removeprefix("_")
            slots[public if public in _OPTIONS else name] = getattr(self._ctl, name)
        return object.__new__, (PotentialFieldController,), (None, slots)


def _steps(ctl: PotentialFieldController) -> list[tuple[float, float, float]]:
    out = []
    pose = Pose2D(0.0, 0.0, 0.0)
    for k in range(5):
        tw = ctl.step(pose, Pose2D(3.0, 1.0, 0.5), dt=0.05, obstacles=[[1.0, 0.6]])
        out.append((tw.vx, tw.vy, tw.omega))
        pose = Pose2D(pose.x + 0.05 * tw.vx, pose.y + 0.05 * tw.vy, 0.1 * k)
    return out


def test_an_old_pickle_loads_with_its_options() -> None:
    # Loading raised "AttributeError: property 'attraction' ... has no setter".
    ctl = PotentialFieldController(max_speed=0.7, k_rep=0.3, drive="diff", stall_timeout=4.0)
    _steps(ctl)  # some state: previous velocity, PID
    loaded = pickle.loads(pickle.dumps(_OldLayout(ctl)))
    for name in _OPTIONS[1:]:
        assert getattr(loaded, name) == getattr(ctl, name), name
    assert _steps(loaded) == _steps(ctl)
    with pytest.raises(AttributeError):
        loaded.max_speed = 2.0


class _Named(PotentialFieldController):
    """A subclass with an instance dict."""

    name: str


def test_copies_of_a_subclass_keep_its_attributes() -> None:
    ctl = _Named(max_speed=0.4)
    ctl.name = "keeper"
    for twin in (copy.copy(ctl), copy.deepcopy(ctl), pickle.loads(pickle.dumps(ctl))):
        assert type(twin) is _Named
        assert twin.name == "keeper"
        assert twin.max_speed == 0.4
