"""A format spec formats a pose's or twist's fields (review 32, OBJECTS).

``f"{pose:.2f}"``, the natural way to log a pose, raised ``TypeError:
unsupported format string passed to Pose2D.__format__``; users wrote
``f"{pose.x:.2f}, {pose.y:.2f}, ..."`` by hand. The spec now applies to each
float field, in the repr's layout; an empty spec is ``str()`` as before, and a
spec no float takes is a ``ValueError`` naming the spec.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.geometry import Pose2D, Twist2D


def test_a_spec_formats_each_field() -> None:
    pose = Pose2D(1.0, -2.0, math.pi / 2)
    assert f"{pose:.2f}" == "Pose2D(x=1.00, y=-2.00, theta=1.57)"
    assert f"{Twist2D(0.5, 0.0, 0.1):+.1e}" == "Twist2D(vx=+5.0e-01, vy=+0.0e+00, omega=+1.0e-01)"
    assert format(pose, "8.3f") == "Pose2D(x=   1.000, y=  -2.000, theta=   1.571)"


def test_no_spec_is_str_as_before() -> None:
    pose = Pose2D(1.0, 2.0, 0.5)
    assert f"{pose}" == str(pose) == repr(pose) == "Pose2D(x=1.0, y=2.0, theta=0.5)"
    assert f"{pose!r:>3}" == repr(pose)


class Waypoint(Pose2D):
    """A user's pose type."""

    __slots__ = ()


def test_a_subclass_is_named_as_its_repr_names_it() -> None:
    waypoint = Waypoint(1.0, 2.0, 0.0)
    assert f"{waypoint:.1f}" == repr(waypoint) == "Waypoint(x=1.0, y=2.0, theta=0.0)"


@pytest.mark.parametrize("spec", ["d", "s", "x", ",q"])
def test_a_spec_no_float_takes_is_refused_by_name(spec: str) -> None:
    with pytest.raises(ValueError, match=rf"format spec '{spec}' of a Pose2D must format its"):
        format(Pose2D(1.0, 2.0, 0.5), spec)


@given(st.floats(-1e6, 1e6), st.floats(-1e6, 1e6), st.floats(-10.0, 10.0))
def test_the_fields_read_back_to_the_precision_asked(x: float, y: float, theta: float) -> None:
    pose = Pose2D(x, y, theta)
    text = f"{pose:.6e}"
    values = [float(part.split("=")[1]) for part in text[len("Pose2D(") : -1].split(", ")]
    for got, want in zip(values, (pose.x, pose.y, pose.theta), strict=True):
        assert got == pytest.approx(want, rel=1e-6, abs=0.0)
