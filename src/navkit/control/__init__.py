"""Control: motion controllers turning goals and obstacles into velocity commands."""

from __future__ import annotations

from navkit.control._potential_field_controller import PotentialFieldController
from navkit.control._velocity_limits import limit_velocity_change

__all__ = ["PotentialFieldController", "limit_velocity_change"]
