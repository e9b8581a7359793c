"""The ``navkit`` command line (``navkit ...`` or ``python -m navkit ...``).

* ``navkit demo`` — a robot plans, tracks and localises on a real office map
  (Willow Garage; a synthetic office built in code when no data is found) and
  prints a results table (seconds once navkit's kernels are compiled).
* ``navkit list`` — the experiments.
* ``navkit run SCENARIO [--trials N] [--seed S] [--plot FILE.png]
  [--animate FILE.gif] [--json FILE] [--workers N] [--scheduler ADDRESS]
  [--data DIR] [--quiet]`` — one paper's experiment, navkit's figures beside
  the paper's; trials in parallel on local processes or a Dask cluster.
* ``navkit plan MAP.yaml --start X,Y --goal X,Y [--planner astar|field_dstar]
  [--radius R] [--start-tolerance METRES] [--plot FILE.png] [--json FILE]`` —
  a path on any ROS map_server map (points also as its table prints them,
  ``"(X, Y)"``); with ``--start-tolerance``, a start within ``R`` of an
  obstacle or unknown space (a drifted position estimate) first moves straight
  to the nearest passable cell centre within ``METRES`` (default 0: refused);
  ``--json`` holds the path's points, length and cost.
* ``navkit warmup [--only STEP] [--workers N] [--quiet]`` — compile every
  numba kernel now (once per install), print what was compiled.
* ``navkit --version``.

``navkit --help`` and each ``navkit COMMAND --help`` end with examples.
Bad arguments print the usage and exit with code 2; a mistyped name (a
command, scenario, planner, map or warm-up step) is answered with the closest
one (``navkit run omni``: "maybe you meant 'omni-apf'?"), and an option the
command does not have with the command's own usage and its closest option
(``navkit demo --trail 3``: "maybe you meant '--trials'?"). A missing,
unreadable or malformed file, map or data set prints one line ``navkit:
error: ...`` and exits with code 1, as do output files that cannot be
written, two options naming one file, ``--json -`` (standard output carries
the tables: give a file), an output naming the map's own files and a
``--data`` that is not a folder (without ``--scheduler``; all checked before
a run starts), and a failed write to standard output (``standard output: No
space left on device``).
Ctrl-C exits with code 130 (``SIGTERM`` and ``SIGHUP`` with 143 and 129, after
the same clean-up: worker processes stopped, no temporary files left), in one
line; a standard output closed early (``navkit list | head -1``, once the
output outgrows the pipe's buffer) ends the command quietly with code 141.
Progress (trials done, ETA) is drawn on standard error when it is a terminal
and a run lasts more than about 2 s; the first run, which compiles navkit's
kernels, says so.

Examples
--------
>>> main(["--version"])  # doctest: +ELLIPSIS
navkit ...
0
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

__all__ = ["main"]


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``navkit`` command.

    The command's modules (numba, scipy, the simulator: about a second) are
    imported here rather than when ``navkit.cli`` is: a Ctrl-C while they load,
    right after the command starts, then ends it like any other interrupt.

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments after the program name (default ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit code: 0 on success, 1 when a file, map or data set is missing
        or malformed (or no path exists), 2 on bad arguments (with a usage
        message), 130 when interrupted (143 on ``SIGTERM``, 129 on ``SIGHUP``),
        141 (silently) when standard output is closed early (``navkit list |
        head -1``).

    Raises
    ------
    TypeError
        ``argv`` is not a sequence of str.

    Examples
    --------
    >>> main(["list"])  # doctest: +ELLIPSIS
    navkit's experiments (navkit run SCENARIO)
    ...
    0
    """
    try:
        from navkit.cli._app import main as run
    except KeyboardInterrupt:
        sys.stderr.write("navkit: interrupted\n")
        return 130
    return run(argv)
