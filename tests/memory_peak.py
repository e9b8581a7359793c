"""Peak memory of one call, for the tests that bound navkit's memory use (shared)."""

from __future__ import annotations

import tracemalloc
from collections.abc import Callable
from typing import Any


def peak_bytes(call: Callable[[], Any]) -> tuple[int, Any]:
    """Peak bytes allocated (tracemalloc) while ``call`` runs, its result included, and the result.

    ``call`` runs once before, untraced: first-call allocations of imports and
    caches are not what the tests bound.
    """
    call()
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        result = call()
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    return peak, result
