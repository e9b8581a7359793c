"""Misaligned points on ``world_to_cell``'s compiled fast path (review 46, JPSMUT).

Review 45's mutant "ao77" declared :data:`navkit._shared.array_objects.POINTS`
(the view :func:`~navkit._shared.array_objects.float_pairs` gives
``world_to_cell``'s kernel) an aligned array, and no test noticed. A
misaligned float64 array does reach that view: ``float_pairs`` tests the
type, shape, strides, dtype and byte order, not the alignment, on purpose
(the view is declared unaligned, so reading the caller's buffer in place,
without a copy, is defined). Declared aligned, numba emits its loads with
LLVM's ``align 8``, which is undefined behaviour on an address that is 1
modulo 8: x86-64 and AArch64 execute such loads as unaligned ones, the same
values (so every result stayed right, and the mutant lived), but LLVM may
assume the low address bits are zero. The tests pin both halves: the fast
path takes the misaligned buffer itself, and its compiled code assumes no
alignment of it.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np
import pytest

from misaligned_arrays import misaligned
from navkit._shared.jit import jit_disabled
from navkit.geometry import Pose2D
from navkit.mapping import OccupancyGrid
from navkit.mapping._new_cells_kernel import new_cells_entry, world_to_new_cells

pytestmark = pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: no compiled fast path")


def test_misaligned_points_take_the_fast_path_with_the_aligned_cells() -> None:
    """The compiled entry accepts the buffer itself (None would send it the general
    way, which converts) and reads the cells its aligned copy gives."""
    grid = OccupancyGrid.empty(width=5.0, height=4.0, resolution=0.1, origin=Pose2D(-1, -2, 0.3))
    points = np.random.default_rng(46).uniform(-10, 10, size=(37, 2))
    o = grid.origin
    want = new_cells_entry()(points, o.x, o.y, o.theta, grid.resolution)
    assert want is not None
    odd = misaligned(points, writeable=False)
    got = new_cells_entry()(odd, o.x, o.y, o.theta, grid.resolution)
    assert got is not None
    np.testing.assert_array_equal(got, want)
    np.testing.assert_array_equal(grid.world_to_cell(odd), want)
    np.testing.assert_array_equal(odd, points)


def test_the_fast_path_reads_the_points_assuming_no_alignment() -> None:
    """Every load of float64 in the compiled fast path (scalar or vector: the loads
    of the points) is ``align 1``; with the points' type declared aligned they were
    ``align 8``, undefined on the misaligned buffers it takes."""
    import numba
    from numba import types

    from navkit._shared.array_objects import OBJECT

    # A fresh, uncached compilation: numba's cache keeps machine code, not the IR.
    fresh: Any = getattr(numba, "njit")(  # noqa: B009 (numba's stubs lack the option)
        world_to_new_cells.py_func,  # type: ignore[attr-defined]
        no_cfunc_wrapper=True,
    )
    signature = (OBJECT, *(types.float64,) * 4)
    fresh.compile(signature)
    loads = re.findall(r"load (?:double|<\d+ x double>), ptr [^,]+, align (\d+)",
                       fresh.inspect_llvm(signature))  # fmt: skip
    assert loads, "no float64 loads found: the IR's form changed"
    assert set(loads) == {"1"}, loads
