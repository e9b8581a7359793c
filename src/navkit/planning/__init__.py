"""Planning: grid search, Field D*, potential fields and the greedy local planner.

Global planners work on per-cell traversal-cost grids indexed ``[row, col]``
(finite values >= 1, ``np.inf`` impassable): :func:`astar` and
:func:`distance_field` (8- or 4-connected cells), :class:`FieldDStar` /
:func:`field_dstar` (any-angle paths through cell corners, incremental
replanning); :func:`plan_path` runs either on a
:class:`navkit.mapping.OccupancyGrid` in world coordinates. Reactive planning
uses potential fields (attractive and repulsive field objects that add together,
:func:`repulsive_force_from_scan` straight from a laser scan), the soccer
behaviours that choose goal and repellers, and :func:`greedy_step` on a local
laser grid. Units are SI; world points are ``(x, y)``.
"""

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
