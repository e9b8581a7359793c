"""A PotentialFieldController pickled with its ``mode`` (before 8c31a76) loads (review 52, FOUND4).

``mode=`` became ``drive=`` (8c31a76, 30 November 2026), the same values: a
controller pickled before held the option as ``mode`` and was refused as it
loaded ("has no attribute 'mode'", since review 51; AttributeError before).
The old name is now read as today's: a differential controller pickled mid-run
steps on as one built and run alike today.
"""

from __future__ import annotations

import base64
import pickle
import sys
from pathlib import Path

import pytest

from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from old_release import made_at

POSES = [Pose2D(0.0, 0.0, 0.3), Pose2D(0.02, 0.01, 0.28), Pose2D(0.05, 0.02, 0.25)]
TARGET = Pose2D(2.0, 1.0, 0.0)


def _run(controller: PotentialFieldController, poses: list[Pose2D]) -> list[object]:
    return [controller.step(pose, TARGET, 0.05, obstacles=[[1.0, 0.6]]) for pose in poses]


def test_a_state_holding_mode_loads_as_drive() -> None:
    controller = PotentialFieldController(drive="diff", ki=0.5)
    _run(controller, POSES[:2])
    # The state such a pickle holds: today's, with the option under its old name.
    instance, slots = controller.__getstate__()  # type: ignore[misc]
    old_slots = {("mode" if name == "_drive" else name): value for name, value in slots.items()}
    old = object.__new__(PotentialFieldController)
    old.__setstate__((instance, old_slots))
    assert old.drive == "diff" and repr(old) == repr(controller)
    assert _run(old, POSES[2:]) == _run(controller, POSES[2:])


MAKER = """
import base64, json, pickle
from navkit.control import PotentialFieldController
from navkit.geometry import Pose2D
controller = PotentialFieldController(mode="diff", ki=0.5)
for pose in (Pose2D(0.0, 0.0, 0.3), Pose2D(0.02, 0.01, 0.28)):
    controller.step(pose, Pose2D(2.0, 1.0, 0.0), dt=0.05, obstacles=[[1.0, 0.6]])
print(json.dumps(base64.b64encode(pickle.dumps(controller)).decode()))
"""


@pytest.mark.slow
def test_a_differential_controller_pickled_at_0123de4_steps_on(tmp_path: Path) -> None:
    old = pickle.loads(base64.b64decode(made_at("0123de4", MAKER, tmp_path)))
    assert isinstance(old, PotentialFieldController) and old.drive == "diff"
    today = PotentialFieldController(drive="diff", ki=0.5)
    _run(today, POSES[:2])
    assert repr(old) == repr(today)
    # Its state is the old release's (that release limited the velocity's change a
    # little differently: 1e-5 m/s apart after two steps), stepped on by today's law.
    (command,) = _run(old, POSES[2:])
    (expected,) = _run(today, POSES[2:])
    assert command.vy == 0.0 and command.omega == expected.omega
    assert abs(command.vx - expected.vx) < 1e-4
