"""Fields, the controller, grids, Field D* and bags give NumPy's default answer whatever
the caller's ``np.seterr`` (review 31; the rest of the policy in
``tests/geometry/test_review31_errstate_quaternions.py`` and its siblings).

A squared offset of 1e-200 m, a tiny sine times a tiny offset, a log-odds of
1e-200 cast to float32: each underflows to 0 under NumPy's defaults, and
raised ``FloatingPointError`` after ``np.seterr(all="raise")`` or
``under="raise"`` (a NaN hunt).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from errstate_checks import assert_default_answer
from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import BagImu
from navkit.planning import (
    BlendedAttraction,
    ConicAttraction,
    FieldDStar,
    ParaboloidAttraction,
    PiecewiseAttraction,
    sample_field,
)

TINY = 1e-200
HERE = np.array([[0.0, 0.0]])


def _imu() -> BagImu:
    cov = np.diag([1.0, 2.0, 3.0])[None]
    return BagImu("/imu", "imu_link", [0.0], [0.0], [[0, 0, 0, 1.0]], [[0, 0, 0.1]],
                  [[0, 0, 9.8]], cov, cov, cov)  # fmt: skip


_CASES: dict[str, Callable[[], Any]] = {
    "ParaboloidAttraction.potential": lambda: ParaboloidAttraction((TINY, TINY)).potential(HERE),
    "BlendedAttraction.potential": lambda: BlendedAttraction((TINY, TINY)).potential(HERE),
    "BlendedAttraction.force": lambda: BlendedAttraction((TINY, TINY)).force(HERE),
    "PiecewiseAttraction.potential": lambda: PiecewiseAttraction((TINY, TINY)).potential(HERE),
    "sum of fields.force": lambda: (
        BlendedAttraction((TINY, TINY)) + ConicAttraction((1.0, 0.0))
    ).force(HERE),
    "sample_field": lambda: (
        sample_field(
            BlendedAttraction((TINY, TINY)), xlim=(-0.25, 0.25), ylim=(-0.25, 0.25), resolution=0.5
        ).force
    ),
    "PotentialFieldController.step": lambda: (
        PotentialFieldController(attraction=BlendedAttraction((0.0, 0.0)))
        .step(Pose2D(0.0, 0.0, 0.0), (TINY, TINY, 0.0), 0.1)
        .as_array()
    ),
    "OccupancyGrid(logodds 1e-200)": lambda: OccupancyGrid(
        np.full((2, 2), TINY), resolution=0.1
    ).probability(),
    "FieldDStar.world_to_node": lambda: FieldDStar(
        np.ones((3, 3)), resolution=0.1, origin=(TINY, TINY, TINY)
    ).world_to_node([0.0, 0.0], continuous=True),
    "BagImu.to_base": lambda: _imu().to_base(mount=[0.0, 0.0, 1e200, 1.0]).orientation_covariances,
}


@pytest.mark.parametrize("name", sorted(_CASES))
@pytest.mark.parametrize("mode", ["all", "under"])
def test_the_default_answer_whatever_numpys_error_state(name: str, mode: str) -> None:
    assert_default_answer(_CASES[name], mode)
