"""Reactive navigation: potential fields, per-beam scan repulsion, the greedy grid step.

Fields map world points ``(x, y)`` (m) to a potential and a force and add
together (``field_a + field_b``, ``sum(fields)``); :func:`sample_field` samples
one on a grid; :func:`repulsive_force_from_scan` sums repulsion straight from a
laser scan; :func:`greedy_step` picks the next cell on a robot-centred laser grid.
Units are SI.

Ranges: world points (goals, obstacles, query points, sampling windows) within
``±1e9`` m; gains in ``[1e-12, 1e12]``; lengths (semi-axes, widths, spreads,
``influence_radius``) in ``[1e-6, 1e6]`` m, offset radii (``threshold_radius``,
``goal_radius``, ``obstacle_radius``) in ``[0, 1e6]`` m; :func:`sample_field` at
most ``2**26`` cells. Inside them forces are always finite and potentials too,
except ``+inf`` exactly on a :class:`KhatibRepulsion` obstacle (whose push
saturates below 1e-9 m). Bad input raises ``ValueError`` or ``TypeError``
naming the argument; :func:`greedy_step` with no feasible cell
:class:`navkit.NoPathError`.
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
