"""Array type aliases used across navkit (private)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, SupportsIndex

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
"""A float64 array."""

IntArray = NDArray[np.int64]
"""An int64 array."""

BoolArray = NDArray[np.bool_]
"""A boolean array."""

CellLike = Sequence[SupportsIndex] | NDArray[np.integer[Any]]
"""A grid cell ``(row, col)`` as the planners take it: two Python or NumPy integers,
or an integer array of shape (2,) (what ``world_to_cell`` returns for one point)."""

RealScalar = float | np.integer[Any] | np.floating[Any]
"""One real number, as the scalar overloads of the public functions take it: a Python
``int`` or ``float`` or a NumPy integer or floating scalar (every one returns a Python
``float`` for it, as for a 0-d array). ``np.bool_`` is neither, and refused."""

IntScalar = int | np.integer[Any]
"""One integer, as :func:`navkit.kinematics.tick_delta`'s scalar overload takes it: a
Python ``int`` or a NumPy integer scalar (the result is a Python ``int``)."""

KernelInt = int | np.int64
"""An integer argument of a numba kernel: a Python ``int`` or a ``np.int64``.

Kernels pass some counters as ``np.int64`` on purpose (a literal would make
numba compile the callee once more), and reading an int64 array gives one."""
