"""Reactive navigation: potential fields, per-beam scan repulsion, the greedy grid step.

Fields map world points ``(x, y)`` (m) to a potential and a force and add
together (``field_a + field_b``, ``sum(fields)``); :func:`sample_field` samples
one on a grid; :func:`repulsive_force_from_scan` sums repulsion straight from a
laser scan; :func:`greedy_step` picks the next cell on a robot-centred laser grid.
Units are SI.
"""

from __future__ import annotations

from navkit.planning.reactive._attraction import (
    AttractiveField,
    BlendedAttraction,
    ConicAttraction,
    ParaboloidAttraction,
    PiecewiseAttraction,
)
from navkit.planning.reactive._greedy import GreedyStep, greedy_step
from navkit.planning.reactive._potential_field import CompositeField, PotentialField
from navkit.planning.reactive._repulsion import KhatibRepulsion, PiecewiseRepulsion
from navkit.planning.reactive._sampling import SampledField, sample_field
from navkit.planning.reactive._scan_repulsion import (
    piecewise_repulsive_force_from_scan,
    repulsive_force_from_scan,
)

__all__ = [
    "AttractiveField",
    "BlendedAttraction",
    "CompositeField",
    "ConicAttraction",
    "GreedyStep",
    "KhatibRepulsion",
    "ParaboloidAttraction",
    "PiecewiseAttraction",
    "PiecewiseRepulsion",
    "PotentialField",
    "SampledField",
    "greedy_step",
    "piecewise_repulsive_force_from_scan",
    "repulsive_force_from_scan",
    "sample_field",
]
