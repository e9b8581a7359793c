"""Comparing scenario results across runs, processes and workers (test helper)."""

from __future__ import annotations

import copy
import re
from typing import Any

from navkit.sim import ScenarioResult

WALL = re.compile(r"\bwall\b")


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
