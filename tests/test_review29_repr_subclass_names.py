"""Every public class's repr names the class of the object, a user subclass included.

Review 29: the filters' reprs hard-coded their class name (fixed with the filters),
and so did twelve more classes, so that a user's ``class MyMap(OccupancyGrid)``
printed as ``OccupancyGrid(...)``. The dataclasses and potential fields already
named ``type(self)``.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from navkit.estimation import CompassCalibration, DiffOdometry, OmniOdometry
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.mapping import OccupancyGrid, ScanMapper, ScanMatcher
from navkit.planning import AStarPlanner, FieldDStar, MapPlanner
from navkit.sim import World


def _grid() -> OccupancyGrid:
    return OccupancyGrid(np.zeros((4, 5)), resolution=0.5)


def _omni() -> OmniDrive:
    return OmniDrive(np.radians([30.0, 150.0, 270.0]), wheel_radius=0.03, base_radius=0.1)


def _diff() -> DiffDrive:
    return DiffDrive(track=0.3, wheel_radius=0.05)


MAKERS: dict[type, Callable[[type], object]] = {
    MapPlanner: lambda cls: cls(_grid()),
    AStarPlanner: lambda cls: cls(np.ones((4, 5))),
    FieldDStar: lambda cls: cls(np.ones((4, 5))),
    World: lambda cls: cls(),
    DiffDrive: lambda cls: cls(track=0.3, wheel_radius=0.05),
    OmniDrive: lambda cls: cls(
        np.radians([30.0, 150.0, 270.0]), wheel_radius=0.03, base_radius=0.1
    ),
    ScanMapper: lambda cls: cls(),
    ScanMatcher: lambda cls: cls(),
    OccupancyGrid: lambda cls: cls(np.zeros((4, 5)), resolution=0.5),
    OmniOdometry: lambda cls: cls(_omni()),
    DiffOdometry: lambda cls: cls(_diff(), ticks_per_rev=1024),
    CompassCalibration: lambda cls: cls(),
}


@pytest.mark.parametrize("base", list(MAKERS), ids=lambda c: c.__name__)
def test_a_subclass_repr_names_the_subclass(base: type) -> None:
    sub = type(f"My{base.__name__}", (base,), {"__module__": __name__})
    own, users = repr(MAKERS[base](base)), repr(MAKERS[base](sub))
    assert own.startswith(f"{base.__name__}(")
    # The same fields, under the subclass's name.
    assert users == f"My{base.__name__}" + own[len(base.__name__) :]
