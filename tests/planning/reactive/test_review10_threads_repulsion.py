"""The scan repulsion's shared beam tables under threads with different scanners.

``_scan_repulsion`` keeps module-level caches (``_TABLES`` and the last table,
``_LAST``) without a lock. The fast path must read ``_LAST`` once into a local
and both check and use that snapshot: a version that checks the global and
then reads it again can take the cosines of another thread's scanner (same
increment and beam count, another ``angle_min``) stored in between. The
interleavings are forced here deterministically, by a scan subclass whose
attribute reads run another scanner's call, and then tried for real with
threads released together at a tiny switch interval.
"""

from __future__ import annotations

import math
import sys
import threading
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np
import pytest

import navkit.planning.reactive._scan_repulsion as scan_repulsion
from navkit.mapping import LaserScan
from navkit.planning import (
    KhatibRepulsion,
    piecewise_repulsive_force_from_scan,
    repulsive_force_from_scan,
)


def _scan(n: int, angle_min: float, increment: float, seed: int) -> LaserScan:
    ranges = np.random.default_rng(seed).uniform(0.05, 3.0, n)
    return LaserScan(
        ranges, angle_min=angle_min, angle_increment=increment, range_min=0.01, range_max=10.0
    )


def _khatib(scan: LaserScan) -> bytes:
    return repulsive_force_from_scan(scan, influence_radius=2.0).tobytes()


def _piecewise(scan: LaserScan) -> bytes:
    return piecewise_repulsive_force_from_scan(scan, obstacle_radius=0.2, spread=1.5).tobytes()


FORCES: dict[str, Callable[[LaserScan], bytes]] = {"khatib": _khatib, "piecewise": _piecewise}


# The tables are built from LaserScan's own angles (a subclass's override is not
# read: see test_review23_fresh2_repulsion_subclass.py), which read the scan's
# attributes from this code.
_ANGLES_CODE = LaserScan.angles.__code__


class _Interrupting(LaserScan):
    """A scan that runs ``interrupt()`` at the first read of ``attribute``, as a thread switch.

    ``"angles"``: at the first read while the beam angles are computed, which is
    while a table is being built.
    """

    attribute = ""
    interrupt: Callable[[], object] | None = None
    interrupted = False

    def __getattribute__(self, name: str) -> Any:
        cls = type(self)
        if cls.interrupt is not None and (
            name == cls.attribute
            or (cls.attribute == "angles" and sys._getframe(1).f_code is _ANGLES_CODE)
        ):
            interrupt, cls.interrupt = cls.interrupt, None
            interrupt()
            cls.interrupted = True
        return super().__getattribute__(name)


@pytest.fixture
def interrupting() -> Iterator[type[_Interrupting]]:
    yield _Interrupting
    _Interrupting.attribute = ""
    _Interrupting.interrupt = None
    _Interrupting.interrupted = False


def _forget_tables() -> None:
    scan_repulsion._TABLES.clear()
    scan_repulsion._LAST = (0.0, 0.0, 0, np.empty((2, 0)))


def _as_interrupting(scan: LaserScan) -> _Interrupting:
    return _Interrupting(
        scan.ranges,
        angle_min=scan.angle_min,
        angle_increment=scan.angle_increment,
        range_min=scan.range_min,
        range_max=scan.range_max,
    )


@pytest.mark.parametrize("force", sorted(FORCES))
@pytest.mark.parametrize(
    "attribute", ["ranges", "angle_min", "angle_increment", "range_min", "range_max", "angles"]
)
def test_another_scanner_between_the_table_check_and_its_use_changes_nothing(
    interrupting: type[_Interrupting], force: str, attribute: str
) -> None:
    call = FORCES[force]
    mine = _scan(60, -1.0, 0.03, seed=1)
    # Same increment and beam count, another first angle: only the cosines differ.
    other = _scan(60, 0.4, 0.03, seed=2)
    expected = call(mine)
    scan = _as_interrupting(mine)
    for warm in (True, False):  # this scanner's table is the last one, or not cached at all
        _forget_tables()
        if warm:
            call(mine)
        interrupting.attribute = attribute
        interrupting.interrupt = lambda: call(other)
        interrupting.interrupted = False
        assert call(scan) == expected
        # The hook ran (angles() is read only when the table is built).
        assert interrupting.interrupted or (attribute == "angles" and warm)
        # The cache the interruption left behind serves both scanners correctly.
        assert call(mine) == expected
        assert call(other) == FORCES[force](other)


def test_a_full_table_cache_cleared_while_a_table_is_built_changes_nothing(
    interrupting: type[_Interrupting],
) -> None:
    mine = _scan(40, 0.1, 0.05, seed=3)
    expected = {name: call(mine) for name, call in FORCES.items()}
    others = [_scan(40, -0.5 - 0.01 * k, 0.05, seed=4) for k in range(scan_repulsion._TABLES_MAX)]
    scan = _as_interrupting(mine)
    for name, call in FORCES.items():
        _forget_tables()
        interrupting.attribute = "angles"  # read only when the table is being built
        # Fills the cache to its bound, so that this scan's insertion clears it.
        interrupting.interrupt = lambda: [_khatib(o) for o in others]
        interrupting.interrupted = False
        assert call(scan) == expected[name]
        assert interrupting.interrupted
        assert len(scan_repulsion._TABLES) <= scan_repulsion._TABLES_MAX
        assert call(mine) == expected[name]


def _geometries() -> list[LaserScan]:
    # More geometries than the cache holds (it is cleared while threads use it),
    # in pairs that share increment and beam count, both increment signs.
    rng = np.random.default_rng(5)
    scans = []
    for k in range(scan_repulsion._TABLES_MAX + 8):
        n = int(rng.integers(1, 200))
        increment = (1 if k % 4 < 2 else -1) * float(rng.uniform(0.001, math.pi / max(n, 2)))
        for angle_min in (-1.5, 1.0 + 0.001 * k):
            scans.append(_scan(n, angle_min, increment, seed=k))
    return scans


def test_threads_with_different_scanners_get_the_serial_results_bit_for_bit() -> None:
    scans = _geometries()

    def forces(scan: LaserScan) -> tuple[bytes, ...]:
        field = KhatibRepulsion(scan.to_points(), influence_radius=2.0)
        return _khatib(scan), _piecewise(scan), field.force((0.0, 0.0)).tobytes()

    serial = [forces(s) for s in scans]
    threads = 4
    barrier = threading.Barrier(threads)
    wrong: list[tuple[int, int]] = []
    errors: list[BaseException] = []

    def worker(t: int) -> None:
        try:
            barrier.wait()
            for _ in range(3):
                for j in range(len(scans)):
                    k = (j * (2 * t + 1) + t) % len(scans)
                    if forces(scans[k]) != serial[k]:
                        wrong.append((t, k))
        except BaseException as exc:  # pragma: no cover - reported below
            errors.append(exc)

    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)
    try:
        workers = [threading.Thread(target=worker, args=(t,)) for t in range(threads)]
        for w in workers:
            w.start()
        for w in workers:
            w.join()
    finally:
        sys.setswitchinterval(interval)
    assert not errors
    assert not wrong
    assert len(scan_repulsion._TABLES) <= scan_repulsion._TABLES_MAX + threads
