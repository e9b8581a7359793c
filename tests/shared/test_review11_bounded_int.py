"""One check for every integer option (review 11, session 15).

Integer options (counts, bits, levels, seeds, widths, digits, holder indices)
were checked by hand in some fifteen places that did not agree: 0-d integer
arrays (``np.array(3)``, what indexing or reducing an integer array gives) were
refused everywhere although float options accept 0-d float arrays, and some
places let ``np.bool_`` through as the number 1. They all use
``navkit._shared.validation.bounded_int`` now.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit._shared.validation import bounded_int
from navkit.behaviours import GameState
from navkit.estimation import DiffOdometry
from navkit.kinematics import DiffDrive
from navkit.mapping import ScanMatcher
from navkit.mapping.io import OccupancyGridMsgFields
from navkit.planning import GreedyStep, Path2D, astar
from navkit.sim import (
    Lidar,
    Metrics,
    Table,
    WarmupReport,
    WheelEncoders,
    sweep,
    trial_seed,
    warmup,
)
from navkit.sim.scenarios import IndoorNav, Soccer

INT_DTYPES: tuple[type[np.integer[Any]], ...] = (
    np.int8, np.int16, np.int32, np.int64, np.uint8, np.uint16, np.uint32, np.uint64,
)


@st.composite
def int_likes(draw: st.DrawFn) -> tuple[Any, int]:
    """An integer in one of the forms accepted, and its value."""
    dtype = draw(st.sampled_from(INT_DTYPES))
    info = np.iinfo(dtype)
    value = draw(st.integers(int(info.min), int(info.max)))
    form = draw(st.sampled_from(("python", "scalar", "0-d array")))
    if form == "python":
        return value, value
    if form == "scalar":
        return dtype(value), value
    return np.array(value, dtype=dtype), value


@settings(max_examples=60, deadline=None)
@given(int_likes(), st.integers(-(2**64), 2**64), st.integers(0, 2**65), st.booleans())
def test_int_likes_are_their_value_or_out_of_range(
    given_value: tuple[Any, int], low: int, span: int, exclusive: bool
) -> None:
    value, expected = given_value
    high = low + span
    inside = low <= expected and (expected < high if exclusive else expected <= high)
    if inside:
        out = bounded_int(value, "count", low, high, exclusive=exclusive)
        assert type(out) is int and out == expected
    else:
        with pytest.raises(ValueError, match=r"^count must be in \[") as info:
            bounded_int(value, "count", low, high, exclusive=exclusive)
        assert info.value.args[0].endswith(f"got {expected}")
        assert info.value.args[0].count(")" if exclusive else "]") == 1


@settings(max_examples=40, deadline=None)
@given(int_likes())
def test_open_sides_accept_every_integer(given_value: tuple[Any, int]) -> None:
    value, expected = given_value
    assert bounded_int(value, "count") == expected
    assert bounded_int(value, "count", low=expected) == expected
    assert bounded_int(value, "count", high=expected) == expected
    with pytest.raises(ValueError, match=rf"^count must be >= .*, got {expected}$") as info:
        bounded_int(value, "count", low=expected + 1)
    assert _stated_bound(info.value, ">=") == expected + 1
    with pytest.raises(ValueError, match=rf"^count must be < .*, got {expected}$") as info:
        bounded_int(value, "count", high=expected, exclusive=True)
    assert _stated_bound(info.value, "<") == expected


def _stated_bound(error: ValueError, relation: str) -> int:
    """The bound a message states, written out (``2**64``, ``2**63 - 1``) or in digits."""
    text = re.fullmatch(rf"count must be {relation} (.*), got -?\d+", str(error))
    assert text is not None, str(error)
    power = re.fullmatch(r"2\*\*(\d+)( - 1)?", text[1])
    if power is None:
        return int(text[1])
    return (1 << int(power[1])) - (1 if power[2] else 0)


@pytest.mark.parametrize(
    "value",
    [True, False, np.True_, np.bool_(False), np.array(True), 2.0, np.float64(3.0),
     np.array(2.0), np.array([3]), np.zeros((1, 1), dtype=int), "3", b"3", None, 1 + 0j,
     math.nan, [1], object()],
    # object()'s repr holds its address: the ids must be the same in every
    # collecting process (pytest-xdist's workers compare them).
    ids=lambda value: "object()" if type(value) is object else repr(value),
)
def test_non_integers_are_a_type_error_naming_the_argument(value: Any) -> None:
    with pytest.raises(TypeError, match=r"^levels must be an integer, got "):
        bounded_int(value, "levels", 0, 10)
    with pytest.raises(TypeError, match=r"^levels must be an integer or None, got "):
        bounded_int(value, "levels", 0, 10, or_none=True)


def test_the_input_is_not_modified_and_a_masked_one_is_refused() -> None:
    value = np.array(7, dtype=np.int16)
    assert bounded_int(value, "n", 0, 10) == 7 and value.dtype == np.int16 and value == 7
    assert bounded_int(np.ma.array(4), "n", 0, 10) == 4
    with pytest.raises(ValueError, match=r"^n has masked entries"):
        bounded_int(np.ma.array(4, mask=True), "n", 0, 10)


@pytest.mark.parametrize(
    ("low", "high", "exclusive", "value", "message"),
    [
        (0, 2**64, True, 2**64, r"seed must be in [0, 2**64), got 18446744073709551616"),
        (0, 2**63 - 1, False, -1, r"seed must be in [0, 2**63 - 1], got -1"),
        (1, 17, False, 10**40, "seed must be in [1, 17], got an integer of about 10**40"),
        (None, 5, False, 6, "seed must be <= 5, got 6"),
    ],
)
def test_range_messages(low: int | None, high: int | None, exclusive: bool, value: int,
                        message: str) -> None:
    with pytest.raises(ValueError) as info:
        bounded_int(value, "seed", low, high, exclusive=exclusive)
    assert str(info.value) == message


# --- every public site: (build with the value, the argument's name, a valid value) ---

_DRIVE = DiffDrive(track=0.3, wheel_radius=0.05)


def _state(holder: Any) -> GameState:
    return GameState(robot_xy=(0.0, 0.0), ball_xy=(2.0, 0.0), opponents_xy=[[3.0, 0.0], [2.0, 0.1]],
                     own_goal_xy=(-4.5, 0.0), opponent_goal_xy=(4.5, 0.0),
                     opponent_with_ball=holder)


def _msg(width: Any) -> OccupancyGridMsgFields:
    return OccupancyGridMsgFields(width, 2, 0.5, (0, 0, 0), (0, 0, 0, 1),
                                  np.zeros(4, dtype=np.int8))


SITES: list[tuple[Callable[[Any], object], str, int]] = [
    (lambda v: ScanMatcher(levels=v), "levels", 2),
    (lambda v: ScanMatcher(max_iterations=v), "max_iterations", 3),
    (_msg, "width", 2),
    (lambda v: Table("t", ("a",), ((1.5,),)).render(digits=v), "digits", 3),
    (lambda v: trial_seed(v, 0, 0), "base", 5),
    (lambda v: trial_seed(5, v, 0), "case_index", 2),
    (lambda v: IndoorNav(targets=v), "targets", 3),
    (lambda v: IndoorNav(paths=v), "paths", 2),
    (lambda v: Soccer(table_cells=v), "table_cells", 100),
    (lambda v: Soccer().cases(v), "trials", 1),
    (lambda v: Metrics(False, "timeout", 1.0, math.nan, math.nan, math.nan, math.nan, math.nan,
                       math.nan, 0.5, v, 1.0), "collisions", 1),
    (lambda v: WheelEncoders(ticks_per_rev=360, bits=v), "bits", 16),
    (lambda v: DiffOdometry(_DRIVE, ticks_per_rev=360, bits=v), "bits", 16),
    (lambda v: Lidar(n_beams=v, noise=None), "n_beams", 4),
    (lambda v: WarmupReport(steps=(), seconds=0.0, workers=v), "workers", 2),
    (_state, "opponent_with_ball", 1),
    (lambda v: Path2D([[0, 0]], "grid", 0.0, 0.0, expanded=v), "expanded", 7),
    (lambda v: astar(np.ones((3, 3)), (0, 0), (2, 2), connectivity=v), "connectivity", 4),
    (lambda v: GreedyStep((10, 12), [0.2, 0.0], 0.2, 1.8, candidates=v), "candidates", 440),
    (lambda v: GreedyStep((v, 12), [0.2, 0.0], 0.2, 1.8, candidates=4), "cell", 10),
]


@pytest.mark.parametrize(("build", "name", "valid"), SITES, ids=[s[1] for s in SITES])
def test_every_integer_option_takes_a_0d_array_and_refuses_numpy_bools(
    build: Callable[[Any], object], name: str, valid: int
) -> None:
    built, plain = build(np.array(valid)), build(valid)
    if " at 0x" not in repr(plain):  # an object without a value repr (ScanMatcher)
        assert repr(built) == repr(plain)
    for flag in (np.True_, np.bool_(False)):
        with pytest.raises(TypeError, match=rf"\b{name}\b"):
            build(flag)
    with pytest.raises(TypeError, match=rf"\b{name}\b"):
        build(np.array(float(valid)))


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda v: sweep(Soccer(), trials=v), "trials"),
        (lambda v: sweep(Soccer(), workers=v), "workers"),
        (lambda v: sweep(Soccer(), seeds=v), "seeds"),
        (lambda v: sweep(Soccer(), seeds=[3, v]), r"seeds\[1\]"),
        (lambda v: warmup(workers=v, only=["geometry"]), "workers"),
    ],
)
def test_run_options_refuse_numpy_bools_before_running(
    call: Callable[[Any], object], name: str
) -> None:
    # Refused up front: nothing is run or compiled (these would take seconds).
    for flag in (np.True_, np.bool_(False)):
        with pytest.raises(TypeError, match=rf"^{name} must be an integer"):
            call(flag)
