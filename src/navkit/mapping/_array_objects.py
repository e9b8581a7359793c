"""Formerly the object types of world_to_cell's fast path: now in navkit._shared.array_objects.

Kept only so that numba cache indexes written while the types lived here
still load: numba unpickles a cache index (whose keys name each argument
type's module) before checking that it is stale. Importing it imports numba.
"""

from __future__ import annotations

from navkit._shared.array_objects import *  # noqa: F403
from navkit._shared.array_objects import LAYOUT_OK, NewPyObject, PyObjectArg

__all__ = ["LAYOUT_OK", "NewPyObject", "PyObjectArg"]
