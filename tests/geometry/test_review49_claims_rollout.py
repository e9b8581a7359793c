"""A rollout's drift far from the origin, as the geometry guide and integrate quote it (review 49).

``docs/guides/geometry.md`` says 10^6 steps of 1 mm at a northing of 5e6 m end
0.16 mm off driving north (0.38 mm from its example's start pose), and
``integrate``'s Notes that such runs drift by up to about 1 mm (0.4 mm measured
after 1 km in 1 mm steps). Measured here against the same rollout from the
origin shifted by the start.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from navkit.geometry import Pose2D, rollout

STEPS = 10**6


def _end_offset(x0: float, y0: float, theta: float) -> float:
    """Metres between the far rollout's end and the origin's rollout shifted by (x0, y0)."""
    twists = np.zeros((STEPS, 3))
    twists[:, 0] = 1e-3
    far = rollout(Pose2D(x0, y0, theta), twists, 1.0)[-1]
    near = rollout(Pose2D(0.0, 0.0, theta), twists, 1.0)[-1]
    return math.hypot(far[0] - (near[0] + x0), far[1] - (near[1] + y0))


def test_a_kilometre_north_at_a_northing_of_5e6_ends_0_16_mm_off() -> None:
    assert _end_offset(0.0, 5e6, math.pi / 2) * 1e3 == pytest.approx(0.16, abs=0.005)


def test_a_kilometre_from_the_guides_start_pose_ends_0_38_mm_off() -> None:
    # The guide's example start (512345.25, 5123456.5) at its heading, 0.3 rad.
    assert _end_offset(512345.25, 5123456.5, 0.3) * 1e3 == pytest.approx(0.38, abs=0.005)


@pytest.mark.parametrize("theta", [0.3, 0.785, 1.0, 2.5])
def test_other_headings_stay_within_the_quoted_millimetre(theta: float) -> None:
    # integrate's bound: about one float spacing (9.3e-10 m) per step and axis.
    offset = _end_offset(5e6, 5e6, theta)
    assert 0.0 < offset <= 1e-3
