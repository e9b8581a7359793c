"""A ``done`` that is a number other than 0 or 1, or a NaN, is refused (review 29, FNF2).

``done_flag`` took ``bool(done)``: a NaN ``done`` (``np.float64('nan')``, a 0-d
or size-1 float array holding NaN) is true in Python, so a NaN ended the run at
once without a word, and so did ``done = 0.3`` (a progress fraction or a
distance written where a flag belongs). Flags (``bool``, ``np.bool_``, boolean
arrays of one element) and the numbers 0 and 1 (``1``, ``0.0``, ``np.int8(1)``)
keep their truth value. Checked: against ``_done.py`` before the change the
refusal tests fail (NaN and 0.3 came back True) and the others pass.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from shapely.geometry import box

from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Robot, Simulation, TrackerController, World
from navkit.sim._done import done_flag

FLAGS = [
    (True, True),
    (False, False),
    (np.True_, True),
    (np.False_, False),
    (np.array(True), True),
    (np.array([False]), False),
    (np.array([[True]]), True),
    (1, True),
    (0, False),
    (1.0, True),
    (-0.0, False),
    (np.float32(1.0), True),
    (np.int8(0), False),
    (np.array(1.0), True),
    (np.array([0]), False),
    (Fraction(1), True),
    (None, False),  # no number: its truth value, as before (strings: review 30 refuses them)
]


@pytest.mark.parametrize(("done", "expected"), FLAGS)
def test_flags_and_zero_and_one_keep_their_truth_value(done: object, expected: bool) -> None:
    result = done_flag(done, "tracker.done")
    assert result is expected


NOT_FLAGS = [
    math.nan,
    np.float64("nan"),
    np.float32("nan"),
    np.array(np.nan),
    np.array([np.nan]),
    0.3,
    2,
    -1.0,
    math.inf,
    np.float64(0.5),
    np.array([2.0]),
    complex(0.0, 1.0),
    Fraction(1, 2),
]


@pytest.mark.parametrize("done", NOT_FLAGS, ids=repr)
def test_a_number_other_than_zero_or_one_is_refused_naming_the_flag(done: object) -> None:
    with pytest.raises(ValueError, match=r"tracker\.done must be true or false, got "):
        done_flag(done, "tracker.done")


def test_an_array_done_is_not_changed() -> None:
    done = np.array([np.nan])
    with pytest.raises(ValueError, match="nan"):
        done_flag(done, "tracker.done")
    assert np.isnan(done[0]) and done.flags.writeable


class _NanTracker:
    """A tracker whose ``done`` is a NaN: a distance left that went wrong."""

    def __init__(self) -> None:
        self.done = np.float64("nan")

    def step(self, pose: Pose2D, dt: float) -> Twist2D:
        return Twist2D(0.1, 0.0, 0.0)


class _NanController:
    done = np.float64("nan")

    def __call__(self, _obs: object) -> Twist2D:
        return Twist2D(0.1, 0.0, 0.0)


def _sim(controller: object) -> Simulation:
    world = World([box(-1.0, -1.0, 4.0, 3.0).exterior])
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    return Simulation(world, robot, controller, start=(0.0, 0.0, 0.0), duration=0.3)  # type: ignore[arg-type]


def test_a_nan_done_does_not_end_a_run_silently() -> None:
    follow = TrackerController(_NanTracker(), control_rate=10.0, use_estimate=False)
    with pytest.raises(ValueError, match=r"tracker\.done must be true or false, got float64 nan"):
        _ = follow.done
    with pytest.raises(ValueError, match=r"tracker\.done"):
        _sim(follow).run()
    with pytest.raises(ValueError, match=r"the controller's done must be true or false"):
        _sim(_NanController()).run()
