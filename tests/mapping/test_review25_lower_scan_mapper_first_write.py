"""ScanMapper interrupted during its ray casting kernel's first call (review 25, lower layers).

``ScanMapper.update`` promises that an interrupted update has written its scan
into every map level or none. The levels are written by one compiled kernel,
called once per level, and an interrupt delivered as a call returns is held
until every level is written. But the kernel's first call in a process runs
Python before the kernel does (numba loads it from its cache or compiles it,
for up to seconds): a Ctrl-C there raised before the finest level was written,
and the coarser levels were then written without it. The first call is now
made before any level, on a one-cell grid; an interrupt in it leaves every
level unwritten.

The interrupt is injected where a user's lands, in a stand-in for numba's
first dispatch: the module's name of the kernel raises before its first call
runs the kernel.
"""

from __future__ import annotations

import copy
from typing import Any

import numpy as np
import pytest
from room_scans import room_scan

from navkit.mapping import ScanMapper, ScanMatcher, _scan_mapper


class _InterruptedDispatch:
    """The kernel, whose first call raises ``KeyboardInterrupt`` before running it."""

    def __init__(self, kernel: Any) -> None:
        self.kernel = kernel
        self.calls = 0
        self.ran = 0

    def __call__(self, *args: Any) -> Any:
        self.calls += 1
        if self.calls == 1:
            raise KeyboardInterrupt  # while numba loads the kernel
        self.ran += 1
        return self.kernel(*args)


def _mapper(levels: int) -> ScanMapper:
    matcher = ScanMatcher(levels=levels, translation_weight=1.0, rotation_weight=1.0)
    return ScanMapper(resolution=0.1, min_distance=0.0, min_angle=0.0, matcher=matcher)


@pytest.mark.parametrize("levels", [1, 2, 3])
@pytest.mark.parametrize("scans_before", [0, 2])
def test_an_interrupt_in_the_kernels_first_dispatch_writes_no_level(
    levels: int, scans_before: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    poses = [(0.1 * k, 0.05 * k, 0.04 * k) for k in range(scans_before + 2)]
    mapper = _mapper(levels)
    for pose in poses[:scans_before]:
        mapper.update(room_scan(*pose), odometry=pose)
    before = copy.deepcopy(mapper)
    pose = poses[scans_before]
    stub = _InterruptedDispatch(_scan_mapper.integrate_beams)
    monkeypatch.setattr(_scan_mapper, "integrate_beams", stub)
    monkeypatch.setattr(_scan_mapper, "_KERNEL_CALLED", [False])  # a fresh process
    with pytest.raises(KeyboardInterrupt):
        mapper.update(room_scan(*pose), odometry=pose)
    assert stub.ran == 0  # no level written, none left behind the others
    assert len(mapper) == scans_before + 1  # the pose is recorded, as documented
    for got, was in zip(mapper._levels, before._levels, strict=False):
        if got.shape == was.shape:
            np.testing.assert_array_equal(got.logodds, was.logodds)
    if scans_before == 0:
        assert not any(level.logodds.any() for level in mapper._levels)
    # The next scan is written into every level, after the first call made again.
    changed = [level.logodds.copy() for level in mapper._levels]
    pose = poses[scans_before + 1]
    mapper.update(room_scan(*pose), odometry=pose)
    assert stub.ran == 1 + levels
    assert all(
        not np.array_equal(level.logodds, old)
        for level, old in zip(mapper._levels, changed, strict=True)
    )


def test_the_first_call_is_made_once_per_process(monkeypatch: pytest.MonkeyPatch) -> None:
    mapper = _mapper(3)
    calls: list[int] = []
    real = _scan_mapper.integrate_beams

    def counted(*args: Any) -> Any:
        calls.append(len(args[8]))  # the beams given
        return real(*args)

    monkeypatch.setattr(_scan_mapper, "integrate_beams", counted)
    monkeypatch.setattr(_scan_mapper, "_KERNEL_CALLED", [False])
    for k in range(3):
        mapper.update(room_scan(0.2 * k, 0.0, 0.0), odometry=(0.2 * k, 0.0, 0.0))
    beams = calls[1]
    # One call without beams before the first write, then one per level and write.
    assert calls == [0] + [beams] * 9
