"""ScanMapper after an exception raised part-way through an update (exception safety).

Python delivers a ``KeyboardInterrupt`` (Ctrl-C stopping a mapping loop in a
notebook) as a call returns: in :meth:`ScanMapper.update` most likely as one of
its compiled kernels returns, the scan matching's or one level's ray casting.
Before session 21 an interrupt after the finest level's ray casting left the
scan in that level only, the coarse levels (which steer the matching on the
finer ones) without it, and the mapper carried on from that pyramid. Now an
update has either not taken the scan, or recorded its pose and written it into
every level; the interrupt is raised after the write.

The interrupts are injected where a user could not: the module's name of the ray
casting kernel (and of the matcher's step) is wrapped to raise once it returned.
"""

from __future__ import annotations

import copy
import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from room_scans import room_scan

from navkit.mapping import ScanMapper, ScanMatcher, _scan_mapper

_POSES = [(0.1 * k, 0.05 * k, 0.04 * k) for k in range(8)]


def _mapper(levels: int) -> ScanMapper:
    matcher = ScanMatcher(
        levels=levels, translation_weight=1.0, rotation_weight=1.0,
        search_distance=0.1, search_angle=0.1,
    )  # fmt: skip
    return ScanMapper(resolution=0.1, min_distance=0.0, min_angle=0.0, matcher=matcher)


def _state(mapper: ScanMapper) -> tuple[Any, ...]:
    """Everything an update reads or writes, comparable with ``==`` after tolist()."""
    return (
        mapper.trajectory.tolist(),
        mapper.pose,
        mapper._last_odometry,
        mapper._last_write,
        [(g.origin, g.logodds.tobytes()) for g in mapper._levels],
    )


def _levels_written(before: ScanMapper, after: ScanMapper) -> list[bool]:
    """Which map levels changed from ``before`` to ``after`` (same level shapes)."""
    return [
        not np.array_equal(a.logodds, b.logodds)
        for a, b in zip(before._levels, after._levels, strict=True)
    ]


class _InterruptAfter:
    """A stand-in for a kernel that raises ``KeyboardInterrupt`` once its ``n``-th call returned."""

    def __init__(self, kernel: Any, n: int) -> None:
        self.kernel = kernel
        self.n = n
        self.calls = 0

    def __call__(self, *args: Any) -> Any:
        out = self.kernel(*args)
        self.calls += 1
        if self.calls == self.n:
            raise KeyboardInterrupt
        return out


@pytest.mark.parametrize("levels", [2, 3])
@pytest.mark.parametrize("after_level", [1, 2])
def test_an_interrupt_after_a_level_is_written_writes_every_level_first(
    levels: int, after_level: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    mapper = _mapper(levels)
    for pose in _POSES[:4]:
        mapper.update(room_scan(*pose), odometry=pose)
    twin = copy.deepcopy(mapper)
    pose = _POSES[4]
    twin.update(room_scan(*pose), odometry=pose)
    before = copy.deepcopy(mapper)
    stub = _InterruptAfter(getattr(_scan_mapper, "integrate_beams"), after_level)  # noqa: B009
    monkeypatch.setattr(_scan_mapper, "integrate_beams", stub)
    with pytest.raises(KeyboardInterrupt):
        mapper.update(room_scan(*pose), odometry=pose)
    monkeypatch.undo()
    assert stub.calls == levels  # every level was written, the interrupt raised after
    assert _levels_written(before, mapper) == [True] * levels
    # The interrupted update is the uninterrupted one, and so are the updates after it.
    assert _state(mapper) == _state(twin)
    for pose in _POSES[5:]:
        r1 = mapper.update(room_scan(*pose), odometry=pose)
        r2 = twin.update(room_scan(*pose), odometry=pose)
        assert r1.pose == r2.pose
    assert _state(mapper) == _state(twin)


def test_an_interrupt_in_the_matching_leaves_the_mapper_as_it_was(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    mapper = _mapper(3)
    for pose in _POSES[:4]:
        mapper.update(room_scan(*pose), odometry=pose)
    before = _state(mapper)
    real = ScanMatcher._match

    def interrupted(self: ScanMatcher, *args: Any) -> Any:
        real(self, *args)
        raise KeyboardInterrupt

    monkeypatch.setattr(ScanMatcher, "_match", interrupted)
    with pytest.raises(KeyboardInterrupt):
        mapper.update(room_scan(*_POSES[4]), odometry=_POSES[4])
    assert _state(mapper) == before


def test_a_refused_write_is_raised_and_leaves_no_level_half_written(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # An exception the kernel raises itself (before writing) for every level: raised
    # once, the first level's, after all were tried; no level holds the scan.
    mapper = _mapper(3)
    mapper.update(room_scan(*_POSES[0]), odometry=_POSES[0])
    before = copy.deepcopy(mapper)
    errors: list[Exception] = []

    def refuse(*args: Any) -> None:
        errors.append(TypeError(f"refused {len(errors)}"))
        raise errors[-1]

    monkeypatch.setattr(_scan_mapper, "integrate_beams", refuse)
    with pytest.raises(TypeError, match="refused 0"):
        mapper.update(room_scan(*_POSES[1]), odometry=_POSES[1])
    assert len(errors) == 3
    assert _levels_written(before, mapper) == [False] * 3
    assert len(mapper) == 2  # the pose is recorded, as documented


@settings(max_examples=20, deadline=None, database=None)
@given(
    scans=st.integers(2, 6),
    levels=st.integers(1, 3),
    call=st.integers(1, 3),
    seed=st.integers(0, 2**16),
)
def test_an_interrupted_mapping_run_never_holds_a_scan_in_some_levels_only(
    scans: int, levels: int, call: int, seed: int
) -> None:
    rng = np.random.default_rng(seed)
    poses = [
        (float(x), float(y), float(t))
        for x, y, t in zip(
            np.cumsum(rng.uniform(-0.1, 0.2, scans)),
            np.cumsum(rng.uniform(-0.1, 0.1, scans)),
            np.cumsum(rng.uniform(-0.1, 0.1, scans)),
            strict=True,
        )
    ]
    mapper = _mapper(levels)
    for pose in poses[:-1]:
        mapper.update(room_scan(*pose), odometry=pose)
    before = copy.deepcopy(mapper)
    real = getattr(_scan_mapper, "integrate_beams")  # noqa: B009
    stub = _InterruptAfter(real, call)
    # Not the monkeypatch fixture: hypothesis runs many examples per test call.
    setattr(_scan_mapper, "integrate_beams", stub)  # noqa: B010
    try:
        try:
            mapper.update(room_scan(*poses[-1]), odometry=poses[-1])
            interrupted = False
        except KeyboardInterrupt:
            interrupted = True
    finally:
        setattr(_scan_mapper, "integrate_beams", real)  # noqa: B010
    assert interrupted == (call <= levels)
    written = _levels_written(before, mapper) if len(before._levels) else [True]
    assert all(written) or not any(written)
    assert len(mapper) == scans
    assert math.isfinite(mapper.pose.x)
