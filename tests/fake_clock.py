"""A clock that moves only when slept on, for tests of waits with deadlines (shared).

A test of a retry loop bounded by ``time.monotonic()`` that runs on the real
clock fails whenever a loaded machine pauses the process past the bound (a
hold of 0.05 s waited out within 0.2 s, say). On this clock time passes only
through the code's own ``sleep`` calls, so the loop's outcome and its number
of attempts are the same on any machine.
"""

from __future__ import annotations

from types import ModuleType

import pytest


class FakeClock:
    """``monotonic()`` and ``sleep(seconds)`` as the :mod:`time` module's, on a clock of its own."""

    def __init__(self) -> None:
        self.now = 0.0

    def monotonic(self) -> float:
        return self.now

    def sleep(self, seconds: float) -> None:
        self.now += seconds


def fake_clock_for(monkeypatch: pytest.MonkeyPatch, module: ModuleType) -> FakeClock:
    """Give ``module`` a :class:`FakeClock` as its ``time`` (for this test) and return it.

    The module must use only ``time.monotonic`` and ``time.sleep`` (as
    :mod:`navkit._shared.files` does); other modules keep the real clock.
    """
    clock = FakeClock()
    monkeypatch.setattr(module, "time", clock)
    return clock
