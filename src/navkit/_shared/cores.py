"""How many cores this process may use: what ``workers=None`` means everywhere."""

from __future__ import annotations

import os
import sys

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
    # Under a platform test (not a try alone) for the type checker: Windows' and
    # macOS's os have no sched_getaffinity, nor their type stubs.
    if sys.platform != "win32" and sys.platform != "darwin":
        try:
            return len(os.sched_getaffinity(0))
        except AttributeError:  # pragma: no cover - a Unix without it
            pass
    return os.cpu_count() or 1
