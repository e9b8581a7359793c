"""Ctrl-C during numba's first import waits until navkit has loaded numba.

An interrupt that cut numba's import short left it half imported: every later
navkit kernel call in that process failed with an ``AttributeError`` from
numba ("partially initialized module 'numba' has no attribute 'core'").
"""

from __future__ import annotations

import signal
import sys
import threading
from collections.abc import Iterator
from types import FrameType

import pytest

from interrupt_points import CTRL_C_IN_NUMBA_IMPORT
from navkit._shared.interrupts import interrupts_deferred
from subprocess_probe import probe_outcome

pytestmark = pytest.mark.skipif(
    not hasattr(signal, "raise_signal") or sys.platform == "win32",
    reason="needs POSIX signals raised in-process",
)


@pytest.fixture
def default_sigint() -> Iterator[None]:
    """Python's own SIGINT handler during the test, the previous one after it."""
    before = signal.getsignal(signal.SIGINT)
    signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, before)


@pytest.mark.usefixtures("default_sigint")
def test_interrupt_arrives_after_the_block() -> None:
    steps: list[str] = []
    with pytest.raises(KeyboardInterrupt):
        with interrupts_deferred():
            signal.raise_signal(signal.SIGINT)
            steps.append("after the signal")
        steps.append("after the block")  # not reached: the interrupt is delivered at the end
    assert steps == ["after the signal"]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


@pytest.mark.usefixtures("default_sigint")
def test_no_interrupt_no_trace() -> None:
    with interrupts_deferred():
        inside = signal.getsignal(signal.SIGINT)
    assert inside is not signal.default_int_handler
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


@pytest.mark.usefixtures("default_sigint")
def test_second_interrupt_is_delivered_at_once() -> None:
    steps: list[str] = []
    with pytest.raises(KeyboardInterrupt), interrupts_deferred():
        signal.raise_signal(signal.SIGINT)
        steps.append("first held")
        signal.raise_signal(signal.SIGINT)
        steps.append("second held")
    assert steps == ["first held"]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_the_programs_own_handler_gets_it_once() -> None:
    calls: list[tuple[int, bool]] = []

    def handler(signum: int, frame: FrameType | None) -> None:
        calls.append((signum, frame is not None))

    before = signal.signal(signal.SIGINT, handler)
    try:
        with interrupts_deferred():
            signal.raise_signal(signal.SIGINT)
            assert calls == []
        assert calls == [(signal.SIGINT, True)]
        assert signal.getsignal(signal.SIGINT) is handler
    finally:
        signal.signal(signal.SIGINT, before)


def test_ignored_stays_ignored() -> None:
    before = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        with interrupts_deferred():
            signal.raise_signal(signal.SIGINT)
        assert signal.getsignal(signal.SIGINT) == signal.SIG_IGN
    finally:
        signal.signal(signal.SIGINT, before)


@pytest.mark.usefixtures("default_sigint")
def test_an_exception_in_the_block_restores_the_handler() -> None:
    with pytest.raises(ZeroDivisionError), interrupts_deferred():
        1 / 0  # noqa: B018
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


@pytest.mark.usefixtures("default_sigint")
def test_other_threads_leave_the_handler_alone() -> None:
    seen: list[object] = []

    def work() -> None:
        with interrupts_deferred():
            seen.append(signal.getsignal(signal.SIGINT))

    thread = threading.Thread(target=work)
    thread.start()
    thread.join()
    assert seen == [signal.default_int_handler]


_INTERRUPTED_IMPORT = r"""
import json, signal, sys
import numpy as np

""" + CTRL_C_IN_NUMBA_IMPORT + r"""
from navkit.mapping import OccupancyGrid
grid = OccupancyGrid(np.zeros((4, 5)), resolution=0.5)
assert "numba" not in sys.modules
sys.meta_path.insert(0, Interrupt())
outcome = {}
try:
    grid.world_to_cell([[0.3, 1.2], [2.2, 0.1]])
    outcome["first"] = "returned"
except KeyboardInterrupt:
    outcome["first"] = "KeyboardInterrupt"
outcome["fired"] = Interrupt.fired
outcome["handler restored"] = signal.getsignal(signal.SIGINT) is signal.default_int_handler
try:
    outcome["later"] = grid.world_to_cell([[0.3, 1.2], [2.2, 0.1]]).tolist()
except Exception as exc:
    outcome["later"] = f"{type(exc).__name__}: {exc}"
print(json.dumps(outcome))
"""


def test_ctrl_c_during_numbas_import_leaves_navkit_working() -> None:
    outcome = probe_outcome(_INTERRUPTED_IMPORT)
    assert outcome["fired"]
    # The user's Ctrl-C is not lost: it arrives when numba is loaded ...
    assert outcome["first"] == "KeyboardInterrupt"
    assert outcome["handler restored"]
    # ... and navkit keeps working afterwards.
    assert outcome["later"] == [[2, 0], [0, 4]]
