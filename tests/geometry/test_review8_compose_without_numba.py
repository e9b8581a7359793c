"""Composing poses never starts numba (docs/compilation.md: building poses costs no numba)."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit._shared.se2 import compose_scalar
from navkit.geometry import Pose2D


def test_compose_does_not_import_numba() -> None:
    code = (
        "import sys\n"
        "from navkit.geometry import Pose2D\n"
        "p = Pose2D(1.0, 2.0, 3.0)\n"
        "q = p.compose((1.0, 0.5, -2.0)) @ [0.0, 1.0, 0.5]\n"
        "print('numba' in sys.modules)\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout
    assert out.strip() == "False"


coordinate = st.floats(-1e6, 1e6)
angle = st.floats(-50.0, 50.0)


@settings(max_examples=50, deadline=None)
@given(coordinate, coordinate, angle, coordinate, coordinate, angle)
def test_compose_equals_the_kernels_compose(
    x: float, y: float, th: float, dx: float, dy: float, dth: float
) -> None:
    pose = Pose2D(x, y, th)
    other = Pose2D(dx, dy, dth)  # (dth wrapped, as compose reads it)
    got = pose.compose(other)
    assert (got.x, got.y, got.theta) == compose_scalar(
        pose.x, pose.y, pose.theta, other.x, other.y, other.theta
    )
    assert -math.pi < got.theta <= math.pi


test_compose_equals_the_kernels_compose_thoroughly = slow_twin(
    test_compose_equals_the_kernels_compose, max_examples=300
)


def test_compose_of_huge_poses_still_scales() -> None:
    got = Pose2D(1.5e308, 0.0, 0.0).compose((-1.0e308, 0.0, 0.0))
    assert np.isclose(got.x, 0.5e308)
