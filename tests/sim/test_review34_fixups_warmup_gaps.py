"""After ``navkit warmup``, the command's own runs compile nothing (issue 17).

A systematic check of this session (a fresh ``NUMBA_CACHE_DIR``, ``navkit
warmup``, then ``navkit demo``, every ``navkit run SCENARIO --trials 1``,
``navkit plan`` and every page of the docs in new processes, each numba compile
counted) found two gaps besides the one fixed earlier today
(``world_to_cell(continuous=True)``'s batch kernel):

* the diff-astar scenario's localiser (``match_scan``) was in no step: every
  first ``navkit run diff-astar`` compiled it. The new ``scenarios`` step runs
  half a second of its house route;
* ``greedy_step`` on a laser grid with a return in the robot's own cell (the
  greedy scenario meets it) freed that cell in a writable copy, so
  ``greedy_select`` (and its ``line_is_free``) compiled again for writable
  arrays; the copy is now read-only, as ``LocalGrid.occupied`` is.

``ExtendedKalmanFilter``'s kernels are specialised per state and measurement
size (the warm-up compiles n = 3, m = 1 and 2; the estimation guide's 2-state
filter compiles its own): documented in ``warmup`` and ``docs/compilation.md``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from navkit.sim import WARMUP_STEPS

ROOT = Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared" / "data"

# Registers a listener of numba's compile events (not cache loads), runs the given
# navkit commands in this process, prints the kernels compiled as JSON.
_COUNTED = textwrap.dedent(
    """
    import json, sys
    import numba
    from numba.core import event

    compiled = []

    class Listener(event.Listener):
        def on_start(self, ev):
            pass

        def on_end(self, ev):
            f = ev.data["dispatcher"].py_func
            compiled.append(f"{f.__module__}.{f.__qualname__}")

    event.register("numba:compile", Listener())
    from navkit.cli import main

    for command in json.loads(sys.argv[1]):
        code = main(command)
        assert code == 0, (command, code)
    print(json.dumps(compiled))
    """
)


def test_the_scenarios_step_warms_the_diff_astar_localiser() -> None:
    assert "scenarios" in WARMUP_STEPS
    # In a fresh process: one that already ran the scenario holds the kernel in
    # memory, and the step then neither compiles nor loads it.
    script = (
        "import json\n"
        "from navkit.sim import warmup\n"
        "report = warmup(workers=1, only=['scenarios'])\n"
        "print(json.dumps(sorted(set(report.compiled) | set(report.loaded))))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=900,
        env={**os.environ, "PYTHONWARNINGS": "ignore"},
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    kernels = json.loads(done.stdout.strip().splitlines()[-1])
    assert "navkit.sim.scenarios._diff_astar_kernels.match_scan" in kernels


# The reactive step in a fresh process (its kernels load from the suite's cache, or
# compile), then greedy_step on a grid with a return in the robot's own cell.
_GREEDY = textwrap.dedent(
    """
    import json
    import numpy as np
    from navkit.mapping import LocalGrid
    from navkit.planning import greedy_step
    from navkit.planning.reactive import _greedy_kernels as kernels
    from navkit.sim import _warmup

    _warmup._STEPS["reactive"][0]()
    warmed = {str(s) for s in kernels.greedy_select.signatures}
    grid = LocalGrid.from_points(np.array([[0.01, -0.02], [0.5, 0.3]]))  # one in its cell
    step = greedy_step(grid, (1.5, 0.5))
    used = {str(s) for s in kernels.greedy_select.signatures}
    print(json.dumps([sorted(warmed), sorted(used - warmed), list(step.cell)]))
    """
)


def test_a_return_in_the_robots_cell_needs_no_other_greedy_kernel() -> None:
    done = subprocess.run(
        [sys.executable, "-c", _GREEDY], capture_output=True, text=True, timeout=900,
        env={**os.environ, "PYTHONWARNINGS": "ignore"},
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    warmed, extra, cell = json.loads(done.stdout.strip().splitlines()[-1])
    assert warmed, "the reactive step never reached greedy_select"
    assert extra == [], extra  # a writable copy compiled greedy_select again
    assert cell != [10, 10]  # the step moved: the robot's own cell was freed


def test_greedy_step_leaves_the_grid_as_it_was() -> None:
    # The freed copy is read-only; the caller's grid is untouched either way.
    import numpy as np

    from navkit.mapping import LocalGrid
    from navkit.planning import greedy_step

    grid = LocalGrid.from_points(np.array([[0.01, -0.02]]))
    before = grid.occupied.copy()
    centre = grid.size // 2
    assert before[centre, centre]
    greedy_step(grid, (1.5, 0.5))
    np.testing.assert_array_equal(grid.occupied, before)


@pytest.mark.slow
def test_after_navkit_warmup_the_commands_compile_nothing(tmp_path: Path) -> None:
    if not SHARED.is_dir():
        pytest.skip(f"the scenarios' maps are in {SHARED}, which is absent")
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env.update(NUMBA_CACHE_DIR=str(tmp_path / "cache"), NAVKIT_DATA=str(SHARED),
               MPLBACKEND="Agg", PYTHONWARNINGS="ignore")  # fmt: skip
    warm = subprocess.run(
        [sys.executable, "-m", "navkit", "warmup"], env=env, capture_output=True, text=True,
        timeout=3600,
    )  # fmt: skip
    assert warm.returncode == 0, warm.stderr[-3000:]
    tb3 = str(SHARED / "ros-map-server-maps" / "turtlebot3_world" / "map.yaml")
    plan = ["plan", tb3, "--start", "-2,-0.5", "--goal", "2,0.5", "--quiet"]
    commands = [
        ["demo", "--quiet"],
        *(["run", name, "--trials", "1", "--workers", "1", "--quiet"]
          for name in ("diff-astar", "greedy", "indoor-nav", "omni-apf", "soccer")),
        plan,
        [*plan, "--planner", "field_dstar", "--radius", "0.2", "--start-tolerance", "0.5"],
        [*plan, "--radius", "0.2", "--start-tolerance", "0.5"],
    ]  # fmt: skip
    done = subprocess.run(
        [sys.executable, "-c", _COUNTED, json.dumps(commands)], env=env, capture_output=True,
        text=True, cwd=tmp_path, timeout=3600,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    compiled = json.loads(done.stdout.strip().splitlines()[-1])
    assert [k for k in compiled if k.startswith("navkit.")] == []
