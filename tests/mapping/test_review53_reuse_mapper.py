"""One ScanMatcher shared by mappers, and matchers reused across maps (review 53, REUSE).

ScanMapper's docstring promises that different mappers may share one
:class:`ScanMatcher` "which keeps only its options". A robot process keeps one
matcher for hours: two maps built at once (two robots, or a map and a
re-localisation attempt), interleaved scan by scan through one matcher, must
each be the map a mapper with a matcher of its own builds, bit for bit (every
match result, the trajectory and the log-odds); and a match against a map after
matches against other maps must be a fresh matcher's.
"""

from __future__ import annotations

from typing import Any

from shapely.geometry import box

from navkit.mapping import LaserScan, ScanMapper, ScanMatcher
from navkit.sim import Lidar, World

_WORLD = World([box(0.0, 0.0, 6.0, 4.0).exterior, box(2.0, 1.0, 2.5, 1.5), box(4.2, 2.6, 4.6, 3.4)])
_LIDAR = Lidar(n_beams=120, range_max=5.0, noise=None)


def _scans(x: float, y: float, dx: float, dy: float, turn: float) -> list[LaserScan]:
    return [_LIDAR.scan(_WORLD, (x + dx * k, y + dy * k, turn * k)) for k in range(12)]


_FIRST = _scans(1.0, 1.0, 0.1, 0.05, 0.1)
_SECOND = _scans(4.0, 3.0, -0.1, -0.05, -0.08)


def _result(result: Any) -> tuple[Any, ...]:
    return (result.pose, result.covariance.tobytes(), result.iterations, result.score,
            result.converged, result.reason)  # fmt: skip


def _map(mapper: ScanMapper) -> tuple[Any, ...]:
    grid = mapper.map
    return mapper.trajectory.tobytes(), grid.logodds.tobytes(), grid.origin, grid.shape


def test_mappers_sharing_a_matcher_build_what_each_builds_alone() -> None:
    shared = ScanMatcher()
    first = ScanMapper(matcher=shared, pose=(1.0, 1.0, 0.0))
    second = ScanMapper(matcher=shared, pose=(4.0, 3.0, 0.0))
    got_first, got_second = [], []
    for a, b in zip(_FIRST, _SECOND, strict=True):
        got_first.append(_result(first.update(a)))
        got_second.append(_result(second.update(b)))
    for mapper, scans, start, got in (
        (first, _FIRST, (1.0, 1.0, 0.0), got_first),
        (second, _SECOND, (4.0, 3.0, 0.0), got_second),
    ):
        alone = ScanMapper(matcher=ScanMatcher(), pose=start)
        assert got == [_result(alone.update(scan)) for scan in scans]
        assert _map(mapper) == _map(alone)


def test_a_matcher_reused_across_maps_matches_as_a_fresh_one() -> None:
    maps = []
    for scans, start in ((_FIRST, (1.0, 1.0, 0.0)), (_SECOND, (4.0, 3.0, 0.0))):
        mapper = ScanMapper(pose=start)
        for scan in scans:
            mapper.update(scan)
        maps.append(mapper.map)
    reused = ScanMatcher(levels=2)
    guesses = [(1.05, 1.0, 0.02), (3.9, 2.9, -0.05), (2.0, 2.5, 0.3)]
    scan = _LIDAR.scan(_WORLD, (2.0, 2.5, 0.3))
    for grid in maps + maps[::-1]:
        for guess in guesses:
            got = _result(reused.match(grid, scan, guess))
            assert got == _result(ScanMatcher(levels=2).match(grid, scan, guess))
