"""Documented parameter ranges of navkit.control and their check (private).

Lengths (m), speeds (m/s), accelerations (m/s²), turn rates (rad/s), times (s)
and the heading integral bound (rad·s) are in [1e-6, 1e6]; the PID gains in
[0, 1e12]; the repulsion gain ``k_rep`` in [1e-12, 1e12]; positions (robot,
goal, obstacles) have ``|x|, |y| <= 1e9`` m, the range of navkit.planning's
fields. Within these ranges no controller quantity can overflow float64.
"""

from __future__ import annotations

from typing import Any

from navkit._shared.validation import finite_float

__all__ = [
    "MAX_COORDINATE",
    "MAX_GAIN",
    "MAX_QUANTITY",
    "MIN_GAIN",
    "MIN_QUANTITY",
    "in_range",
    "position",
    "quantity",
]

MIN_QUANTITY = 1e-6
MAX_QUANTITY = 1e6
MIN_GAIN = 1e-12
MAX_GAIN = 1e12
MAX_COORDINATE = 1e9


def in_range(value: Any, name: str, low: float, high: float, unit: str = "") -> float:
    """Return ``value`` as a float in [low, high] or raise naming ``name`` and the range."""
    out = finite_float(value, name)
    if not low <= out <= high:
        suffix = f" {unit}" if unit else ""
        # The value exactly (repr): :g rounded 1e6 + 0.01 to "1e+06", inside the range.
        raise ValueError(f"{name} must be in [{low:g}, {high:g}]{suffix}, got {out!r}")
    return out


def quantity(value: Any, name: str, unit: str) -> float:
    """A physical limit, length or time: a float in [MIN_QUANTITY, MAX_QUANTITY]."""
    return in_range(value, name, MIN_QUANTITY, MAX_QUANTITY, unit)


def position(x: float, y: float, name: str) -> None:
    """Raise naming ``name`` unless ``|x|, |y| <= MAX_COORDINATE`` (finite floats given)."""
    if not (abs(x) <= MAX_COORDINATE and abs(y) <= MAX_COORDINATE):
        raise ValueError(
            f"{name}: positions must have |x|, |y| <= {MAX_COORDINATE:g} m, got ({x!r}, {y!r})"
        )
