"""How many cores this process may use: what ``workers=None`` means everywhere."""

from __future__ import annotations

import os

__all__ = ["usable_cores"]


def usable_cores() -> int:
    """Cores this process may run on: what ``workers=None`` means to ``sweep`` and ``warmup``.

    Its CPU affinity where the system has one (Linux: a container's or
    ``taskset``'s share of the machine), else every core.

    Examples
    --------
    >>> usable_cores() >= 1
    True
    """
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not on Linux
        return os.cpu_count() or 1
