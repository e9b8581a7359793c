"""Two small grid defects (session 39, SMALLS).

* ``OccupancyGrid(cells)`` with a nested list of bools got no hint to use
  ``from_occupancy``, where a bool array did.
* With ``NUMBA_DISABLE_JIT=1`` (kernels run as Python) and ``np.seterr(all="raise")``,
  ``world_to_cell`` of an infinite point raised ``FloatingPointError`` (and under the
  default ``"warn"`` emitted a ``RuntimeWarning``) instead of the compiled path's
  ``ValueError`` naming ``points_xy``.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from navkit.mapping import OccupancyGrid

_HINT = "OccupancyGrid.from_occupancy(mask, resolution=...)"


@pytest.mark.parametrize(
    "cells",
    [
        np.array([[True, False]]),
        [[True, False]],
        ((True, False), (False, False)),
        [[np.True_, np.False_]],
        [[True, 0.5]],  # a bool mixed in: still refused, with the same advice
        [np.array([True, False])],
    ],
)
def test_every_boolean_mask_names_from_occupancy(cells: object) -> None:
    with pytest.raises(TypeError, match=r"logodds must hold real numbers") as info:
        OccupancyGrid(cells, resolution=0.1)  # type: ignore[arg-type]
    assert str(info.value).endswith(_HINT)


def test_other_bad_cells_get_no_mask_hint() -> None:
    # The hint is for booleans only: strings and complex numbers keep their messages.
    for cells in ([["a", "b"]], [[1.0, 2j]]):
        with pytest.raises(TypeError, match="logodds") as info:
            OccupancyGrid(cells, resolution=0.1)  # type: ignore[arg-type]
        assert "from_occupancy" not in str(info.value)
    # Real numbers in nested lists are log-odds as before.
    grid = OccupancyGrid([[0.0, 1.5]], resolution=0.1)
    assert grid.logodds.tolist() == [[0.0, 1.5]]


_PYTHON_KERNELS = textwrap.dedent(
    """
    import warnings
    import numpy as np
    from navkit.mapping import OccupancyGrid

    warnings.simplefilter("error")  # a RuntimeWarning from NumPy scalars is a failure
    grid = OccupancyGrid.empty(width=2.0, height=2.0, resolution=0.5)
    for mode in ("raise", "warn"):
        np.seterr(all=mode)
        bads = ([[np.inf, 0.0]], [[0.0, -np.inf]], [[np.nan, 0.0]], [[1.0, 1.0], [np.inf, np.nan]])
        for bad in bads:
            try:
                grid.world_to_cell(np.array(bad))
            except ValueError as exc:
                assert "points_xy" in str(exc), exc
            else:
                raise AssertionError(f"no error for {bad}")
        assert grid.world_to_cell(np.array([[0.7, 0.2], [1e300, -1e300]])).tolist() == [
            [0, 1], [-(2**62), 2**62]
        ]
    print("ok")
    """
)


def test_python_kernels_refuse_infinite_points_as_compiled(tmp_path: object) -> None:
    # NUMBA_DISABLE_JIT is read when numba is imported: a fresh process.
    env = dict(os.environ, NUMBA_DISABLE_JIT="1", NUMBA_CACHE_DIR=str(tmp_path))
    done = subprocess.run(
        [sys.executable, "-c", _PYTHON_KERNELS],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == "ok"
