"""``navkit plan MAP.yaml --start X,Y --goal X,Y``: plan on a map_server map."""

from __future__ import annotations

import argparse
import math
import os
import time
from pathlib import Path
from typing import Literal, TextIO

import numpy as np

from navkit._shared.metres import metres_text
from navkit._shared.types import FloatArray
from navkit.cli._files import write_json
from navkit.cli._kernels import announce_compilation, check_cache
from navkit.cli._outputs import check_distinct, check_output, save_picture
from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import map_image_path, read_map
from navkit.planning import MapPlanner
from navkit.sim import Scene, Table

__all__ = ["plan_command"]

PlannerName = Literal["astar", "field_dstar"]
# The table's row for Path2D.expanded: Field D* expands grid corners, not cells.
_EXPANDED_LABEL = {"astar": "cells expanded", "field_dstar": "nodes expanded"}


def _warm_up(resolution: float, radius: float, planner: PlannerName) -> None:
    """Plan once on a small grid: compiles the kernels (or loads them from the
    cache), so that the times printed are the costmap's and the search's alone."""
    occupied = np.zeros((4, 40), dtype=bool)
    # One obstacle, off the path: on an empty grid the costmap runs no obstacle-distance
    # kernel, and the first real map's costmap time held their compiling (0.9 s).
    occupied[0, 20] = True
    grid = OccupancyGrid.from_occupancy(occupied, resolution=resolution)
    inflate = min(radius, resolution)
    MapPlanner(grid, robot_radius=inflate, planner=planner).plan(
        (1.5 * resolution, 2 * resolution), (38.5 * resolution, 2 * resolution)
    )


def _check_not_an_input(option: str, output: str | None, map_yaml: str) -> None:
    """Refuse an output (``--plot``, ``--json``) naming the map's YAML or the image it names.

    ``--plot map.png`` beside ``map.yaml`` whose image is ``map.png`` would
    otherwise replace the map itself with the picture (read_map checked both).
    """
    if output is None or not os.path.exists(output):
        return
    yaml_path = Path(map_yaml)
    if os.path.exists(yaml_path) and os.path.samefile(output, yaml_path):
        raise ValueError(f"{option}: {output} is the map's YAML ({yaml_path}); choose another file")
    # The image as read_map finds it (its own reading of the YAML: UTF-32, Latin-1
    # bytes, tabs, "image: 017" as text, a name written on Windows), where a YAML
    # loader of this command's own refused an existing output for a YAML it could
    # not read (review 54, FOUND8).
    image = map_image_path(yaml_path)
    if os.path.exists(image) and os.path.samefile(output, image):
        raise ValueError(f"{option}: {output} is the map's image ({image}); choose another file")


def _in_option_names(message: str) -> str:
    """A MapPlanner message about a blocked or off-map start or goal, in the command's terms.

    The planner names its own arguments (``start``, ``robot_radius``,
    ``start_tolerance``, ``unknown_cost``, ``inflate_unknown``); the command's
    user gave ``--start``, ``--goal``, ``--radius`` and ``--start-tolerance``
    and cannot set the others (unknown space is always blocked and inflated
    here), so those asides are dropped.

    Examples
    --------
    >>> _in_option_names("goal (1.0, 2.0) (cell (20, 10)) is within robot_radius (0.5 m) of an "
    ...                  "obstacle")
    '--goal (1.0, 2.0) (cell (20, 10)) is within --radius (0.5 m) of an obstacle'
    >>> _in_option_names("no collision-free path from start (0.0, 0.0) to goal (1.0, 2.0)")
    'no collision-free path from --start (0.0, 0.0) to --goal (1.0, 2.0)'
    >>> _in_option_names("no collision-free path: obstacles grown by robot_radius=0.3 m may "
    ...                  "close every way; a smaller robot_radius may open one")
    'no collision-free path: obstacles grown by --radius 0.3 m may close every way; a smaller
     --radius may open one'
    >>> _in_option_names("start (1.0, 2.0) (cell (20, 10)) is within robot_radius (0.5 m) of an "
    ...                  "obstacle; pass start_tolerance > 0 to escape to the nearest passable "
    ...                  "cell")
    '--start (1.0, 2.0) (cell (20, 10)) is within --radius (0.5 m) of an obstacle;
     pass --start-tolerance > 0 to escape to the nearest passable cell'
    """
    for name in ("start", "goal"):
        if message.startswith(f"{name} ("):
            message = f"--{message}"
    # No path: "no collision-free path from start (...) to goal (...)".
    message = message.replace(" from start (", " from --start (").replace(
        " to goal (", " to --goal ("
    )
    message = message.replace("within robot_radius (", "within --radius (")
    # No path's hint on what may have closed every way, in the command's options:
    # "a smaller robot_radius or a finite unknown_cost" named a keyword the command
    # spells --radius and one it does not take.
    message = message.replace("obstacles grown by robot_radius=", "obstacles grown by --radius ")
    message = message.replace(" with unknown_cost=inf may close", " may close")
    message = message.replace(" or a finite unknown_cost may open one", " may open one")
    message = message.replace(
        "; a smaller robot_radius may open one", "; a smaller --radius may open one"
    )
    message = message.replace(
        "; a finite unknown_cost may open one", " (the command keeps them impassable)"
    )
    # The escape's hint ("pass start_tolerance > 0 ...") and its refusal ("within
    # start_tolerance (0.1 m)"); the library keeps naming its keyword.
    message = message.replace("start_tolerance", "--start-tolerance")
    for aside in (" (unknown_cost is inf)", " (inflate_unknown is True)"):
        message = message.replace(aside, "")
    return message


def _point_text(x: float, y: float) -> str:
    """``"(x, y)"`` in metres, each coordinate to the nanometre (``metres_text``).

    Examples
    --------
    >>> _point_text(500130.87, 4500681.73)
    '(500130.87, 4500681.73)'
    """
    return f"({metres_text(x)}, {metres_text(y)})"


def _escape_rows(
    planner: MapPlanner, start: tuple[float, float], tolerance: float, points: FloatArray
) -> tuple[tuple[str, str | float], ...]:
    """The table's rows on ``--start-tolerance``: the tolerance and, after an escape, where to.

    The planner escaped only from a start on an impassable cell (it refuses
    the others); the path then runs from ``start`` to the escape cell's centre.
    """
    if tolerance == 0.0:
        return ()
    rows: tuple[tuple[str, str | float], ...] = (("start tolerance (m)", tolerance),)
    row, col = (int(v) for v in np.asarray(planner.grid.world_to_cell(start)).reshape(2))
    if not math.isfinite(planner.costs[row, col]):
        x, y = (float(v) for v in points[1])
        rows += (("escaped to (m)", _point_text(x, y)),)
    return rows


def plan_command(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Load the map, plan, print length and time as a table, draw it and save it if asked.

    ``--json FILE`` holds the plan in world metres (``start`` and ``goal`` as
    given, ``points`` as ``[x, y]`` lists, ``length``, ``cost``,
    ``robot_radius``, ``start_tolerance``), the planner's name,
    ``cells_expanded`` (the search's expansions: cells for ``astar``, corner
    nodes for ``field_dstar``, as the table's "cells expanded" or "nodes
    expanded" row says) and the two times in ms, each point ``[x, y]`` on one
    line. The points are :meth:`MapPlanner.plan`'s: from the start given
    (linked to its cell's centre, or after an escape to the escape cell's) to
    the goal given.
    """
    check_output(args.plot, ".png", "--plot")
    check_output(args.json, "", "--json")
    check_distinct({"--plot": args.plot, "--json": args.json})
    grid = read_map(args.map)
    _check_not_an_input("--plot", args.plot, args.map)
    _check_not_an_input("--json", args.json, args.map)
    problem = check_cache(err)
    if not args.quiet:
        announce_compilation(args.planner, err, problem=problem)
    _warm_up(grid.resolution, args.radius, args.planner)
    began = time.perf_counter()
    planner = MapPlanner(grid, robot_radius=args.radius, planner=args.planner)
    prepared = time.perf_counter()
    try:
        path = planner.plan(args.start, args.goal, start_tolerance=args.start_tolerance)
    except NoPathError as exc:
        raise NoPathError(_in_option_names(str(exc)), expanded=exc.expanded) from exc
    except ValueError as exc:
        raise ValueError(_in_option_names(str(exc))) from exc
    searched = time.perf_counter()
    name = Path(args.map).name
    rows: tuple[tuple[str, str | float | int], ...] = (
        ("map", f"{name} ({grid.shape[1]} x {grid.shape[0]} cells of {grid.resolution:g} m)"),
        ("planner", args.planner),
        ("robot radius (m)", args.radius),
        ("start (m)", _point_text(*args.start)),
        *_escape_rows(planner, args.start, args.start_tolerance, path.points),
        ("goal (m)", _point_text(*args.goal)),
        ("length (m)", float(path.length)),
        ("plan time (ms)", 1e3 * (searched - prepared)),
        ("costmap time (ms)", 1e3 * (prepared - began)),
        (_EXPANDED_LABEL[args.planner], int(path.expanded)),
        ("path points", len(path.points)),
    )
    print(Table(f"navkit plan on {name}", ("", "value"), rows).render(digits=4), file=out)
    if args.plot is not None:
        scene = Scene(
            f"{args.planner} on {name}: {path.length:.2f} m",
            grid=grid,
            paths=((args.planner, path.points),),
            points=(
                ("start", np.array([args.start], dtype=np.float64)),
                ("goal", np.array([args.goal], dtype=np.float64)),
            ),
        )
        print(f"wrote {save_picture(scene, args.plot)}", file=out)
    if args.json is not None:
        data = {
            "map": args.map,
            "planner": args.planner,
            "robot_radius": args.radius,
            "start_tolerance": args.start_tolerance,
            "start": list(args.start),
            "goal": list(args.goal),
            "length": float(path.length),
            "cost": float(path.cost),
            "cells_expanded": int(path.expanded),
            "plan_time_ms": 1e3 * (searched - prepared),
            "costmap_time_ms": 1e3 * (prepared - began),
            "points": path.points.tolist(),
        }
        print(f"wrote {write_json(data, args.json, number_lists_on_one_line=True)}", file=out)
    return 0
