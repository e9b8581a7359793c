"""CompassCalibration fed a log in random pieces, against the whole log converted at once.

The class notes promise that the yaws of a log given in pieces equal
``compass_to_yaw(log, initial_deg=log[0], unwrap=True)`` (and without ``unwrap``
each reading is ``compass_to_yaw`` of it from the latched first one). A hypothesis
state machine gives readings one at a time (floats, NumPy scalars, ints) and in
pieces of 0-5 (lists, arrays; 2-D without unwrap), with steps of exactly ±180°,
readings far outside [0, 360) and repeated ones, resets, refused readings (which
must latch nothing) and copies or pickle round trips. Every piece's yaws must
equal the slice of the whole log's, bit for bit.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, rule

from navkit.estimation import CompassCalibration, compass_to_yaw
from stateful_runs import COPIERS, run_machine

_COPIERS: tuple[Callable[[CompassCalibration], CompassCalibration], ...] = COPIERS
# Readings: ordinary, exactly half a turn apart, far outside [0, 360).
_READING = st.one_of(
    st.floats(-720.0, 720.0, allow_nan=False),
    st.sampled_from([0.0, 180.0, -180.0, 360.0, 540.0, 90.0, 270.0]),
    st.floats(-1e7, 1e7, allow_nan=False),
)


class CompassMachine(RuleBasedStateMachine):
    cal: CompassCalibration
    unwrap: bool
    log: list[float]  # every reading since the last reset
    got: list[float]  # every yaw returned since, in order

    @initialize(unwrap=st.booleans())
    def start(self, unwrap: bool) -> None:
        self.unwrap = unwrap
        self.cal = CompassCalibration(unwrap=unwrap)
        self.log = []
        self.got = []

    @rule(reading=_READING, kind=st.sampled_from(["float", "numpy", "int", "0-d"]))
    def one(self, reading: float, kind: str) -> None:
        arg: Any = reading
        if kind == "numpy":
            arg = np.float64(reading)
        elif kind == "int":
            reading = float(round(reading))
            arg = int(reading)
        elif kind == "0-d":
            arg = np.array(reading)
        yaw = self.cal(arg)
        assert isinstance(yaw, float)
        self.log.append(reading)
        self.got.append(yaw)

    @rule(readings=st.lists(_READING, max_size=5), kind=st.sampled_from(["list", "array", "2-d"]))
    def piece(self, readings: list[float], kind: str) -> None:
        arg: Any = list(readings)
        if kind == "array":
            arg = np.array(readings)
        elif kind == "2-d":
            if self.unwrap or len(readings) % 2:
                return  # refused with unwrap (see refused), and needs pairs here
            arg = np.array(readings).reshape(-1, 2)
        yaw = self.cal(arg)
        assert isinstance(yaw, np.ndarray)
        assert yaw.shape == np.shape(arg)
        self.log.extend(readings)
        self.got.extend(yaw.reshape(-1).tolist())

    @rule(kind=st.sampled_from(["nan", "inf", "string", "2-d"]))
    def refused(self, kind: str) -> None:
        initial = self.cal.initial_deg
        arg: Any = {"nan": [1.0, math.nan], "inf": math.inf, "string": "10"}.get(kind)
        if kind == "2-d":
            if not self.unwrap:
                return
            arg = [[1.0, 2.0]]
        with pytest.raises((ValueError, TypeError), match="raw_deg"):
            self.cal(arg)
        assert self.cal.initial_deg == initial

    @rule()
    def reset(self) -> None:
        self.cal.reset()
        assert self.cal.initial_deg is None
        self.log = []
        self.got = []

    @rule(how=st.integers(0, len(_COPIERS) - 1), reading=_READING)
    def swap_for_copy(self, how: int, reading: float) -> None:
        old, self.cal = self.cal, _COPIERS[how](self.cal)
        # The original going on must not reach the copy (checked by the invariant).
        old(reading)
        old(reading + 180.0)

    @invariant()
    def pieces_equal_the_whole_log(self) -> None:
        if not self.log:
            return
        assert self.cal.initial_deg == self.log[0]
        whole = np.asarray(
            compass_to_yaw(np.array(self.log), initial_deg=self.log[0], unwrap=self.unwrap)
        )
        assert whole.tobytes() == np.array(self.got).tobytes(), (whole, self.got)


def test_pieces_equal_the_whole_log() -> None:
    run_machine(CompassMachine, examples=50, steps=25)


@pytest.mark.slow
def test_pieces_equal_the_whole_log_long() -> None:
    run_machine(CompassMachine, examples=500, steps=50)
