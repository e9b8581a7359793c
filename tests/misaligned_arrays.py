"""Arrays whose data is not aligned for their dtype, for the compiled paths' tests.

A NumPy array may start at any byte of its buffer (``np.frombuffer`` at an
offset, a packed structured array's field); numba's compiled code must then
read it without assuming alignment, or a copy must be made. Review 46's points
and cost-grid tests each wrote this maker again (review 47).
"""

from __future__ import annotations

import numpy as np


def misaligned(a: np.ndarray, *, writeable: bool = True) -> np.ndarray:
    """A copy of ``a`` (same dtype and shape, C order) in a buffer at byte offset 1."""
    raw = bytearray(a.nbytes + a.itemsize + 1)
    out = np.frombuffer(raw, dtype=a.dtype, count=a.size, offset=1).reshape(a.shape)
    out[...] = a
    out.flags.writeable = writeable
    assert out.size == 0 or not out.flags.aligned
    return out
