"""PlanarFusion's x0 holding a Pose2D gets no advice for points (review 53, FRESH3).

2e87d60 took ``x0`` through ``as_float_array`` without its shape first (to name
a start pose given as ``x0``), and that call, knowing no component count, gave a
list holding a Pose2D the advice for an ``(x, y)`` argument: "pass (p.x, p.y) of
that Pose2D p", which x0 (six numbers) then refuses again.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import PlanarFusion
from navkit.geometry import Pose2D


@pytest.mark.parametrize(
    "x0",
    [[Pose2D(1.0, 2.0, 0.5)], [Pose2D(1.0, 2.0, 0.5), 0.0, 0.0, 0.0, 0.0, 0.0]],
    ids=["alone", "first-of-six"],
)
def test_an_x0_holding_a_pose_is_refused_without_the_points_advice(x0: list[object]) -> None:
    for call in (lambda: PlanarFusion(x0=x0), lambda: PlanarFusion().reset(x0=x0)):
        with pytest.raises(TypeError, match="x0 must hold real numbers") as caught:
            call()
        assert "(p.x, p.y)" not in str(caught.value)


def test_the_advice_for_a_start_pose_still_works_when_followed() -> None:
    pose = Pose2D(1.0, 2.0, 0.5)
    with pytest.raises(TypeError, match="a start pose goes in as pose="):
        PlanarFusion(x0=pose)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="a start pose goes in as pose="):
        PlanarFusion(x0=(1.0, 2.0, 0.5))
    fusion = PlanarFusion(pose=pose)
    np.testing.assert_array_equal(fusion.x, [1.0, 2.0, 0.5, 0.0, 0.0, 0.0])
