"""Private: whether a robot is at its goal position, the one test of every controller.

``PotentialFieldController`` (its ``done``), ``FollowTheCarrot``,
``OnOffTracker`` (its waypoints too) and ``RegulatedPurePursuit`` all decide
"within ``goal_tolerance``" with :func:`~navkit._shared.goal.at_goal`, exact at
the boundary. It lives in :mod:`navkit._shared.goal`, where the simulator's run
kernels take it too (compiled), so that a run counts the goal as reached
exactly where the controller is done (review 48).
"""

from __future__ import annotations

from navkit._shared.goal import at_goal, resolution

__all__ = ["at_goal", "resolution"]
