"""``limit_velocity_change`` names each refused limit first, then its range in its unit (review 32).

Mutants swapping the name and the unit given to the range check (``quantity(max_accel,
"m/s²", "max_accel")``, and so for ``max_decel`` and ``dt``) survived: the tests
matched the name anywhere in the message, and the swapped message ("m/s² must
be in [1e-06, 1e+06] max_accel") still holds it. Oracle: the docstring's
ranges and units (``max_accel``, ``max_decel`` in [1e-6, 1e6] m/s², ``dt`` in
[1e-6, 1e6] s). Checked: each case fails on its mutant of
``_velocity_limits.py`` and passes on HEAD.
"""

from __future__ import annotations

import re

import pytest

from navkit.control import limit_velocity_change


@pytest.mark.parametrize(
    ("name", "unit"), [("max_accel", "m/s²"), ("max_decel", "m/s²"), ("dt", "s")]
)
@pytest.mark.parametrize("value", [0.0, 2e6, -1.0])
def test_a_refused_limit_is_named_with_its_range_and_unit(
    name: str, unit: str, value: float
) -> None:
    limits = {"max_accel": 1.0, "max_decel": 1.0, "dt": 0.1, name: value}
    expected = f"{name} must be in [1e-06, 1e+06] {unit}, got {value!r}"
    with pytest.raises(ValueError, match=f"^{re.escape(expected)}$"):
        limit_velocity_change([0.0, 0.0], [1.0, 0.0], **limits)
