"""A ScanMapper takes one update at a time: another thread's or a signal handler's is refused.

A mapper keeps its map and trajectory between updates and is documented as
used by one thread at a time. A signal handler's update inside an update of
the main thread (or another thread's) ran both on the same state without an
error: both matched from the guess made before either recorded its pose, the
rows of the trajectory were taken in either order (one written over the
other), and the scans were written into the map at the wrong poses (391 of
the 1552 points of the update below left poses and a map that neither order
of the two updates gives, among them a scan at 0.1 m recorded at 0.246 m).
An update now refuses to start while another is under way (``RuntimeError``
saying whose), changes nothing, and the update under way goes on as alone; a
guard of half a microsecond on an update of milliseconds (review 37, GUARD2).

The interleavings are forced: a profile hook runs the second update at every
point where CPython runs a signal handler (``interrupt_points.DELIVERY``).
"""

from __future__ import annotations

import copy
import math
import pickle
import time
from typing import Any

import numpy as np

from interrupt_points import interleaved
from navkit.mapping import LaserScan, ScanMapper
from thread_runs import run_switching_often


def _room_scan(x: float, y: float, beams: int = 90) -> LaserScan:
    """A scan from (x, y), heading 0, in the 6 m x 4 m room centred on the origin."""
    ranges = []
    for a in np.linspace(-math.pi, math.pi, beams, endpoint=False):
        c, s = math.cos(a), math.sin(a)
        tx = (3 - x) / c if c > 1e-9 else (-3 - x) / c if c < -1e-9 else math.inf
        ty = (2 - y) / s if s > 1e-9 else (-2 - y) / s if s < -1e-9 else math.inf
        ranges.append(min(tx, ty))
    return LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / beams,
                     range_min=0.1, range_max=10.0)  # fmt: skip


def _state(mapper: ScanMapper) -> tuple[Any, ...]:
    # Every level of the pyramid, where they lie and what they hold.
    levels = [(g.origin, g.shape, g._logodds.tobytes()) for g in mapper._levels]
    return len(mapper), mapper.trajectory.tobytes(), levels


SCAN_A, ODOM_A = _room_scan(0.1, 0.0), (0.1, 0.0, 0.0)
SCAN_B, ODOM_B = _room_scan(0.2, 0.05), (0.2, 0.05, 0.0)


def _base() -> ScanMapper:
    mapper = ScanMapper(resolution=0.1, min_distance=0.0)
    mapper.update(_room_scan(0.0, 0.0), odometry=(0.0, 0.0, 0.0))
    return mapper


def test_a_handlers_update_at_every_point_of_an_update_is_refused_or_taken_whole() -> None:
    base = _base()
    a_only = copy.deepcopy(base)
    a_only.update(SCAN_A, odometry=ODOM_A)
    orders = []
    for first, second in (
        ((SCAN_A, ODOM_A), (SCAN_B, ODOM_B)),
        ((SCAN_B, ODOM_B), (SCAN_A, ODOM_A)),
    ):
        both = copy.deepcopy(base)
        both.update(first[0], odometry=first[1])
        both.update(second[0], odometry=second[1])
        orders.append(_state(both))
    probe = copy.deepcopy(base)
    first = interleaved(
        0, lambda: probe.update(SCAN_A, odometry=ODOM_A), lambda: None, catch_main=False
    )
    points = first["points"]
    assert points > 50
    refused = 0
    for k in range(1, points + 1):
        mapper = copy.deepcopy(base)
        out = interleaved(
            k,
            lambda m=mapper: m.update(SCAN_A, odometry=ODOM_A),  # type: ignore[misc]
            lambda m=mapper: m.update(SCAN_B, odometry=ODOM_B),  # type: ignore[misc]
            catch_main=False,
        )
        assert mapper._callers == []
        if "h" not in out:  # fewer points this time
            assert _state(mapper) == _state(a_only)
        elif isinstance(out["h"], RuntimeError):
            refused += 1
            assert "ScanMapper.update was called during this ScanMapper's own update" in str(
                out["h"]
            )
            assert _state(mapper) == _state(a_only), k
            assert out["m"].pose == a_only.pose
        else:
            assert _state(mapper) in orders, k
    assert refused > points // 2


def test_copies_and_pickles_of_a_mapper_in_use_are_not_in_use() -> None:
    mapper = _base()
    copies: list[ScanMapper] = []

    def take() -> None:
        copies.extend((copy.copy(mapper), copy.deepcopy(mapper)))
        copies.append(pickle.loads(pickle.dumps(mapper)))
        assert mapper._callers  # in use: the copies are taken inside the update

    probe = copy.deepcopy(mapper)
    first = interleaved(
        0, lambda: probe.update(SCAN_A, odometry=ODOM_A), lambda: None, catch_main=False
    )
    points = first["points"]
    interleaved(points // 2, lambda: mapper.update(SCAN_A, odometry=ODOM_A), take, catch_main=False)
    assert len(copies) == 3
    for other in copies:
        assert other._callers == []
        other.update(SCAN_B, odometry=ODOM_B)
    # The pickled state holds no callers list: pickles are as before the guard.
    assert "_callers" not in mapper.__getstate__()[1]


def test_two_threads_on_one_mapper_take_whole_updates_or_the_refusal() -> None:
    mapper = _base()
    scans = [(_room_scan(0.01 * i, 0.0, beams=45), (0.01 * i, 0.0, 0.0)) for i in range(1, 40)]
    outcomes: list[list[str]] = [[], []]

    def run(k: int) -> None:
        deadline = time.monotonic() + 120.0
        for scan, odom in scans[k::2]:
            # Until taken: a refusal is quick, the other thread's update takes
            # milliseconds (tens of thousands of refusals).
            while time.monotonic() < deadline:
                try:
                    mapper.update(scan, odometry=odom)
                except RuntimeError as error:
                    outcomes[k].append("refused" if "another thread" in str(error) else repr(error))
                    continue
                outcomes[k].append("taken")
                break

    run_switching_often(run)
    for seen in outcomes:
        assert set(seen) <= {"taken", "refused"}, sorted(set(seen))
    # Every scan taken is a row of the trajectory, none lost or written over.
    assert sum(seen.count("taken") for seen in outcomes) == len(scans)
    assert len(mapper) == len(scans) + 1
    assert np.isfinite(mapper.trajectory).all()
    assert mapper._callers == []
