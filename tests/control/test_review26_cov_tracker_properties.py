"""Tracker properties that no test read (coverage review, session 30).

Each returns the option it is named after, as given (distinct values, so a
property reading a neighbouring option fails), also under the deprecated names.
"""

from __future__ import annotations

import pytest

from navkit.control import FollowTheCarrot, RegulatedPurePursuit


def test_follow_the_carrot_rotate_angle_is_the_option() -> None:
    tracker = FollowTheCarrot(rotate_angle=0.5, align_tolerance=0.2, max_omega=1.25)
    assert (tracker.rotate_angle, tracker.max_omega) == (0.5, 1.25)
    with pytest.warns(DeprecationWarning, match="align_angle is deprecated"):
        assert FollowTheCarrot(align_angle=0.4).rotate_angle == 0.4


def test_regulated_pure_pursuit_turn_options_are_read_back() -> None:
    tracker = RegulatedPurePursuit(max_omega=1.0, rotate_omega=1.1, rotate_angle=0.6)
    assert (tracker.max_omega, tracker.rotate_omega, tracker.rotate_angle) == (1.0, 1.1, 0.6)
    assert RegulatedPurePursuit().max_omega is None  # in-place turns only, by default
    with pytest.warns(DeprecationWarning, match="rotate_to_heading_angle is deprecated"):
        assert RegulatedPurePursuit(rotate_to_heading_angle=0.3).rotate_angle == 0.3
