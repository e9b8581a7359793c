"""Copies and pickles of the simulation's records keep their arrays read-only."""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from navkit.sim import EncoderReading, Event, Metrics, Trace

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda record: pickle.loads(pickle.dumps(record)),
]


def a_trace() -> Trace:
    metrics = Metrics(True, "goal reached", 0.2, 0.2, 0.01, 0.02, 0.01, 0.0, 0.0, 0.5, 0, 0.1)
    poses = np.column_stack((np.linspace(0.0, 0.1, 3), np.zeros(3), np.zeros(3)))
    estimates = poses.copy()
    estimates[0] = np.nan  # no estimate yet at the start
    return Trace(
        np.array([0.0, 0.1, 0.2]), poses, estimates, np.zeros((3, 3)), (),
        (Event(0.2, "goal reached", "at the goal"),), metrics,
    )  # fmt: skip


@pytest.mark.parametrize("duplicate", COPIES, ids=["copy", "deepcopy", "pickle"])
def test_trace_copies_stay_read_only(duplicate: Callable[[Any], Any]) -> None:
    trace = a_trace()
    twin = duplicate(trace)
    for name in ("times", "poses", "estimates", "commands"):
        array = getattr(twin, name)
        np.testing.assert_array_equal(array, getattr(trace, name))
        assert not array.flags.writeable, name
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 1.0
    assert twin.metrics == trace.metrics and twin.events == trace.events
    assert len(twin) == len(trace)


@pytest.mark.parametrize("duplicate", COPIES, ids=["copy", "deepcopy", "pickle"])
def test_encoder_reading_copies_stay_read_only(duplicate: Callable[[Any], Any]) -> None:
    reading = EncoderReading(0.02, np.array([10, -3]))
    twin = duplicate(reading)
    assert twin.stamp == reading.stamp
    assert twin.ticks.tolist() == [10, -3] and twin.ticks.dtype == np.int64
    assert not twin.ticks.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        twin.ticks[0] = 0
    assert reading.ticks.tolist() == [10, -3]


@pytest.mark.parametrize(
    ("args", "error", "match"),
    [
        ((float("nan"), "collision", "x"), ValueError, "^t "),
        ((0.0, "crash", "x"), ValueError, "^kind "),
        ((0.0, "collision", 5), TypeError, "^message must be a str, got int"),
        ((0.0, "collision", b"bytes"), TypeError, "^message must be a str, got bytes"),
    ],
)
def test_bad_events_name_their_field(args: tuple[Any, ...], error: type[Exception],
                                     match: str) -> None:
    with pytest.raises(error, match=match):
        Event(*args)
