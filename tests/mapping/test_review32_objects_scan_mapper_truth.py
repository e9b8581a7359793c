"""A fresh ScanMapper is true (review 32, OBJECTS).

``ScanMapper`` defines ``__len__`` (the scans processed) and had no
``__bool__``, so Python took its length as its truth: a mapper was false until
its first scan. The usual test of an optional mapper, ``if self.mapper:``,
then never gave a new mapper its first scan, and ``mapper or ScanMapper()``
threw the caller's mapper (and its options) away. A mapper is an object, not
a collection: it is true; ``len(mapper)`` still counts its scans.
"""

from __future__ import annotations

import math

import numpy as np

from navkit.mapping import LaserScan, ScanMapper


def _scan() -> LaserScan:
    angles = np.linspace(-math.pi, math.pi, 90, endpoint=False)
    ranges = 2.0 / np.maximum(np.abs(np.cos(angles)), np.abs(np.sin(angles)))
    return LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / 90,
                     range_min=0.1, range_max=10.0)  # fmt: skip


class _Node:
    """A user's node with an optional mapper, tested for truth as optionals often are."""

    def __init__(self, mapper: ScanMapper | None) -> None:
        self.mapper = mapper

    def on_scan(self, scan: LaserScan) -> None:
        if self.mapper:
            self.mapper.update(scan)


def test_a_fresh_mapper_is_true_and_counts_no_scans() -> None:
    mapper = ScanMapper(resolution=0.1)
    assert bool(mapper) is True
    assert len(mapper) == 0


def test_an_optional_mapper_gets_its_first_scan() -> None:
    mapper = ScanMapper(resolution=0.1)
    node = _Node(mapper)
    node.on_scan(_scan())
    node.on_scan(_scan())
    assert len(mapper) == 2  # was 0: the fresh mapper read as "no mapper"
    assert bool(mapper) is True


def test_or_keeps_the_callers_mapper() -> None:
    mine = ScanMapper(resolution=0.2)
    assert (mine or ScanMapper()) is mine
