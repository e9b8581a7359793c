"""OmniOdometry.update: the pose does not depend on the increments' memory layout."""

from __future__ import annotations

import numpy as np

from navkit.estimation import OmniOdometry
from navkit.kinematics import OmniDrive


def test_reversed_and_broadcast_views_give_the_contiguous_arrays_pose() -> None:
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    rng = np.random.default_rng(7)
    differs = 0
    for _ in range(300):
        inc = rng.normal(0.0, 1.0, 3)
        yaw = float(rng.uniform(-3.0, 3.0))
        views = [inc[::-1].copy()[::-1], np.broadcast_to(inc[:1], (3,))]
        plains = [inc.copy(), np.full(3, inc[0])]
        for view, plain in zip(views, plains, strict=True):
            a, b = OmniOdometry(drive), OmniOdometry(drive)
            pa, pb = a.update(view, yaw), b.update(plain, yaw)
            differs += pa != pb
            assert pa == pb, (view, plain)
    assert differs == 0
