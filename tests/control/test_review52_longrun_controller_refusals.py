"""A long-running node's controllers after a refused message and after a reset (review 52, LONGRUN).

A tracker or a potential-field controller kept for hours gets, now and then, a
bad pose, time step, path, obstacle set or measured velocity. The call is
refused with a clear exception and the controller goes on as if it had never
come: every later command is bit for bit a twin's that never saw it. After a
long run, a tracker given a new path and a controller ``reset()`` command as
new ones do.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.control import (
    FollowTheCarrot,
    OnOffTracker,
    PotentialFieldController,
    RegulatedPurePursuit,
)
from navkit.mapping import LaserScan

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from refused_twin import offer

_BAD = [math.nan, math.inf, -1.0, 0.0, 1e308, "0.1", None, [1.0, 2.0], np.zeros((2, 2)), 1 + 1j,
        (0.0, 0.0, math.nan), np.array([np.nan, 0.0])]  # fmt: skip
_PATH = np.column_stack([np.linspace(0.0, 5.0, 50), 0.3 * np.sin(np.linspace(0.0, 3.0, 50))])
_BACK = np.column_stack([np.linspace(0.0, -4.0, 40), 0.1 * np.cos(np.linspace(0.0, 3.0, 40))])
_SCAN = LaserScan(np.random.default_rng(3).uniform(0.3, 3.0, 72), angle_min=-math.pi,
                  angle_increment=2 * math.pi / 72, range_min=0.05, range_max=5.0)  # fmt: skip


def _track(tracker: Any, seed: int, n: int, low: float = -1.0, high: float = 5.0) -> list[bytes]:
    rng = np.random.default_rng(seed)
    return [tracker.step(tuple(rng.uniform(low, high, 3)), 0.05).as_array().tobytes()
            for _ in range(n)]  # fmt: skip


@pytest.mark.parametrize("kind", [RegulatedPurePursuit, FollowTheCarrot, OnOffTracker])
def test_tracker_refusing_bad_input_goes_on_as_its_twin(kind: type[Any]) -> None:
    tracker, twin = kind(), kind()
    tracker.set_path(_PATH)
    twin.set_path(_PATH)
    assert _track(tracker, 1, 40) == _track(twin, 1, 40)
    refused = 0
    for bad in _BAD:
        refused += offer(lambda t, bad=bad: t.step(bad, 0.05), tracker, twin)
        refused += offer(lambda t, bad=bad: t.step((1.0, 0.1, 0.05), bad), tracker, twin)
        refused += offer(lambda t, bad=bad: t.set_path(bad), tracker, twin)
        refused += offer(lambda t, bad=bad: t.set_path(_PATH, goal_yaw=bad), tracker, twin)
    assert refused > 30
    assert _track(tracker, 2, 40) == _track(twin, 2, 40)
    # A new path after a long run: as a new tracker's.
    _track(tracker, 3, 300)
    tracker.set_path(_BACK)
    new = kind()
    new.set_path(_BACK)
    assert _track(tracker, 4, 100, -4.0, 0.0) == _track(new, 4, 100, -4.0, 0.0)


def _steer(controller: PotentialFieldController, seed: int, n: int) -> list[bytes]:
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        pose = tuple(rng.uniform(-1.0, 1.0, 3))
        command = controller.step(pose, (2.0, 1.0, 0.3), 0.05, obstacles=_SCAN)
        out.append(command.as_array().tobytes() + controller.previous_velocity.tobytes())
    return out


@pytest.mark.parametrize(
    "options", [{}, {"drive": "diff", "ki": 0.7, "kd": 0.4}, {"ki": 1.0, "stall_timeout": 0.2}]
)
def test_potential_field_refusing_bad_input_goes_on_as_its_twin(options: dict[str, Any]) -> None:
    controller, twin = PotentialFieldController(**options), PotentialFieldController(**options)
    assert _steer(controller, 1, 30) == _steer(twin, 1, 30)
    goal, refused = (2.0, 1.0, 0.3), 0
    for bad in _BAD:
        refused += offer(lambda c, bad=bad: c.step(bad, goal, 0.05), controller, twin)
        refused += offer(lambda c, bad=bad: c.step((0.1, 0.0, 0.0), bad, 0.05), controller, twin)
        refused += offer(lambda c, bad=bad: c.step((0.1, 0.0, 0.0), goal, bad), controller, twin)
        refused += offer(
            lambda c, bad=bad: c.step((0.1, 0.0, 0.0), goal, 0.05, obstacles=bad), controller, twin
        )
        refused += offer(
            lambda c, bad=bad: c.step((0.1, 0.0, 0.0), goal, 0.05, velocity=bad), controller, twin
        )
        refused += offer(
            lambda c, bad=bad: c.step((0.1, 0.0, 0.0), goal, 0.05, obstacles=_SCAN, mount=bad),
            controller,
            twin,
        )
    assert refused > 50
    assert _steer(controller, 2, 30) == _steer(twin, 2, 30)
    # Reset after a long run: as a new controller.
    _steer(controller, 3, 200)
    controller.reset()
    assert _steer(controller, 4, 50) == _steer(PotentialFieldController(**options), 4, 50)
