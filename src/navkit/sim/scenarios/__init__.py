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

import importlib
import sys
from typing import TYPE_CHECKING, Any

from navkit.sim import Scenario
from navkit.sim.scenarios._data import find_data

if TYPE_CHECKING:
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

#: Each scenario's command-line name: its class and the module defining it. A
#: scenario's module (and what it needs: shapely, scipy, the controllers) is
#: imported when its class is first asked for, so that ``navkit run greedy``
#: does not pay for the other five (issue 17).
_REGISTRY: dict[str, tuple[str, str]] = {
    "omni-apf": ("OmniApf", "navkit.sim.scenarios._omni_apf"),
    "indoor-nav": ("IndoorNav", "navkit.sim.scenarios._indoor_nav"),
    "soccer": ("Soccer", "navkit.sim.scenarios._soccer"),
    "diff-astar": ("DiffAStar", "navkit.sim.scenarios._diff_astar"),
    "greedy": ("Greedy", "navkit.sim.scenarios._greedy"),
    "demo": ("Demo", "navkit.sim.scenarios._demo"),
}
_MODULES = dict(_REGISTRY.values())

SCENARIOS: dict[str, type[Scenario]]
"""Every scenario class by its command-line name (``"omni-apf"``, ...).

A scenario of your own added here (``SCENARIOS["mine"] = Mine``, a
:class:`~navkit.sim.Scenario` subclass) is found by :func:`get_scenario`
and by :func:`~navkit.sim.sweep` given its name, in this process; an entry
removed is no longer found.
"""


def __getattr__(name: str) -> Any:
    """The scenario classes and :data:`SCENARIOS`, imported on first use (PEP 562)."""
    if name == "SCENARIOS":
        value: Any = {scenario: get_scenario(scenario) for scenario in _REGISTRY}
    elif name in _MODULES:
        value = getattr(importlib.import_module(_MODULES[name]), name)
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value  # later look-ups find it without calling this function
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})


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
    TypeError
        For a name that is not a str, or an entry added to :data:`SCENARIOS`
        that is not a Scenario subclass.

    Examples
    --------
    >>> get_scenario("omni-apf").__name__
    'OmniApf'
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be a str, got {type(name).__name__}")
    # SCENARIOS exists only once asked for: only then can a user have changed it,
    # and until then the registry answers without importing every scenario's module.
    scenarios: dict[str, type[Scenario]] | None = globals().get("SCENARIOS")
    if scenarios is None:
        if name not in _REGISTRY:
            known = ", ".join(sorted(_REGISTRY))
            raise ValueError(f"name: unknown scenario {name!r}; known: {known}")
        cls: type[Scenario] = getattr(sys.modules[__name__], _REGISTRY[name][0])
        return cls
    if name not in scenarios:
        known = ", ".join(sorted(map(str, scenarios)))
        raise ValueError(f"name: unknown scenario {name!r}; known: {known}")
    found: object = scenarios[name]
    if not (isinstance(found, type) and issubclass(found, Scenario)):
        raise TypeError(
            f"SCENARIOS[{name!r}] must be a Scenario subclass, got {found!r} "
            f"({type(found).__name__})"
        )
    return found
