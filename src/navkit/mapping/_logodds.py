"""Log-odds conventions of the occupancy grids (private).

``logit`` and the probability clipping used to turn probabilities into log-odds,
map_server's classification thresholds, and OctoMap's sensor model (the default
log-odds increments of ray casting and their clamping bounds).

Examples
--------
>>> round(logit(0.7), 6), round(DEFAULT_HIT, 6)
(0.847298, 0.847298)
>>> P_MIN, P_MAX
(0.001, 0.999)
"""

from __future__ import annotations

import math

__all__ = [
    "DEFAULT_CLAMP",
    "DEFAULT_FREE_THRESH",
    "DEFAULT_HIT",
    "DEFAULT_MISS",
    "DEFAULT_OCCUPIED_THRESH",
    "P_MAX",
    "P_MIN",
    "logit",
    "logit_bound",
]


def logit(p: float) -> float:
    """Log-odds ``log(p / (1 - p))`` of a probability strictly between 0 and 1.

    Examples
    --------
    >>> logit(0.5)
    0.0
    """
    return math.log(p / (1.0 - p))


def logit_bound(p: float) -> float:
    """As :func:`logit`, with ``-inf`` for ``p <= 0`` and ``+inf`` for ``p >= 1``.

    Used to compare log-odds against probability thresholds that may be 0 or 1.

    Examples
    --------
    >>> logit_bound(0.0), logit_bound(1.0)
    (-inf, inf)
    """
    if p <= 0.0:
        return -math.inf
    if p >= 1.0:
        return math.inf
    return logit(p)


#: Probabilities are clipped to [P_MIN, P_MAX] before taking log-odds so that
#: certain cells (p = 0 or 1, as in map files) stay finite (about ±6.9).
P_MIN = 1e-3
P_MAX = 1.0 - 1e-3
#: OctoMap's sensor model (prob_hit 0.7, prob_miss 0.4, clamping 0.12 / 0.97).
DEFAULT_HIT = logit(0.7)
DEFAULT_MISS = logit(0.4)
DEFAULT_CLAMP = (logit(0.12), logit(0.97))
#: map_server's default thresholds.
DEFAULT_OCCUPIED_THRESH = 0.65
DEFAULT_FREE_THRESH = 0.196
