"""A ``done`` with a truth value only through its metaclass is refused (review 32, FRESH).

``done_flag`` refuses an object whose class defines neither ``__bool__`` nor
``__len__`` (Python takes every such object for true). It looked them up with
``getattr`` on the class, which falls back to the *metaclass*: ``EnumType``
defines ``__bool__`` (for the class itself), so every member of a plain
``Enum`` passed, and ``done = Status.RUNNING`` ended the run at its first step
as "controller done". The lookup now goes through the class's MRO only.
Checked against the source before the fix: the refusal tests failed there
(``done_flag(Status.RUNNING, ...)`` returned True; the run ended at 0 s).
"""

from __future__ import annotations

import enum

import pytest

from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.sim import Observation, Robot, Simulation, World
from navkit.sim._done import done_flag

ROBOT = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)


class Status(enum.Enum):
    RUNNING = "running"
    DONE = "done"


class Meta(type):
    def __len__(cls) -> int:
        return 0


class Marker(metaclass=Meta):
    """No truth value of its own: its metaclass's __len__ is the class's, not its instances'."""


class StatusController:
    done = Status.RUNNING

    def __call__(self, obs: Observation) -> Twist2D:
        return Twist2D(0.1, 0.0, 0.0)


@pytest.mark.parametrize("value", [Status.RUNNING, Status.DONE, Marker()])
def test_a_truth_value_of_the_metaclass_only_is_refused(value: object) -> None:
    kind = type(value).__name__
    with pytest.raises(TypeError, match=rf"^done must be true or false, got a {kind}, which has "
                       "no truth value of its own"):  # fmt: skip
        done_flag(value, "done")


def test_a_run_with_an_enum_done_is_refused_not_ended_at_once() -> None:
    sim = Simulation(World(), ROBOT, StatusController(), start=(0.0, 0.0, 0.0), duration=1.0)
    with pytest.raises(TypeError, match=r"^the controller's done must be true or false, got a "
                       r"Status"):  # fmt: skip
        sim.run()


class Phase(enum.Enum):
    RUNNING = 0
    DONE = 1

    def __bool__(self) -> bool:
        return self is Phase.DONE


class Flags(enum.Flag):
    ARRIVED = 1


class Level(enum.IntEnum):
    NO = 0
    YES = 1


@pytest.mark.parametrize(
    ("value", "want"),
    [
        (Phase.RUNNING, False), (Phase.DONE, True), (Flags(0), False), (Flags.ARRIVED, True),
        (Level.NO, False), (Level.YES, True),
    ],
)  # fmt: skip
def test_enums_with_a_truth_value_of_their_own_keep_it(value: object, want: bool) -> None:
    assert done_flag(value, "done") is want
