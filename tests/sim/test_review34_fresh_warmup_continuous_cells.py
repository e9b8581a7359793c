"""``navkit warmup`` compiles the batch kernel of ``world_to_cell(continuous=True)``.

The mapping step called it on one point, which ``world_to_cell`` computes in
Python since review 20's "single points in Python": after a full warm-up a
fresh process's first ``world_to_cell(points, continuous=True)`` on two or more
points compiled ``world_to_continuous_kernel`` (0.1-0.3 s, in a control loop
or a planner's first escape). A fresh-eyes review of review 33's warm-up of
the new ``cell_to_world`` kernels found it.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

# Runs the mapping step in a fresh process (the kernels then load from the cache the
# suite uses, or compile), then lists the signatures of the batch kernel it loaded.
_SCRIPT = textwrap.dedent(
    """
    import numpy as np
    from navkit.mapping import OccupancyGrid
    from navkit.mapping import _grid_kernels as kernels
    from navkit.sim import _warmup

    kernel = kernels.world_to_continuous_kernel
    _warmup._STEPS["mapping"][0]()
    warmed = [str(s) for s in kernel.signatures]
    grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.1)
    grid.world_to_cell(np.array([[0.3, 0.4], [1.0, 1.5], [2.0, 0.5]]), continuous=True)
    used = [str(s) for s in kernel.signatures]
    print(len(warmed), len(used), all(u in warmed for u in used))
    """
)


def _run(env: dict[str, str]) -> list[str]:
    done = subprocess.run(
        [sys.executable, "-c", _SCRIPT], env=env, capture_output=True, text=True, timeout=900
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout.split()


def test_the_mapping_step_compiles_the_batch_continuous_kernel() -> None:
    warmed, used, covered = _run(dict(os.environ))
    assert int(warmed) >= 1  # one point alone never reached the kernel
    assert covered == "True", (warmed, used)  # a batch call needs no other signature


@pytest.mark.slow
def test_after_the_mapping_step_a_fresh_process_compiles_nothing_for_it(tmp_path: Path) -> None:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    warm = "from navkit.sim import warmup; warmup(workers=1, only=['mapping'])"
    subprocess.run([sys.executable, "-c", warm], env=env, check=True, timeout=1800)
    check = textwrap.dedent(
        """
        import numpy as np
        from navkit.mapping import OccupancyGrid
        from navkit.mapping import _grid_kernels as kernels

        grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.1)
        grid.world_to_cell(np.array([[0.3, 0.4], [1.0, 1.5]]), continuous=True)
        print(sum(kernels.world_to_continuous_kernel.stats.cache_misses.values()))
        """
    )
    done = subprocess.run(
        [sys.executable, "-c", check], env=env, capture_output=True, text=True, timeout=900
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout.split()[-1] == "0"  # loaded from the warm cache, not compiled
