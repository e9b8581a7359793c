"""Text options checked and kept as the plain ``str`` (a fresh-eyes review of review 33).

Review 33 checked ``Event.kind``, ``Metrics.reason``, ``Path2D.frame`` and
``MovingObstacle.after`` as the plain text stored. Six more options compared a
``str`` subclass with its own ``==`` and kept it as it was:
``MapPlanner(planner=)``, ``DiffOdometry(method=)``,
``PotentialFieldController(drive=)``, ``Demo(map=)``, ``DiffAStar(building=,
parts=)`` and ``IndoorNav(map_source=)``. An ``np.str_`` (an option read from a
NumPy array) printed as ``np.str_('astar')`` in their reprs and properties, and
a case-blind subclass's ``"ASTAR"`` was taken and kept, no name the library
documents.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from case_blind import CaseBlind
from navkit.control import PotentialFieldController
from navkit.estimation import DiffOdometry
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.planning import MapPlanner
from navkit.planning.reactive import ConicAttraction
from navkit.sim.scenarios import Demo, DiffAStar, IndoorNav


def _grid() -> OccupancyGrid:
    return OccupancyGrid.from_occupancy(np.zeros((10, 10), dtype=bool), resolution=0.1)


# (option, a valid value, build(value), the stored value read back)
_CASES: list[tuple[str, str, Callable[[Any], Any], Callable[[Any], Any]]] = [
    ("planner", "field_dstar",
     lambda v: MapPlanner(_grid(), robot_radius=0.1, planner=v), lambda o: o.planner),
    ("method", "midpoint",
     lambda v: DiffOdometry(DiffDrive(track=0.3, wheel_radius=0.05), ticks_per_rev=1000, method=v),
     lambda o: o._method),
    ("drive", "diff",
     lambda v: PotentialFieldController(ConicAttraction((1.0, 0.0)), drive=v), lambda o: o.drive),
    ("map", "office", lambda v: Demo(map=v), lambda o: o.map),
    ("building", "corridor", lambda v: DiffAStar(building=v), lambda o: o.building),
    ("parts", "house", lambda v: DiffAStar(parts=(v,)), lambda o: o.parts[0]),
    ("map_source", "plan", lambda v: IndoorNav(map_source=v), lambda o: o.map_source),
]  # fmt: skip


@pytest.mark.parametrize(("option", "value", "build", "stored"), _CASES)
def test_numpy_text_is_kept_as_plain_str(
    option: str, value: str, build: Callable[[Any], Any], stored: Callable[[Any], Any]
) -> None:
    made = build(np.str_(value))
    kept = stored(made)
    assert type(kept) is str and kept == value
    assert "np.str_" not in repr(made)
    assert repr(made) == repr(build(value))  # the object a plain str makes


@pytest.mark.parametrize(("option", "value", "build", "stored"), _CASES)
def test_a_case_blind_option_is_checked_as_the_text_stored(
    option: str, value: str, build: Callable[[Any], Any], stored: Callable[[Any], Any]
) -> None:
    with pytest.raises(ValueError, match=option):
        build(CaseBlind(value.upper()))
    kept = stored(build(CaseBlind(value)))
    assert type(kept) is str and kept == value
