"""Fuzz specs of navkit.mapping's scan matcher and mapper (imported by ``fuzz_specs.py``).

Tiny maps and scans (a 2 m room at 0.1 m, 12 beams) keep every call fast.
"""

from __future__ import annotations

import math

import numpy as np
from fuzz_engine import Array, Call, Choice, Obj, Real, call, method, spec

from navkit.geometry import Pose2D
from navkit.mapping import LaserScan, OccupancyGrid, ScanMapper, ScanMatcher, ScanMatchResult
from navkit.mapping._scan_matcher import REASONS

A = np.array
P = "navkit.mapping."


def room() -> Call:
    occupied = np.zeros((20, 20), dtype=bool)
    occupied[0, :] = occupied[-1, :] = occupied[:, 0] = occupied[:, -1] = True
    occupied[5:8, 12:15] = True
    return call(OccupancyGrid.from_occupancy, occupied, resolution=0.1)


def scan() -> Call:
    ranges = A([0.85, 0.9, 1.1, 0.95, 0.9, 0.85, 0.9, 1.0, 1.2, 0.9, 0.95, 0.8])
    return call(
        LaserScan,
        ranges,
        angle_min=-math.pi,
        angle_increment=math.pi / 6,
        range_min=0.05,
        range_max=5.0,
    )


def matcher() -> Call:
    return call(ScanMatcher, levels=2, max_iterations=5, search_distance=0.2, search_angle=0.3)


def mapper() -> Call:
    return call(ScanMapper, resolution=0.1, pose=Pose2D(1.0, 1.0, 0.0), matcher=matcher())


spec(
    P + "ScanMatcher",
    lambda c: matcher(),
    kinds={"levels": Real(integer=True), "max_iterations": Real(integer=True)},
)
spec(P + "ScanMatcher.pyramid", lambda c: method(matcher(), "pyramid", room()))
spec(
    P + "ScanMatcher.match",
    lambda c: method(matcher(), "match", room(), scan(), A([1.0, 1.0, 0.1])),
    kinds={"maps": Obj(OccupancyGrid)},
    inf_ok="documented: infinite variances when no match could be made",
)
spec(
    P + "ScanMatchResult",
    lambda c: call(ScanMatchResult, Pose2D(0.0, 0.0, 0.0), np.eye(3), 3, 0.5, True, "converged"),
    kinds={
        "covariance": Array(allow={"posinf"}),
        "iterations": Real(integer=True),
        "converged": Choice(True, False),
        "reason": Choice(*REASONS),
    },
)
spec(
    P + "ScanMapper",
    lambda c: mapper(),
    kinds={"matcher": Obj(ScanMatcher, optional=True), "clamp": Array()},
)
spec(
    P + "ScanMapper.update",
    lambda c: method(mapper(), "update", scan(), A([0.0, 0.0, 0.0])),
    mutates=("self",),
    inf_ok="documented: infinite variances when no match could be made (the first scan)",
)
