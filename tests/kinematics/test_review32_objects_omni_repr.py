"""``eval(repr(drive))`` rebuilds an OmniDrive with the very wheel angles (review 32, OBJECTS).

The repr looks like the constructor call (``radians([30, 150, 270])``) and the
drive computes from the angles as given, bit for bit; but the repr printed 6
significant digits of degrees, so a drive built from radians (0.1, 2.2, 4.3)
printed ``radians([5.72958, 126.051, 246.372])``, which evaluates to a
different drive (its forward twist off in the 7th digit). Whole-ish degrees
still print as degrees; other angles print exactly, in radians.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from numpy import radians

from hypothesis_twins import slow_twin
from navkit.kinematics import OmniDrive


def _rebuilt(drive: OmniDrive) -> OmniDrive:
    rebuilt = eval(repr(drive), {"OmniDrive": OmniDrive, "radians": radians})
    assert isinstance(rebuilt, OmniDrive)
    return rebuilt


def test_radian_angles_round_trip_exactly() -> None:
    drive = OmniDrive([0.1, 2.2, 4.3], wheel_radius=0.05, base_radius=0.2)
    # Was radians([5.72958, 126.051, 246.372]): 0.1 came back as 0.09999994...
    assert repr(drive) == (
        "OmniDrive(wheel_angles=[0.1, 2.2, 4.3], wheel_radius=0.05, base_radius=0.2)"
    )
    rebuilt = _rebuilt(drive)
    np.testing.assert_array_equal(rebuilt.jacobian, drive.jacobian)
    assert rebuilt.forward([1.0, -2.0, 0.5]) == drive.forward([1.0, -2.0, 0.5])


def test_layouts_in_degrees_still_print_in_degrees() -> None:
    for degrees, text in (
        ([30, 150, 270], "radians([30, 150, 270])"),
        ([45, 135, 225, 315], "radians([45, 135, 225, 315])"),
        ([37.5, 120, -90], "radians([37.5, 120, -90])"),
    ):
        drive = OmniDrive(np.radians(degrees), wheel_radius=0.05, base_radius=0.2)
        assert f"wheel_angles={text}," in repr(drive)
        np.testing.assert_array_equal(_rebuilt(drive).jacobian, drive.jacobian)


_ANGLES = st.lists(st.floats(-7.0, 7.0, allow_subnormal=False), min_size=3, max_size=5)


@settings(max_examples=60, deadline=None)
@given(_ANGLES)
def test_any_drive_round_trips_bit_for_bit(angles: list[float]) -> None:
    given_angles = np.array(angles)
    layout = np.column_stack((-np.sin(given_angles), np.cos(given_angles), np.ones(len(angles))))
    assume(np.linalg.cond(layout) < 1e8)  # a singular layout is refused: not this subject
    # Whole numbers beyond a full turn look like degrees and warn: not this subject.
    assume(not (np.max(np.abs(given_angles)) > 2 * math.pi and np.all(given_angles % 1.0 == 0.0)))
    drive = OmniDrive(given_angles, wheel_radius=0.05, base_radius=0.2)
    rebuilt = _rebuilt(drive)
    np.testing.assert_array_equal(rebuilt.jacobian, drive.jacobian)
    np.testing.assert_array_equal(np.signbit(rebuilt.jacobian), np.signbit(drive.jacobian))
    assert repr(rebuilt) == repr(drive)


test_any_drive_round_trips_bit_for_bit_thoroughly = slow_twin(
    test_any_drive_round_trips_bit_for_bit, max_examples=400
)
