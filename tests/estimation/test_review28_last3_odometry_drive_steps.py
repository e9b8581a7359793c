"""DiffOdometry.update_batch and the steps a DiffDrive subclass returns (review 28, LAST3).

84a7c20 wrote the poses over the array ``drive.odometry_step_batch`` returned, to
save memory. That array is the drive's own result: a subclass that keeps it (a
log of its last steps) had it turned into poses, and one that hands it out
read-only made ``update_batch`` fail with NumPy's "assignment destination is
read-only", naming nothing. The base class's fresh array may be reused; a
subclass's may not.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import FloatArray
from navkit.estimation import DiffOdometry
from navkit.kinematics import DiffDrive

# The fix is in src/navkit/estimation/_odometry.py, claimed by another helper this
# session: the lead applies it (LAST3's report) and removes this marker.

LEFT = [0, 100, 200, 260]
RIGHT = [0, 120, 260, 300]


class _KeepsSteps(DiffDrive):
    """A drive that keeps the steps it returned (say, for a log), read-only or not."""

    read_only = False
    kept: FloatArray | None = None
    returned: FloatArray | None = None

    def odometry_step_batch(
        self, d_left: ArrayLike, d_right: ArrayLike, *, method: Any = "arc"
    ) -> FloatArray:
        steps = super().odometry_step_batch(d_left, d_right, method=method)
        steps.flags.writeable = not self.read_only
        self.kept = steps
        self.returned = steps.copy()  # what the caller was given
        return steps


def _expected() -> FloatArray:
    return DiffOdometry(DiffDrive(track=0.3, wheel_radius=0.05), ticks_per_rev=1024).update_batch(
        LEFT, RIGHT
    )


def test_a_subclass_s_kept_steps_stay_steps() -> None:
    drive = _KeepsSteps(track=0.3, wheel_radius=0.05)
    poses = DiffOdometry(drive, ticks_per_rev=1024).update_batch(LEFT, RIGHT)
    assert drive.kept is not None
    # Still the steps it returned, not the poses written over them.
    np.testing.assert_array_equal(drive.kept, drive.returned)
    assert not np.shares_memory(poses, drive.kept)
    np.testing.assert_array_equal(poses, _expected())


def test_read_only_steps_of_a_subclass_are_read_not_written() -> None:
    drive = _KeepsSteps(track=0.3, wheel_radius=0.05)
    drive.read_only = True
    poses = DiffOdometry(drive, ticks_per_rev=1024).update_batch(LEFT, RIGHT)
    np.testing.assert_array_equal(poses, _expected())
    assert poses.flags.writeable
