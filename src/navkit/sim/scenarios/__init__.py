"""The source papers' experiments, reproduced in :mod:`navkit.sim`.

Each scenario is a :class:`~navkit.sim.Scenario` subclass: construct it with its
options (keyword-only), then :meth:`~navkit.sim.Scenario.run` it, or hand it to
:func:`~navkit.sim.sweep` to spread its trials over processes or a Dask cluster.
The result's :meth:`~navkit.sim.ScenarioResult.table` puts navkit's figures
beside the paper's.

========================  ==========================================================
``OmniApf`` (omni-apf)    3-wheel omni robot, compass-fused odometry, piecewise
                          potential field on LiDAR beams
``IndoorNav``             map from simulated scans, EKF wheel odometry + IMU, Field D*
(indoor-nav)              against A*, ON-OFF tracking in a 14.4 × 12 m lab
``Soccer`` (soccer)       blended-sigmoid attraction, Khatib repulsion, attack /
                          support / defence against moving opponents
``DiffAStar``             differential delivery robot: A* + follow-the-carrot in a
(diff-astar)              three-room house and along a 32 m building route
``Greedy`` (greedy)       TurtleBot3 Burger, greedy step on a 21 × 21 laser grid
``Demo`` (demo)           plan, track and estimate on a real map in seconds
========================  ==========================================================
"""

from __future__ import annotations

from navkit.sim import Scenario
from navkit.sim.scenarios._data import find_data
from navkit.sim.scenarios._demo import Demo
from navkit.sim.scenarios._diff_astar import DiffAStar
from navkit.sim.scenarios._greedy import Greedy
from navkit.sim.scenarios._indoor_nav import IndoorNav
from navkit.sim.scenarios._omni_apf import OmniApf
from navkit.sim.scenarios._soccer import Soccer

__all__ = [
    "SCENARIOS",
    "Demo",
    "DiffAStar",
    "Greedy",
    "IndoorNav",
    "OmniApf",
    "Soccer",
    "find_data",
    "get_scenario",
]

SCENARIOS: dict[str, type[Scenario]] = {
    cls.name: cls for cls in (OmniApf, IndoorNav, Soccer, DiffAStar, Greedy, Demo)
}
"""Every scenario class by its command-line name (``"omni-apf"``, ...)."""


def get_scenario(name: str) -> type[Scenario]:
    """The scenario class of a command-line name.

    Parameters
    ----------
    name : str
        One of :data:`SCENARIOS` (``"omni-apf"``, ``"indoor-nav"``, ...).

    Returns
    -------
    type of Scenario
        The class; construct it with its options.

    Raises
    ------
    ValueError
        For an unknown name (the message lists the known ones).

    Examples
    --------
    >>> get_scenario("omni-apf").__name__
    'OmniApf'
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be a str, got {type(name).__name__}")
    try:
        return SCENARIOS[name]
    except KeyError:
        known = ", ".join(sorted(SCENARIOS))
        raise ValueError(f"name: unknown scenario {name!r}; known: {known}") from None
