"""Reactive navigation: potential fields, per-beam scan repulsion, the greedy grid step.

Fields map world points ``(x, y)`` (m) to a potential and a force and add
together; :func:`repulsive_force_from_scan` sums repulsion straight from a laser
scan; :func:`greedy_step` picks the next cell on a robot-centred laser grid.
Units are SI.
"""

from navkit.planning.reactive._fields import (
    AttractiveField,
    BlendedAttraction,
    CompositeField,
    ConicAttraction,
    FieldGrid,
    KhatibRepulsion,
    ParaboloidAttraction,
    PiecewiseAttraction,
    PiecewiseRepulsion,
    PotentialField,
    field_grid,
)
from navkit.planning.reactive._greedy import GreedyStep, greedy_step
from navkit.planning.reactive._scan_repulsion import (
    piecewise_repulsive_force_from_scan,
    repulsive_force_from_scan,
)

__all__ = [
    "AttractiveField",
    "BlendedAttraction",
    "CompositeField",
    "ConicAttraction",
    "FieldGrid",
    "GreedyStep",
    "KhatibRepulsion",
    "ParaboloidAttraction",
    "PiecewiseAttraction",
    "PiecewiseRepulsion",
    "PotentialField",
    "field_grid",
    "greedy_step",
    "piecewise_repulsive_force_from_scan",
    "repulsive_force_from_scan",
]
