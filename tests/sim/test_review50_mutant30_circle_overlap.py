"""Review 50 (MUTANT30): a footprint across a circle's boundary has clearance 0.

``World.clearance`` is 0 when the footprint touches or overlaps an obstacle's
boundary, never negative. The disc-to-circle distance outside the circle is
``max(d - radius - r, 0)`` (``max2`` since review 50, SIMCOLD); a mutant
without the clamp (a negative clearance for a disc straddling the boundary
from outside) survived the suite. A disc straddling a pillar's or a circular
wall's boundary, from outside its centre's circle, has clearance exactly 0.
"""

from __future__ import annotations

import pytest

from navkit.sim import Circle, World


@pytest.mark.parametrize("solid", [True, False], ids=["pillar", "circular-wall"])
@pytest.mark.parametrize("offset", [1.05, 1.2, 1.29])
def test_a_disc_across_the_boundary_from_outside_has_no_negative_clearance(
    solid: bool, offset: float
) -> None:
    # A circle of radius 1 at the origin; a disc of radius 0.3 centred just outside
    # it: the boundary crosses the disc.
    world = World([Circle((0.0, 0.0), 1.0, solid=solid)])
    assert world.clearance(0.3, (offset, 0.0, 0.0)) == 0.0
    assert world.clearance(0.3, (0.0, -offset, 1.0)) == 0.0
    # Clear of it: the gap itself.
    assert world.clearance(0.3, (1.5, 0.0, 0.0)) == pytest.approx(0.2, abs=1e-12)
