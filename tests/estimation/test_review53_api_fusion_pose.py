"""PlanarFusion(x0) given a start pose: the refusal points to pose=.

Review 52's PIPELINE user passed a Pose2D as PlanarFusion's first argument (the
six-state x0) and was told only "x0 must hold real numbers, got an element of
type Pose2D". The estimation package takes a start pose by the keyword pose=
(the odometry classes too), so that stays the one way, and the refusal says so.
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.estimation import PlanarFusion
from navkit.geometry import Pose2D

WAY_OUT = r"a start pose goes in as pose= \(x0 with zero rates\)"


def test_a_pose2d_as_x0_points_to_pose() -> None:
    with pytest.raises(
        TypeError,
        match=r"^x0 must be the state \[x, y, yaw, v, omega, a\], "
        r"got a Pose2D; " + WAY_OUT + "$",
    ):
        PlanarFusion(Pose2D(1.0, 2.0, 0.3))


def test_a_pose_triple_as_x0_points_to_pose() -> None:
    for pose in ((1.0, 2.0, 0.3), np.array([1.0, 2.0, 0.3]), [1, 2, 0]):
        with pytest.raises(ValueError, match=r"got shape \(3,\); " + WAY_OUT):
            PlanarFusion(pose)


def test_reset_gives_the_same_way_out() -> None:
    fusion = PlanarFusion(t0=0.0)
    before = fusion.x.copy()
    with pytest.raises(TypeError, match=WAY_OUT):
        fusion.reset(Pose2D(1.0, 2.0, 0.3))
    with pytest.raises(ValueError, match=WAY_OUT):
        fusion.reset((1.0, 2.0, 0.3))
    np.testing.assert_array_equal(fusion.x, before)


def test_the_way_out_works() -> None:
    pose = Pose2D(1.0, 2.0, 0.3)
    assert PlanarFusion(pose=pose).x.tolist() == [1.0, 2.0, 0.3, 0.0, 0.0, 0.0]
    assert PlanarFusion(pose=(1.0, 2.0, 0.3)).x.tolist() == [1.0, 2.0, 0.3, 0.0, 0.0, 0.0]


def test_other_x0_refusals_keep_their_messages() -> None:
    with pytest.raises(ValueError, match=r"^x0 must have length 6 along axis 0, got shape \(2,\)$"):
        PlanarFusion([1.0, 2.0])
    with pytest.raises(ValueError, match=r"^x0 must contain only finite values$"):
        PlanarFusion([0.0, 0.0, 0.0, np.nan, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"^give x0 or pose, not both"):
        PlanarFusion(Pose2D(1.0, 2.0, 0.3), pose=Pose2D(1.0, 2.0, 0.3))
    six = np.arange(6.0)
    assert PlanarFusion(six).x.tolist() == six.tolist()
