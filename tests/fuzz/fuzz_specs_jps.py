"""Fuzz kinds of the jump point search option (registered on import by ``fuzz_specs.py``).

``astar`` and ``AStarPlanner`` gained the keyword ``method`` ("astar", "jps",
"auto"); their specs live in ``fuzz_specs.py`` and are completed here with the
kind of that option (a ``str`` annotation gives the fuzzer no kind). On the
fuzzed grids of varying cost ``"jps"`` must raise its documented ValueError
and ``"auto"`` falls back to A*.
"""

from __future__ import annotations

from fuzz_engine import SPECS, Choice

METHOD = Choice("astar", "jps", "auto")

for _name in ("navkit.planning.grid.astar", "navkit.planning.grid.AStarPlanner"):
    SPECS[_name].kinds["method"] = METHOD
