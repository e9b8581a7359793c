"""Control: motion controllers turning goals and obstacles into velocity commands."""

from navkit.control._potential_controller import (
    PotentialFieldController,
    limit_velocity_change,
)

__all__ = ["PotentialFieldController", "limit_velocity_change"]
