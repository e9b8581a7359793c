"""Velocity changes below a nanometre per second are limited like any other (review 32, mutants).

``limit_velocity_change`` has no absolute tolerance: a change is a
deceleration exactly when it leaves the speed at most its previous value. Three
mutants giving it one survived the suite: ``t_slow = max(1e-9, ...)`` (a
speed-up shorter than 1e-9 m/s taken as a deceleration, so limited by
``max_decel·dt`` instead of ``max_accel·dt``), ``n == 1e-9`` for ``n == 0.0``
(a change of exactly 1e-9 m/s dropped) and ``n > 1e-9`` for ``n > 0.0`` in the
direction's normalisation (a change below 1e-9 m/s scaled by its own length).
Oracle: the docstring's rule, computed by hand: from rest every change raises
the speed, so it moves by ``min(|change|, max_accel·dt)`` toward ``desired``.
Checked: the tests fail on those mutants of ``_velocity_limits.py`` and pass on
HEAD.
"""

from __future__ import annotations

import pytest

from navkit.control import limit_velocity_change


@pytest.mark.parametrize("change", [1e-9, 1e-10, 5e-12])
def test_a_tiny_speed_up_within_the_limit_is_made_whole(change: float) -> None:
    out = limit_velocity_change([0.0], [change], max_accel=1.0, max_decel=1.0, dt=1.0)
    assert out.tolist() == [change]


def test_a_tiny_speed_up_beyond_the_limit_is_cut_to_max_accel_dt() -> None:
    # max_accel·dt = 1e-12 m/s, max_decel·dt = 1 m/s: the speed-up of 1e-10 m/s is
    # an acceleration, cut to 1e-12, not a deceleration allowed whole.
    out = limit_velocity_change([0.0], [1e-10], max_accel=1e-6, max_decel=1e6, dt=1e-6)
    assert out.tolist() == [pytest.approx(1e-12, rel=1e-12)]
