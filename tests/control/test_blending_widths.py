"""Closed-loop comparison of blending widths with the two limits (the paper's table).

A robot 3 m from the goal, ``max_speed`` 0.5 m/s, accel 1 / decel 2 m/s², 20 Hz.
Measured here (time to come within 1 cm, overshoot past the goal, final error):
paraboloid 7.3 s, none, 0; cone 6.8 s, 6.2 cm, chattering; blended ω = 0.05 and 0.1
(``threshold_radius = 0.5``) stall about 0.55 m short in the ring of minima
outside ``threshold_radius``; ω = 0.15 (the default) 8.25 s, none, 3.75 mm;
ω = 0.3 and 0.5 settle 4.6 cm short, where σ(0) > 0 moves the minimum off the goal.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D, integrate
from navkit.planning import (
    AttractiveField,
    BlendedAttraction,
    ConicAttraction,
    ParaboloidAttraction,
)

GOAL = 3.0


def approach(
    attraction: AttractiveField, dt: float = 0.05, seconds: float = 20.0
) -> dict[str, float]:
    ctl = PotentialFieldController(attraction, max_speed=0.5, max_accel=1.0, max_decel=2.0)
    pose = Pose2D(0.0, 0.0, 0.0)
    target = Pose2D(GOAL, 0.0, 0.0)
    arrival = math.inf
    xs = []
    for k in range(int(seconds / dt)):
        pose = integrate(pose, ctl.step(pose, target, dt=dt), dt)
        xs.append(pose.x)
        if arrival == math.inf and abs(GOAL - pose.x) < 0.01:
            arrival = (k + 1) * dt
    x = np.array(xs)
    return {
        "arrival": arrival,
        "overshoot": float(max(x.max() - GOAL, 0.0)),
        "error": float(GOAL - x[-1]),
        "stalled": float(ctl.stalled),
    }


def equilibrium(field: BlendedAttraction, lo: float, hi: float) -> float:
    """Distance from the goal where the radial force vanishes (between lo and hi)."""
    return float(brentq(lambda d: field.force([[d, 0.0]])[0, 0], lo, hi, xtol=1e-12))


def test_paraboloid_arrives_without_overshoot() -> None:
    out = approach(ParaboloidAttraction((0.0, 0.0)))
    assert out["arrival"] < 10.0
    assert out["overshoot"] == 0.0
    assert abs(out["error"]) < 1e-6


def test_cone_arrives_first_but_overshoots() -> None:
    cone = approach(ConicAttraction((0.0, 0.0)))
    para = approach(ParaboloidAttraction((0.0, 0.0)))
    assert cone["arrival"] < para["arrival"]
    assert cone["overshoot"] > 0.03


@pytest.mark.parametrize("width", [0.05, 0.1])
def test_narrow_blend_stalls_in_the_ring_of_minima(width: float) -> None:
    field = BlendedAttraction((0.0, 0.0), threshold_radius=0.5, width=width)
    out = approach(field)
    assert out["stalled"] == 1.0 and out["arrival"] == math.inf
    # It stops on the field's own equilibrium just outside threshold_radius.
    ring = equilibrium(field, 0.5, 1.0)
    assert out["error"] == pytest.approx(ring, abs=2e-3)


@pytest.mark.parametrize("width", [0.15, 0.3, 0.5])
def test_wider_blends_settle_on_the_displaced_minimum(width: float) -> None:
    field = BlendedAttraction((0.0, 0.0), threshold_radius=0.5, width=width)
    out = approach(field)
    assert not out["stalled"]
    assert out["overshoot"] == 0.0
    minimum = equilibrium(field, 1e-6, 0.3)
    assert out["error"] == pytest.approx(minimum, abs=1e-3)
    assert minimum < 0.005 if width == 0.15 else minimum > 0.03
