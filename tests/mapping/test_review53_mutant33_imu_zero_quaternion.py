"""Only an all-zero orientation is marked "no orientation" (review 53, MUTANT33).

07b1791 marks a message whose orientation quaternion is all zero, and whose
``orientation_covariance[0]`` is not -1, as REP 145's "no orientation". Its
tests' quaternions were yaw turns, ``(0, 0, z, w)``: mutants looking at three
of the four components (``x, y, z`` or ``y, z, w``) passed them, and marked
the identity ``(0, 0, 0, 1)``, the commonest orientation there is, or a half
turn about x ``(1, 0, 0, 0)``. A mutant taking only a non-negative
``orientation_covariance[0]`` as "claiming an orientation" passed too; a
negative one other than -1 is no REP 145 mark either.
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from navkit.mapping.io import read_bag_imu

pytest.importorskip("rosbags")
sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_review52_found_imu import ZERO, imu_msg, write_bag

KEPT = [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0)]


def test_one_non_zero_component_is_an_orientation(tmp_path: Path) -> None:
    messages = [imu_msg(k, quat, 1.0, 0.1) for k, quat in enumerate(KEPT)]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        imu = read_bag_imu(write_bag(tmp_path / "bag", messages))
    np.testing.assert_array_equal(imu.orientations, KEPT)
    np.testing.assert_array_equal(imu.orientation_covariances[:, 0, 0], [1.0] * 4)


@pytest.mark.parametrize("cov00", [0.0, -0.5, -2.0])
def test_a_zero_quaternion_is_marked_whatever_its_covariance_but_minus_one(
    tmp_path: Path, cov00: float
) -> None:
    messages = [imu_msg(0, ZERO, cov00, 0.1), imu_msg(1, ZERO, -1.0, 0.2)]
    with pytest.warns(RuntimeWarning, match="1 of the 2 messages of /imu give an all-zero"):
        imu = read_bag_imu(write_bag(tmp_path / "bag", messages))
    np.testing.assert_array_equal(imu.orientation_covariances[:, 0, 0], [-1.0, -1.0])
    np.testing.assert_array_equal(imu.orientation_covariances[0, 1, 1], 2.0)  # the rest kept
