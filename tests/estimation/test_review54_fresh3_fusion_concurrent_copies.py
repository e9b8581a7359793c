"""Copies of a PlanarFusion with history taken by two threads at once (review 54, FRESH3).

``PlanarFusion.__reduce__`` (with ``history``) takes a copy as a short call of
the filter: a copy made while a call is under way keeps no steps (the buffer
may be ahead of them), as after an interrupted call. A copy under way counts
as such a call too, although it only reads: of two threads copying a filter at
once with no update running, the second copy keeps no steps, and a late
measurement within ``history`` that the original (and the first copy) fuse is
refused by it as out of order, its estimate then apart from theirs. The same
defect as FieldDStar's (fixed there in review 54); found here by FRESH3 as a
strict xfail, fixed by FOUND7 with FRESH3's one-line fix (a call writing the
buffer runs only as the first token: another copy first only reads).
"""

from __future__ import annotations

import copy
import sys
import threading
from types import FrameType
from typing import Any

import numpy as np

from navkit.estimation import PlanarFusion


def test_a_copy_taken_while_another_thread_copies_keeps_the_steps() -> None:
    fusion = PlanarFusion(history=1.0)
    for k in range(1, 6):
        fusion.update_speed(0.1 * k, 0.5, variance=0.01)
    entered, release = threading.Event(), threading.Event()

    def hold(frame: FrameType, event: str, arg: Any) -> None:
        # The first copy waits inside its guard, at its copy of the buffer.
        if (
            event == "c_call"
            and frame.f_code.co_name == "__reduce__"
            and getattr(arg, "__name__", "") == "copy"
            and not entered.is_set()
        ):
            entered.set()
            release.wait(30.0)

    held: list[PlanarFusion] = []

    def copier() -> None:
        sys.setprofile(hold)
        try:
            held.append(copy.deepcopy(fusion))
        finally:
            sys.setprofile(None)

    thread = threading.Thread(target=copier)
    thread.start()
    try:
        if not entered.wait(30.0):
            raise RuntimeError("the first copy never reached its buffer copy")
        second = copy.deepcopy(fusion)  # this thread's copy, the other's under way
    finally:
        release.set()
        thread.join(30.0)
    late = fusion.update_speed(0.25, 0.8, variance=0.01)  # within history: fused
    assert late.accepted
    for twin in (held[0], second):
        again = twin.update_speed(0.25, 0.8, variance=0.01)
        assert again.accepted, again.reason
        np.testing.assert_array_equal(twin.x, fusion.x)
