"""Planning: potential fields and grid planners."""

from navkit.planning._astar import GridPath, astar
from navkit.planning._distance_field import distance_field
from navkit.planning._field_dstar import FieldDStar, FieldPath, field_dstar
from navkit.planning._fields import (
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
from navkit.planning._greedy import GreedyStep, greedy_step
from navkit.planning._plan_path import WorldPath, plan_path
from navkit.planning._scan_forces import (
    piecewise_repulsive_force_from_scan,
    repulsive_force_from_scan,
)
from navkit.planning._soccer import BehaviourTarget, GameState, attack, defend, support

__all__ = [
    "AttractiveField",
    "BehaviourTarget",
    "BlendedAttraction",
    "CompositeField",
    "ConicAttraction",
    "FieldDStar",
    "FieldGrid",
    "FieldPath",
    "GameState",
    "GreedyStep",
    "GridPath",
    "KhatibRepulsion",
    "ParaboloidAttraction",
    "PiecewiseAttraction",
    "PiecewiseRepulsion",
    "PotentialField",
    "WorldPath",
    "astar",
    "attack",
    "defend",
    "distance_field",
    "field_dstar",
    "field_grid",
    "greedy_step",
    "piecewise_repulsive_force_from_scan",
    "plan_path",
    "repulsive_force_from_scan",
    "support",
]
