"""Simulation messages that name what to write, followed literally (review 28, lead).

"lower that rate" read as the simulation's rate, the wrong one to lower, and the
simulation estimators' refusals named no argument and no remedy.
"""

from __future__ import annotations

import pytest
from shapely.geometry import box

from navkit.estimation import DiffOdometry, OmniOdometry
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.sim import Compass, Imu, Observation, Robot, Simulation, World

ROOM = World(box(-1.0, -1.0, 1.0, 1.0).exterior)
DIFF = DiffDrive(track=0.3, wheel_radius=0.05)
OMNI = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)


def _still(obs: Observation) -> Twist2D:
    return Twist2D(0.0, 0.0, 0.0)


def test_the_rate_advice_names_the_sensor_rate() -> None:
    robot = Robot(drive=DIFF, footprint=0.2, imu=Imu(rate=150.0))
    advice = r"lower robot\.imu\.rate \(Imu\(rate=\.\.\.\)\) or raise Simulation"
    with pytest.raises(ValueError, match=advice):
        Simulation(ROOM, robot, _still, start=(0.0, 0.0, 0.0), rate=100.0, duration=0.1)
    # Either remedy runs.
    Simulation(ROOM, robot, _still, start=(0.0, 0.0, 0.0), rate=150.0, duration=0.1).run()
    slower = Robot(drive=DIFF, footprint=0.2, imu=Imu(rate=100.0))
    Simulation(ROOM, slower, _still, start=(0.0, 0.0, 0.0), rate=100.0, duration=0.1).run()


def test_the_estimator_refusals_name_the_argument_and_the_fix() -> None:
    start = (0.0, 0.0, 0.0)
    no_compass = Robot(drive=OMNI, footprint=0.2, encoders=None)
    with pytest.raises(ValueError, match=r"^estimator: OmniOdometry .*Robot\(compass=Compass"):
        Simulation(ROOM, no_compass, _still, start=start, estimator=OmniOdometry(OMNI))
    diff = Robot(drive=DIFF, footprint=0.2, compass=Compass())
    with pytest.raises(ValueError, match=r"^estimator: OmniOdometry needs an omnidirectional"):
        Simulation(ROOM, diff, _still, start=start, estimator=OmniOdometry(OMNI))
    omni = Robot(drive=OMNI, footprint=0.2, compass=Compass())
    with pytest.raises(ValueError, match=r"^estimator: DiffOdometry needs a differential-drive"):
        odometry = DiffOdometry(DIFF, ticks_per_rev=1024)
        Simulation(ROOM, omni, _still, start=start, estimator=odometry)
    no_encoders = Robot(drive=OMNI, footprint=0.2, compass=Compass(), encoders=None)
    with pytest.raises(ValueError, match=r"^estimator: .*Robot\(encoders=WheelEncoders\(\)\)"):
        Simulation(ROOM, no_encoders, _still, start=start, estimator=OmniOdometry(OMNI))
    # Following the first advice: the run goes.
    fixed = Robot(drive=OMNI, footprint=0.2, compass=Compass())
    Simulation(ROOM, fixed, _still, start=start, estimator=OmniOdometry(OMNI), duration=0.1).run()
