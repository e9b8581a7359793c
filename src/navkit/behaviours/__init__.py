"""Behaviours: application logic that chooses what the controllers pursue.

The wheeled soccer robot's roles (attack, support, defend) map a
:class:`GameState` to a :class:`BehaviourTarget` — a goal point and the points
that repel — for any planner or controller (e.g.
:class:`navkit.control.PotentialFieldController`). World points are ``(x, y)`` in
metres.

Ranges: positions are finite (NaN rows mark players not seen);
``possession_radius`` in [1e-6, 1e6] m. Records copy their arrays.
"""

from __future__ import annotations

from navkit.behaviours._soccer import BehaviourTarget, GameState, attack, defend, support

__all__ = ["BehaviourTarget", "GameState", "attack", "defend", "support"]
