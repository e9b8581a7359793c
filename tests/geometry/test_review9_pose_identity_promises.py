"""Review 9 (mutation testing): documented identities of the pose and twist converters."""

from __future__ import annotations

from navkit.geometry import Pose2D, Twist2D, as_pose, as_twist


def test_as_pose_and_as_twist_return_navkit_objects_themselves() -> None:
    # Documented: "``value`` itself when it already is one" (no copy, no re-wrap).
    pose = Pose2D(1.5, -2.0, 3.0)
    twist = Twist2D(0.5, -0.25, 1.0)
    assert as_pose(pose) is pose
    assert as_pose(pose, "frame") is pose
    assert as_twist(twist) is twist
    assert as_twist(twist, "command") is twist
    # A sequence is converted into a new object with the same fields.
    built = as_pose([1.5, -2.0, 3.0])
    assert built == pose and built is not pose
