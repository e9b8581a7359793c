"""repulsive_force_from_scan's shared beam-direction tables and LaserScan subclasses.

Found by the second fresh-eyes review of session 27: the tables are shared by
every scan of one geometry (beam count, ``angle_min``, ``angle_increment``) but
were built from ``scan.angles()``, so a subclass overriding ``angles`` put its
directions into the table that plain scans of that geometry then used (a plain
8-beam scan at 0.5 m all round, whose force is about 0, got (-32, 0) after such a
subclass's call). The tables are now built from LaserScan's own angles.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import navkit.planning.reactive._scan_repulsion as repulsion
from navkit.mapping import LaserScan
from navkit.planning import piecewise_repulsive_force_from_scan, repulsive_force_from_scan

_GEOMETRY = {
    "angle_min": -math.pi + 0.125,
    "angle_increment": 2.0 * math.pi / 8,
    "range_min": 0.0,
    "range_max": 5.0,
}


class _AllAhead(LaserScan):
    """A scan subclass whose ``angles`` says every beam points straight ahead."""

    __slots__ = ()

    def angles(self) -> np.ndarray:
        return np.zeros(len(self.ranges))


def _forces(scan: LaserScan) -> tuple[bytes, bytes]:
    return (
        repulsive_force_from_scan(scan, influence_radius=1.0).tobytes(),
        piecewise_repulsive_force_from_scan(scan, delta=1.0, beta=1.0).tobytes(),
    )


@pytest.mark.parametrize("subclass_first", [True, False])
def test_a_subclass_overriding_angles_does_not_change_plain_scans(
    monkeypatch: pytest.MonkeyPatch, subclass_first: bool
) -> None:
    monkeypatch.setattr(repulsion, "_TABLES", {})
    monkeypatch.setattr(repulsion, "_LAST", (0.0, 0.0, 0, np.empty((2, 0))))
    ranges = np.full(8, 0.5)
    plain = LaserScan(ranges, **_GEOMETRY)
    odd = _AllAhead(ranges, **_GEOMETRY)
    angles = LaserScan.angles(plain)
    weight = (1.0 / 0.5 - 1.0) / 0.5**2
    want = -weight * np.array([np.cos(angles).sum(), np.sin(angles).sum()])
    if subclass_first:
        _forces(odd)
    got = repulsive_force_from_scan(plain, influence_radius=1.0)
    assert np.allclose(got, want, atol=1e-12)  # about 0: the beams cancel
    # Both scans use the one table of their geometry: the same forces, bit for bit.
    assert _forces(plain) == _forces(odd)
    assert np.allclose(repulsive_force_from_scan(odd, influence_radius=1.0), want, atol=1e-12)
