"""Plain Pose2D / Twist2D copies and pickles: as small and direct as before subclass support.

Keeping a subclass's attributes through copies sent every pose through the
generic record rebuild: pickles named ``navkit._shared.frozen.rebuild_record``
(a list of 10 000 poses pickled 35 % larger, unreadable by older navkit) and
``copy``/``deepcopy``/pickle round trips took about twice as long. A plain
record now rebuilds from its fields; subclasses still take the generic path.
"""

from __future__ import annotations

import copy
import math
import pickle
from collections.abc import Callable
from typing import Any

import pytest

import navkit.geometry._pose as pose_module
from navkit.geometry import Pose2D, Twist2D

# Pickles written by navkit before Pose2D and Twist2D had a __reduce__ (the
# slotted dataclass's default state), protocols 2 and 5.
OLD_PICKLES = [
    b"\x80\x02cnavkit.geometry._pose\nPose2D\nq\x00)\x81q\x01]q\x02(G?\xf8\x00\x00\x00\x00\x00"
    b"\x00G\xc0\x00\x00\x00\x00\x00\x00\x00G@\x08\x00\x00\x00\x00\x00\x00ebcnavkit.geometry."
    b"_pose\nTwist2D\nq\x03)\x81q\x04]q\x05(G?\xe0\x00\x00\x00\x00\x00\x00G\x00\x00\x00\x00"
    b"\x00\x00\x00\x00G\xbf\xd0\x00\x00\x00\x00\x00\x00eb\x86q\x06.",
    b"\x80\x05\x95z\x00\x00\x00\x00\x00\x00\x00\x8c\x15navkit.geometry._pose\x94\x8c\x06Pose2D"
    b"\x94\x93\x94)\x81\x94]\x94(G?\xf8\x00\x00\x00\x00\x00\x00G\xc0\x00\x00\x00\x00\x00\x00"
    b"\x00G@\x08\x00\x00\x00\x00\x00\x00ebh\x00\x8c\x07Twist2D\x94\x93\x94)\x81\x94]\x94(G?"
    b"\xe0\x00\x00\x00\x00\x00\x00G\x00\x00\x00\x00\x00\x00\x00\x00G\xbf\xd0\x00\x00\x00\x00"
    b"\x00\x00eb\x86\x94.",
]

COPIES: list[Callable[[Any], Any]] = [
    copy.copy,
    copy.deepcopy,
    lambda value: pickle.loads(pickle.dumps(value)),
    lambda value: pickle.loads(pickle.dumps(value, protocol=0)),
]

THETAS = [0.0, -0.0, math.pi, -math.pi + 1e-15, math.nextafter(math.pi, 0.0), 1e-300, -2.5]


@pytest.mark.parametrize("data", OLD_PICKLES)
def test_pickles_of_older_versions_load(data: bytes) -> None:
    pose, twist = pickle.loads(data)
    assert type(pose) is Pose2D and type(twist) is Twist2D
    assert (pose.x, pose.y, pose.theta) == (1.5, -2.0, 3.0)
    assert (twist.vx, twist.vy, twist.omega) == (0.5, 0.0, -0.25)


@pytest.mark.parametrize("duplicate", COPIES)
def test_plain_copies_rebuild_from_the_fields_alone(
    duplicate: Callable[[Any], Any], monkeypatch: pytest.MonkeyPatch
) -> None:
    def refuse(*args: object) -> None:
        raise AssertionError("a plain record went through the generic subclass path")

    monkeypatch.setattr(pose_module, "reduce_record", refuse)
    for theta in THETAS:
        pose = Pose2D(1e300, -1e-300, theta)
        copied = duplicate(pose)
        assert type(copied) is Pose2D
        # Bit for bit, the sign of zero included.
        assert [v.hex() for v in (copied.x, copied.y, copied.theta)] == [
            v.hex() for v in (pose.x, pose.y, pose.theta)
        ]
        twist = Twist2D(-0.0, 1e-300, theta)
        copied_twist = duplicate(twist)
        assert type(copied_twist) is Twist2D and copied_twist == twist
        assert math.copysign(1.0, copied_twist.vx) == -1.0


def test_plain_pickles_name_only_the_record_class() -> None:
    for value in (Pose2D(1.0, 2.0, 0.5), Twist2D(1.0, 2.0, 3.0)):
        data = pickle.dumps(value)
        assert b"rebuild_record" not in data and b"_shared" not in data
        assert pickle.loads(data) == value


class _Tagged(Pose2D):
    note: str  # set on instances (in their __dict__), not a dataclass field


def test_subclasses_still_keep_their_attributes() -> None:
    tagged = _Tagged(1.0, 2.0, 3.0)
    tagged.note = "kept"
    for duplicate in COPIES:
        copied = duplicate(tagged)
        assert type(copied) is _Tagged and copied.note == "kept" and copied == tagged
