"""Documented parameter ranges of navkit.kinematics and their check (private).

Lengths (track width, wheel radii, base radius) are in [1e-6, 1e6] m: from a
micro-robot to far beyond any vehicle, and with ratios of at most 1e12 every
kinematic matrix stays well conditioned and far from overflow. Encoder
resolutions are in [1, 1e12] counts per revolution.
"""

from __future__ import annotations

from typing import Any

from navkit._shared.validation import finite_float

__all__ = ["MAX_LENGTH", "MAX_TICKS_PER_REV", "MIN_LENGTH", "MIN_TICKS_PER_REV", "in_range"]

MIN_LENGTH = 1e-6
MAX_LENGTH = 1e6
MIN_TICKS_PER_REV = 1.0
MAX_TICKS_PER_REV = 1e12


def in_range(value: Any, name: str, low: float, high: float, unit: str) -> float:
    """Return ``value`` as a float in [low, high] or raise naming ``name`` and the range."""
    out = finite_float(value, name)
    if not low <= out <= high:
        raise ValueError(f"{name} must be in [{low:g}, {high:g}] {unit}, got {out!r}")
    return out
