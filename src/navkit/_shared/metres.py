"""Private text of lengths and coordinates in metres, for messages and reports.

Coordinates are printed to the nanometre, never with ``:g``'s 6 significant
digits: a map in UTM coordinates (a northing of 4.5e6 m) would read
``4.50068e+06``, metres off, and a computed cell centre's float noise
(``0.35000000000000003``) is not worth printing either.
"""

from __future__ import annotations

import math


def metres_text(value: float) -> str:
    """``value`` (m) with the fewest decimals that keep it to the nanometre.

    To the nanometre, or to one step of the float where that is coarser (at
    4.5e6 m, a UTM northing, floats are 9.3e-10 m apart); ``repr`` from 1e15
    on (no fixed-point text a thousand digits long) and for non-finite values.

    Examples
    --------
    >>> metres_text(0.35000000000000003), metres_text(4500681.725000001), metres_text(-0.0)
    ('0.35', '4500681.725', '0')
    >>> import numpy as np
    >>> metres_text(np.float64("nan"))
    'nan'
    """
    value = float(value)  # a NumPy float's repr would name its type
    if not abs(value) < 1e15:
        return repr(value)
    slack = max(5e-10, math.ulp(value))
    # Nine decimals are the nanometre whatever the test says: the float nearest to
    # the rounded text may lie 5e-10 plus its own rounding from the value (at
    # 32768.6277635715, 5.02e-10), and the search then found no decimals at all.
    decimals = next((d for d in range(9) if abs(round(value, d) - value) <= slack), 9)
    return f"{round(value, decimals) + 0.0:.{decimals}f}"  # + 0.0: no "-0"
