"""Fuzz specs of navkit.control's path trackers (see ``fuzz_specs.py`` for how specs work).

Imported at the end of ``fuzz_specs.py``, which registers them.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from fuzz_engine import Anything, Array, Call, Choice, PoseLike, Real, call, method, spec

from navkit.control import FollowTheCarrot, OnOffTracker, RegulatedPurePursuit
from navkit.mapping import OccupancyGrid

A = np.array

PATH = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]
POSE = [0.1, 0.05, 0.2]

_OCCUPIED = np.zeros((8, 10), dtype=bool)
_OCCUPIED[2:6, 5] = True


def _grid() -> Call:
    return call(
        OccupancyGrid.from_occupancy, _OCCUPIED.copy(), resolution=0.1, origin=(-0.2, -0.1, 0.0)
    )


def _with_path(tracker: Any) -> None:
    tracker.set_path(A(PATH), goal_yaw=0.5)


for _cls in (FollowTheCarrot, OnOffTracker, RegulatedPurePursuit):
    _name = f"navkit.control.{_cls.__name__}"
    _ctor_kinds: dict[str, Any] = {"drive": Choice("diff", "omni")}
    if _cls is RegulatedPurePursuit:
        _ctor_kinds["clearance"] = Anything(optional=True)
        spec(
            _name,
            lambda c, C=_cls: call(C, drive="omni", clearance=_grid()),
            kinds=_ctor_kinds,
        )
    else:
        spec(_name, lambda c, C=_cls: call(C, drive="omni"), kinds=_ctor_kinds)
    spec(
        f"{_name}.set_path",
        lambda c, C=_cls: method(call(C), "set_path", A(PATH), goal_yaw=0.5),
        kinds={"path": Array()},
        mutates=("self",),
    )
    _step_kinds: dict[str, Any] = {"dt": Real()}
    if _cls is RegulatedPurePursuit:
        _step_kinds["velocity"] = PoseLike("Twist2D", optional=True)
        spec(
            f"{_name}.step",
            lambda c, C=_cls: method(
                call(C, clearance=_grid()),
                "step",
                A(POSE),
                0.05,
                velocity=A([0.2, 0.0, 0.1]),
                prepare=_with_path,
            ),
            kinds=_step_kinds,
            mutates=("self",),
        )
    else:
        spec(
            f"{_name}.step",
            lambda c, C=_cls: method(call(C), "step", A(POSE), 0.05, prepare=_with_path),
            kinds=_step_kinds,
            mutates=("self",),
        )
