"""PlanarFusion(history=): trimming the steps kept costs O(1) a call (review 31, SCALING).

Found: ``_record`` dropped the steps gone from the window with ``del entries[:n]``,
which shifts every step kept, on every call: at 1 kHz an update cost 1.9, 2.6, 5.4
and 21.4 µs with windows of 4, 16, 64 and 256 s. The steps gone now leave a
placeholder in their slot (freed as they go) and the list drops those slots once
they are half of it: a shift of the window's steps once per window's worth of calls.

Checked here without timing: the list elements moved per update (counted by a list
that records them) are bounded whatever the window; the dead slots hold no step;
late measurements, ties, copies and interrupts around the compaction give the
filter the batch in stamp order gives, bit for bit.
"""

from __future__ import annotations

import copy
import gc
import pickle
import weakref
from typing import Any, SupportsIndex

import numpy as np
import pytest
from test_review22_fusion_history import Meas, _assert_same_filter, _batch, _feed

from interrupt_points import delivery_points, interrupted_at
from navkit._shared.jit import jit_disabled
from navkit.estimation import FusionStatus, PlanarFusion, _fusion


class _MoveCounter(list[Any]):
    """A list counting the elements its deletions and resizing slice stores shift."""

    moves = 0

    def __delitem__(self, key: SupportsIndex | slice) -> None:
        if isinstance(key, slice):
            start, stop, step = key.indices(len(self))
            if step == 1 and stop > start:
                self.moves += len(self) - stop
        else:
            self.moves += len(self) - (key.__index__() % len(self)) - 1
        super().__delitem__(key)

    def __setitem__(self, key: Any, value: Any) -> None:
        if isinstance(key, slice):
            value = list(value)
            start, stop, _ = key.indices(len(self))
            if len(value) != max(stop - start, 0):
                self.moves += len(self) - stop
        super().__setitem__(key, value)

    def pop(self, index: SupportsIndex = -1) -> Any:
        self.moves += len(self) - (index.__index__() % len(self)) - 1
        return super().pop(index)

    def insert(self, index: SupportsIndex, value: Any) -> None:
        self.moves += max(len(self) - index.__index__(), 0)
        super().insert(index, value)


def _odometry_at(fusion: PlanarFusion, k: int, rate: float) -> None:
    fusion.update_odometry(k / rate, 1.0, 0.1, v_variance=1e-4, omega_variance=1e-4)


@pytest.mark.parametrize("window", [0.5, 4.0])
def test_an_update_moves_a_bounded_number_of_kept_steps(window: float) -> None:
    # At 1 kHz the window holds 500 or 4,000 steps. Deleting the oldest step each call
    # shifted them all: 500 and 4,000 moves per update (O(window)); now about one
    # (a shift of the window's steps once per window's worth of calls).
    rate = 1000.0
    kept = int(window * rate)
    fusion = PlanarFusion(t0=0.0, history=window)
    spy = _MoveCounter()
    fusion._steps = spy
    filled = kept + 50  # the window filled, trimming every call
    for k in range(1, filled):
        _odometry_at(fusion, k, rate)
    spy.moves = 0
    calls = 3 * kept  # two compactions at least
    for k in range(filled, filled + calls):
        _odometry_at(fusion, k, rate)
    assert fusion._steps is spy  # every trim went through the spy
    assert kept <= len(fusion._entries) <= kept + 2
    assert spy.moves <= 2 * calls
    # The dead slots are dropped as they become half the list.
    assert len(spy) <= 2 * len(fusion._entries) + 2


def _run(rate: float, seconds: float) -> list[Meas]:
    """Odometry at ``rate``; a yaw rate every 7th step, one in three stamped with it."""
    out: list[Meas] = []
    for k in range(1, int(seconds * rate) + 1):
        t = k / rate
        out.append((t, "odometry", 1.0 + 0.01 * (k % 5), 0.1))
        if k % 7 == 0:
            out.append((t if k % 3 == 0 else t - 0.4 / rate, "yaw_rate", 0.12, 0.0))
    return out


def test_late_measurements_across_compactions_equal_the_batch() -> None:
    # Late yaw rates, some tied with an odometry step, 10 to 35 ms late in a 50 ms
    # window (at 200 Hz, 10 steps kept): fused where they belong while the kept steps
    # start past dead slots, and after the slots are dropped, as the batch fuses them.
    window, rate = 0.05, 200.0
    run = _run(rate, 3.0)
    arrivals = sorted(
        enumerate(run),
        key=lambda im: (im[1][0] + (0.01 + 0.005 * (im[0] % 6) if im[1][1] == "yaw_rate" else 0.0),
                        im[0]),
    )  # fmt: skip
    fusion = PlanarFusion(t0=0.0, history=window)
    heads = set()
    for _, m in arrivals:
        if m[1] == "yaw_rate":
            heads.add(fusion._head)
        assert _feed(fusion, m).accepted
    assert len(heads) > 3 and max(heads) > 3  # late ones met dead slots, few or many
    _assert_same_filter(fusion, _batch(run, t0=0.0))


@pytest.mark.parametrize("how", ["copy", "deepcopy", "pickle"])
def test_copies_carry_the_steps_kept_and_no_dead_slots(how: str) -> None:
    rate, window = 200.0, 0.05
    run = _run(rate, 1.0)
    fusion = PlanarFusion(t0=0.0, history=window)
    for m in run:
        _feed(fusion, m)
        if fusion._head > 3:
            break
    kept = fusion._entries
    assert np.isfinite([e[0] for e in kept]).all()
    twin = pickle.loads(pickle.dumps(fusion)) if how == "pickle" else getattr(copy, how)(fusion)
    # The copy's steps are the ones kept (no placeholder), the same stamps and states.
    assert twin._head == 0 and len(twin._steps) == len(kept)
    assert [(e[0], e[2].tobytes(), e[3]) for e in twin._entries] == [
        (e[0], e[2].tobytes(), e[3]) for e in kept
    ]
    t = kept[-1][0]
    late: Meas = (t - 0.03, "yaw", 0.05, 0.0)  # behind 6 of the steps kept
    for f in (fusion, twin):
        assert _feed(f, late).accepted
        _feed(f, (t + 1 / rate, "odometry", 1.0, 0.1))
    _assert_same_filter(twin, fusion)


def test_a_step_leaving_the_window_is_freed_at_once() -> None:
    # The placeholders keep no step alive until the slots are dropped: a 256 s window
    # at 1 kHz would otherwise hold up to twice its 256,000 steps.
    fusion = PlanarFusion(t0=0.0, history=0.5)
    rate = 100.0
    for k in range(1, 60):
        _odometry_at(fusion, k, rate)
    stamp = fusion._entries[0][0]
    oldest = weakref.ref(fusion._entries[0][2])
    for k in range(60, 70):  # until the oldest step leaves the window
        _odometry_at(fusion, k, rate)
        if fusion._entries[0][0] != stamp:
            break
    assert fusion._head > 0  # its slot is not dropped yet
    gc.collect()
    assert oldest() is None


def _at_compaction() -> tuple[list[Meas], Meas]:
    """Odometry steps after which the next one (returned) drops the dead slots."""
    rate, window = 100.0, 0.1
    probe = PlanarFusion(t0=0.0, history=window)
    fed: list[Meas] = []
    for k in range(1, 200):
        m: Meas = (k / rate, "odometry", 1.0, 0.1)
        before = len(probe._steps)
        _feed(probe, m)
        if len(probe._steps) < before and k > 40:
            return fed, m
        fed.append(m)
    raise AssertionError("no compaction")


@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: interrupts land inside the step")
def test_an_interrupt_around_the_compaction_leaves_a_consistent_filter() -> None:
    # Interrupted anywhere in the update that drops the dead slots, the filter took the
    # update or not, and its history is whole or dropped: a later late measurement is
    # then fused as in the batch, or refused.
    fed, m1 = _at_compaction()
    m2: Meas = (m1[0] - 0.05, "yaw_rate", 0.2, 0.0)

    def built() -> PlanarFusion:
        # Replayed, not copied: a copy carries the steps kept without the dead slots.
        fusion = PlanarFusion(t0=0.0, history=0.1)
        for m in fed:
            _feed(fusion, m)
        return fusion

    took = _batch([*fed, m1], t0=0.0)
    probe = built()
    points = delivery_points(lambda: _feed(probe, m1))
    assert points > 5
    for k in range(1, points + 1):
        fusion = built()
        interrupted_at(k, lambda f=fusion: _feed(f, m1))  # type: ignore[misc]
        assert fusion._buf[_fusion.BUF_UNDO] == 0.0
        assert 0 <= fusion._head <= len(fusion._steps)
        seen = [*fed, m1] if fusion.t == took.t else list(fed)
        _assert_same_filter(fusion, _batch(seen, t0=0.0))
        second = _feed(fusion, m2)
        if second.accepted:
            _assert_same_filter(fusion, _batch([*seen, m2], t0=0.0))
        else:
            assert second.status == FusionStatus.OUT_OF_ORDER
            _assert_same_filter(fusion, _batch(seen, t0=0.0))
