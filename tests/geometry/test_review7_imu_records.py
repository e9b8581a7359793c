"""imu_to_base near the top of the float range, and copies of ImuInBase subclasses.

* A rotated reading within the float range was refused when a partial sum of
  ``R_m @ v`` overflowed, and one beyond it was refused as "angular_velocities
  must contain only finite values" (with NumPy's overflow warning) although the
  caller's values were finite.
* A subclass of ``ImuInBase`` that is itself a frozen slotted dataclass (to add a
  field) got writable arrays back from ``copy.deepcopy`` and pickle: the
  dataclass decorator gives it a ``__setstate__`` of its own.
"""

from __future__ import annotations

import copy
import math
import pickle
import warnings
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import ImuInBase, imu_to_base, quaternion_to_matrix, rpy_to_quaternion

_HUGE = st.tuples(st.floats(1.0, 17.9), st.integers(306, 307), st.booleans()).map(
    lambda t: (-t[0] if t[2] else t[0]) * 10.0 ** t[1]
)
_QUAT = st.lists(st.floats(-1.0, 1.0), min_size=4, max_size=4).filter(
    lambda q: math.fsum(v * v for v in q) > 1e-3
)
_LIMIT = Fraction(np.finfo(np.float64).max)


@settings(max_examples=50, deadline=None)
@given(_QUAT, st.tuples(_HUGE, _HUGE, _HUGE))
@example(
    [1.2665688645247233, 0.5565275331801396, -0.8489745470896223, -0.0909370888182374],
    (1.6017565032357083e308, -1.2094399265539522e308, 1.2446722093628624e308),
)
# The draws rarely overflow (none in the default 50 examples): one that does, a 45° yaw
# taking x to 1.34 times the largest float, runs the refusal branch every time.
@example([0.0, 0.0, math.sin(math.pi / 8), math.cos(math.pi / 8)], (1.7e308, -1.7e308, 1e306))
def test_rotated_readings_within_the_float_range(
    mounting: list[float], reading: tuple[float, float, float]
) -> None:
    rot = quaternion_to_matrix(mounting)
    terms = [[Fraction(float(r)) * Fraction(v) for r, v in zip(row, reading, strict=True)]
             for row in rot]
    exact = [sum(t, Fraction(0)) for t in terms]
    peak = max(abs(e) for e in exact)
    if abs(peak / _LIMIT - 1) < Fraction(1, 2**40):
        return  # too close to the float range's end to tell
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no NumPy overflow warning either way
        if peak < _LIMIT:
            out = imu_to_base([[0.0, 0.0, 0.0, 1.0]], [reading], [reading], mount=mounting)
            for got in (out.angular_velocities[0], out.linear_accelerations[0]):
                for value, want, row in zip(got, exact, terms, strict=True):
                    size = sum(map(abs, row), Fraction(0))
                    assert abs(Fraction(float(value)) - want) <= size * Fraction(1, 2**49)
        else:
            with pytest.raises(ValueError, match="angular_velocities: rotating"):
                imu_to_base([0.0, 0.0, 0.0, 1.0], reading, [0.0, 0.0, 0.0], mount=mounting)
            with pytest.raises(ValueError, match="linear_accelerations: rotating"):
                imu_to_base([0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0], reading, mount=mounting)


test_rotated_readings_within_the_float_range_thoroughly = slow_twin(
    test_rotated_readings_within_the_float_range, max_examples=300
)


def test_a_component_beyond_the_float_range_is_refused_naming_the_readings() -> None:
    yawed = rpy_to_quaternion(0.0, 0.0, math.pi / 4)
    with pytest.raises(ValueError, match=r"angular_velocities: rotating .* overflows float64"):
        imu_to_base([0.0, 0.0, 0.0, 1.0], [1.7e308, 1.7e308, 0.0], [0.0, 0.0, 0.0],
                    mount=yawed)


@dataclass(frozen=True, slots=True, eq=False)
class _Tagged(ImuInBase):
    tag: str = ""


def _roundtrip(value: Any) -> Any:
    return pickle.loads(pickle.dumps(value))


@pytest.mark.parametrize("make_copy", [copy.copy, copy.deepcopy, _roundtrip])
def test_subclass_copies_keep_class_fields_and_read_only_arrays(make_copy: Any) -> None:
    original = _Tagged(np.array([0.0, 0.0, 0.0, 2.0]), np.zeros(3), np.full(3, 9.8), "imu0")
    copied = make_copy(original)
    assert type(copied) is _Tagged and copied.tag == "imu0"
    for name in ("orientations", "angular_velocities", "linear_accelerations"):
        array = getattr(copied, name)
        assert not array.flags.writeable
        np.testing.assert_array_equal(array, getattr(original, name))
    base = make_copy(ImuInBase(np.array([0.0, 0.0, 0.0, 1.0]), np.zeros(3), np.ones(3)))
    assert type(base) is ImuInBase and not base.orientations.flags.writeable


def test_an_older_pickle_state_still_loads_read_only() -> None:
    # What the dataclass-generated __getstate__ wrote: the field values in order.
    restored = ImuInBase.__new__(ImuInBase)
    restored.__setstate__([np.array([0.0, 0.0, 0.0, 1.0]), np.zeros(3), np.ones(3)])
    assert not restored.linear_accelerations.flags.writeable
    np.testing.assert_array_equal(restored.linear_accelerations, np.ones(3))
