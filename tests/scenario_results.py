"""Comparing scenario results across runs, processes and workers (test helper)."""

from __future__ import annotations

import copy
import re
from collections.abc import Callable
from typing import Any

from navkit.sim import Scenario, ScenarioResult
from navkit.sim.scenarios import Demo, DiffAStar, Greedy, IndoorNav, OmniApf, Soccer

WALL = re.compile(r"\bwall\b")

#: Every registered scenario cut to a few seconds a trial (greedy and diff-astar
#: read the shared data folder: take the ``shared_data`` fixture).
SMALL: dict[str, Callable[[], Scenario]] = {
    "omni-apf": lambda: OmniApf(targets=[(0.0, 1.0)], duration=6.0),
    "soccer": lambda: Soccer(duration=3.0, table_cells=50),
    "diff-astar": lambda: DiffAStar(parts=("house",), duration=5.0),
    "indoor-nav": lambda: IndoorNav(targets=1, paths=1, map_source="plan"),
    "greedy": lambda: Greedy(pairs=[((-2.0, -0.5), (-1.0, -0.5))], duration=10.0),
    "demo": lambda: Demo(map="office", duration=0.5),
}


def comparable(result: ScenarioResult) -> dict[str, Any]:
    """``to_dict()`` without wall-clock measurements (the only figures allowed to differ).

    Those are each trial's ``wall_time``, values and summary entries named
    ``*_wall_time``, and table columns and rows whose heading or first cell
    holds the word ``wall``.
    """
    return comparable_dict(result.to_dict())


def comparable_dict(data: dict[str, Any]) -> dict[str, Any]:
    """:func:`comparable` of a result already in ``to_dict()`` form (a CLI's JSON, say)."""
    data = copy.deepcopy(data)
    data["summary"] = {k: v for k, v in data["summary"].items() if not k.endswith("_wall_time")}
    for trial in data["trials"]:
        del trial["wall_time"]
        trial["values"] = {k: v for k, v in trial["values"].items() if not k.endswith("_wall_time")}
    for table in data["tables"]:
        keep = [i for i, c in enumerate(table["columns"]) if not WALL.search(c)]
        table["columns"] = [table["columns"][i] for i in keep]
        table["rows"] = [
            [row[i] for i in keep]
            for row in table["rows"]
            if not (row and isinstance(row[0], str) and WALL.search(row[0]))
        ]
    return data
