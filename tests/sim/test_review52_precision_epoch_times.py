"""Epoch stamps given to the simulator's moving obstacles get the way out (review 52, PRECISION).

A simulation runs from t = 0 and its moving obstacles take times within ±1e9 s. A
recorded track (a pedestrian from a bag) carries epoch stamps, 1.78e9 s, and was
refused with "times must lie within ±1e+09 s" alone. The message now says that
such stamps are refused because the simulation starts at 0, and what to pass; the
advice works: the same track with its times from its start moves as recorded.
"""

from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import box

from navkit.sim import MovingObstacle, World

STAMPS = 1_780_000_000.123456 + np.array([0.0, 0.5, 1.25, 2.0])
TRACK = [(1.0, 1.0), (1.5, 1.0), (1.5, 2.0), (2.5, 2.0)]


def test_epoch_times_are_refused_with_the_advice() -> None:
    advice = r"epoch stamps\? a simulation starts at t = 0: give times since the start"
    with pytest.raises(ValueError, match=r"times must lie within ±1e\+09 s \(" + advice):
        MovingObstacle.scripted(0.2, TRACK, times=STAMPS)
    with pytest.raises(ValueError, match=advice + r", times - times\[0\]"):
        MovingObstacle(0.2, TRACK, STAMPS)
    person = MovingObstacle.scripted(0.2, TRACK, times=STAMPS - STAMPS[0])
    with pytest.raises(ValueError, match=r"\bt must lie within ±1e\+09 s, got 1780000000\.623456 "):
        person.position_at(float(STAMPS[1]))
    world = World(box(0.0, 0.0, 4.0, 4.0).exterior, moving=[person])
    with pytest.raises(ValueError, match=advice + r", t - t0"):
        world.collides(0.1, (3.0, 3.0, 0.0), t=float(STAMPS[2]))


def test_times_far_beyond_any_epoch_get_no_such_advice() -> None:
    with pytest.raises(ValueError, match=r"times must lie within ±1e\+09 s$"):
        MovingObstacle(0.2, TRACK[:2], [0.0, 1e12])
    person = MovingObstacle(0.2, TRACK[:2], [0.0, 1.0])
    with pytest.raises(ValueError, match=r"got 1e\+300$"):
        person.position_at(1e300)


def test_the_advice_works_the_track_moves_as_recorded() -> None:
    person = MovingObstacle.scripted(0.2, TRACK, times=STAMPS - STAMPS[0])
    for k, stamp in enumerate(STAMPS):
        np.testing.assert_array_equal(person.position_at(stamp - STAMPS[0]), TRACK[k])
    # Half-way along the second leg (0.5 s .. 1.25 s): the recorded midpoint.
    middle = (STAMPS[1] + STAMPS[2]) / 2 - STAMPS[0]
    np.testing.assert_allclose(person.position_at(middle), (1.5, 1.5), rtol=0, atol=1e-9)
