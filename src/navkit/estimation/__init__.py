"""State estimation: compass heading, wheel odometry and Kalman filtering.

Fuses wheel odometry with an IMU or compass as real robots do
(robot_localization's approach) in 2-D. Units are SI (m, rad, s); angles are
wrapped to (-π, π]; poses are ``navkit.geometry.Pose2D`` in the world (odometry)
frame. Numerical failures raise :class:`navkit.errors.FilterError` and leave the
filter unchanged.

Ranges: covariance entries (``P0``, process noise, ``Q``, ``R``) of magnitude at
most 1e100; scalar measurement variances in [1e-100, 1e100]; times, states and
measured values any finite numbers. A time gap whose prediction would overflow
raises ``FilterError`` online and is skipped in a batch (``FusionStatus.TIME_GAP``);
a measurement whose update would overflow is not applied (``accepted=False``,
``FusionStatus.OVERFLOW``). State and covariance never become NaN or infinite.

Filters and odometry are stateful: the one-measurement methods (``update``,
``update_odometry``, ...) return navkit objects (``Pose2D``, ``UpdateResult``) and
their ``update_batch`` forms take arrays (or a :class:`MeasurementLog`) with a
leading time axis and return arrays (or a :class:`FusionResult`).
"""

from navkit.estimation._compass import CompassCalibration, compass_to_yaw
from navkit.estimation._ekf import ExtendedKalmanFilter
from navkit.estimation._fusion import FusionResult, FusionStatus, MeasurementLog, PlanarFusion
from navkit.estimation._odometry import DiffOdometry, OmniOdometry
from navkit.estimation._result import UpdateResult

__all__ = [
    "CompassCalibration",
    "DiffOdometry",
    "ExtendedKalmanFilter",
    "FusionResult",
    "FusionStatus",
    "MeasurementLog",
    "OmniOdometry",
    "PlanarFusion",
    "UpdateResult",
    "compass_to_yaw",
]
