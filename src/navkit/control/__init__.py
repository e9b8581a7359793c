"""Control: motion controllers turning goals and obstacles into velocity commands.

Ranges of :class:`PotentialFieldController` and :func:`limit_velocity_change`:
lengths, speeds, accelerations, turn rates, times (including ``dt``) and the
heading-integral bound in [1e-6, 1e6] (SI units); PID gains in [0, 1e12];
``k_rep`` in [1e-12, 1e12]; positions ``|x|, |y| <= 1e9`` m (as navkit.planning's
fields); velocities any finite numbers.
"""

from __future__ import annotations

from navkit.control._follow_the_carrot import FollowTheCarrot
from navkit.control._on_off_tracker import OnOffTracker
from navkit.control._potential_field_controller import PotentialFieldController
from navkit.control._regulated_pure_pursuit import RegulatedPurePursuit
from navkit.control._velocity_limits import limit_velocity_change

__all__ = [
    "FollowTheCarrot",
    "OnOffTracker",
    "PotentialFieldController",
    "RegulatedPurePursuit",
    "limit_velocity_change",
]
