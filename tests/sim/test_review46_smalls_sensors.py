"""Review 46 (SMALLS): the compass's out-of-range messages and 64-bit encoder counts.

* ``Compass(north=3 * pi)`` was told "degrees? pass math.radians(9.42478)": a
  radian angle a turn too far read as degrees. Every hint a message offers
  must now be a reading of the value that fits (each one is passed back to the
  constructor here), and no hint is offered where none fits.
* ``EncoderReading`` keeps counts modulo 2**64 (a uint64 count of 2**63 or
  more reads as int64, the same counter bits); Python ints that NumPy gives no
  integer dtype were refused as "dtype object" or "dtype float64".
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from navkit.geometry import wrap_angle
from navkit.kinematics import tick_delta
from navkit.sim import Compass, EncoderReading, WheelEncoders

_WRAP = re.compile(r"radians\? navkit\.geometry\.wrap_angle\((?P<v>[^)]*)\) is (?P<w>[-+0-9.e]+)")
_DEG = re.compile(r"degrees\? pass math\.radians\((?P<v>[^)]*)\)")


def _message(**kwargs: float) -> str:
    with pytest.raises(ValueError) as info:
        Compass(**kwargs)
    return str(info.value)


def _hints(message: str) -> list[str]:
    """The kinds of hint in the order given: "radians" (wrap) and "degrees"."""
    found = [(m.start(), "radians") for m in _WRAP.finditer(message)]
    found += [(m.start(), "degrees") for m in _DEG.finditer(message)]
    return [kind for _, kind in sorted(found)]


def test_north_three_pi_is_offered_its_wrap_first() -> None:
    msg = _message(north=3 * math.pi)
    assert msg.startswith("north must lie in [-2π, 2π] rad, got 9.42477796076938 (")
    assert _hints(msg) == ["radians", "degrees"]
    m = _WRAP.search(msg)
    assert m is not None and float(m["w"]) == wrap_angle(3 * math.pi)


@pytest.mark.parametrize(
    ("kwargs", "hints"),
    [
        ({"north": 7.0}, ["radians", "degrees"]),  # within two turns: radians likelier
        ({"north": -7.0}, ["radians", "degrees"]),
        ({"north": 90.0}, ["degrees", "radians"]),  # beyond two turns: degrees likelier
        ({"north": -300.0}, ["degrees", "radians"]),
        ({"north": 400.0}, ["radians"]),  # 400° is beyond [-2π, 2π] as well
        ({"north": 1e300}, []),  # no angle left to wrap, no degrees that fit
        ({"north": -2e6}, []),
        ({"bias": 4.0}, ["radians", "degrees"]),
        ({"bias": 90.0}, ["degrees", "radians"]),
        ({"bias": -200.0}, ["radians"]),
        ({"noise": 4.0}, ["degrees"]),  # a deviation does not wrap
        ({"noise": 200.0}, []),
        ({"noise": -0.5}, []),
    ],
)
def test_each_out_of_range_class_gets_its_own_hints(
    kwargs: dict[str, float], hints: list[str]
) -> None:
    msg = _message(**kwargs)
    (name,) = kwargs
    assert re.match(rf"^{name} must lie in \[(-2π, 2π|-π, π|0, π)\] rad, got ", msg), msg
    assert _hints(msg) == hints, msg
    if not hints:
        assert "(" not in msg.split(" got ", 1)[1], msg


@pytest.mark.parametrize("value", [math.inf, -math.inf, math.nan])
@pytest.mark.parametrize("name", ["north", "bias", "noise"])
def test_non_finite_angles_are_called_so(name: str, value: float) -> None:
    msg = _message(**{name: value})
    assert msg == f"{name} must be finite, got {value}"


@given(
    st.sampled_from(["north", "bias", "noise"]),
    st.floats(-1e6, 1e6, allow_nan=False),
    st.floats(-10.0, 10.0),
)
def test_every_hint_offered_fits_and_means_what_it_says(
    name: str, value: float, yaw: float
) -> None:
    try:
        Compass(**{name: value})
    except ValueError as exc:
        msg = str(exc)
    else:
        return  # in range: nothing to hint
    wrap = _WRAP.search(msg)
    if wrap is not None:
        assert name != "noise"
        assert float(wrap["v"]) == value
        fitted = float(wrap["w"])
        assert fitted == wrap_angle(value)
        # The wrapped angle is the same direction: the same compass reading (to the
        # rounding of the value's own turns).
        wrapped = Compass(**{name: fitted})
        want = math.degrees((math.pi / 2 if name == "bias" else value) - yaw
                            + (value if name == "bias" else 0.0)) % 360.0  # fmt: skip
        got = wrapped.heading_deg(yaw)
        assert abs((got - want + 180.0) % 360.0 - 180.0) < 1e-6
    elif name != "noise":
        assert abs(value) > 1e6
    degrees = _DEG.search(msg)
    if degrees is not None:
        assert float(degrees["v"]) == value
        Compass(**{name: math.radians(value)})  # fits
    else:
        low = {"north": -2 * math.pi, "bias": -math.pi, "noise": 0.0}[name]
        high = {"north": 2 * math.pi, "bias": math.pi, "noise": math.pi}[name]
        assert not low <= math.radians(value) <= high


def test_heading_deg_names_the_argument_out_of_range() -> None:
    with pytest.raises(ValueError, match=r"^yaw must lie within ±1e6, got 2000000\.0$"):
        Compass().heading_deg(2e6)
    with pytest.raises(ValueError, match=r"^z must lie within ±1e6, got -30000000\.0$"):
        Compass().heading_deg(0.0, -3e7)


def test_wheel_angles_out_of_range_says_how_far() -> None:
    with pytest.raises(
        ValueError, match=r"^wheel_angles must lie within ±1e9 rad, got \|angle\| 2000000000\.0$"
    ):
        WheelEncoders().ticks([0.0, -2e9])


# --------------------------------------------------------------------------- encoders

_U64 = st.integers(0, 2**64 - 1)


@given(_U64, st.integers(-(2**20), 2**20))
def test_uint64_counts_are_kept_modulo_2_64_and_decode_exactly(start: int, step: int) -> None:
    end = (start + step) % 2**64
    before = EncoderReading(0.0, np.array([start], dtype=np.uint64))
    after = EncoderReading(0.1, np.array([end], dtype=np.uint64))
    for reading, count in ((before, start), (after, end)):
        (stored,) = reading.ticks.tolist()
        assert stored == (count - 2**64 if count >= 2**63 else count)
        assert reading.ticks.dtype == np.int64
    assert tick_delta(before.ticks, after.ticks, bits=64).tolist() == [step]
    # Python ints read the same as the uint64 array.
    assert EncoderReading(0.0, [start]).ticks.tolist() == before.ticks.tolist()


@given(st.lists(st.integers(-(2**63), 2**64 - 1), min_size=1, max_size=4))
def test_python_counts_of_both_signs_are_read_as_64_bit_counters(counts: list[int]) -> None:
    # NumPy makes float64 (rounded) of [-1, 2**63] and object of [2**64 - 1, -1]:
    # each count is still one 64-bit counter reading.
    got = EncoderReading(0.0, counts).ticks.tolist()
    assert got == [c - 2**64 if c >= 2**63 else c for c in counts]


@pytest.mark.parametrize("bad", [2**64, -(2**63) - 1, 10**30])
def test_python_counts_beyond_64_bits_are_refused_by_value(bad: int) -> None:
    with pytest.raises(
        ValueError,
        match=rf"^ticks must be 64-bit counter readings, in \[-2\*\*63, 2\*\*64\), got {bad}$",
    ):
        EncoderReading(0.0, [3, bad])


@pytest.mark.parametrize(
    "bad", [[1.0, 2.0], [True, False], [2**64, 1.5], np.array([3], dtype=object), []]
)
def test_non_integer_counts_are_still_type_errors(bad: object) -> None:
    with pytest.raises(TypeError, match=r"^ticks must be an integer array, got dtype "):
        EncoderReading(0.0, bad)


@pytest.mark.parametrize(
    ("fov", "radians_hint", "degrees_hint"),
    [(7.0, True, True), (3 * math.pi, True, True), (13.0, False, True), (400.0, False, False)],
)
def test_a_lidar_fov_beyond_a_turn_is_offered_each_reading_that_fits(
    fov: float, radians_hint: bool, degrees_hint: bool
) -> None:
    """A field of view of 7 rad (all round, in radians, a bit much) was only asked "degrees?"."""
    from navkit.sim import Lidar

    with pytest.raises(ValueError, match=r"^fov must lie in \(0, 2π\] rad, got ") as info:
        Lidar(fov=fov)
    msg = str(info.value)
    assert ("radians? a full turn, 2π, is the widest: pass 2 * math.pi" in msg) is radians_hint
    assert ("degrees? pass math.radians(" in msg) is degrees_hint
    if radians_hint:
        assert Lidar(fov=2 * math.pi).fov == 2 * math.pi
