"""Fuzz specs of ``navkit.sim`` (registered on import by ``fuzz_specs.py``).

Sizes are kept tiny (a box world, a few beams, runs of a fraction of a second)
so the fuzz run stays fast.
"""

from __future__ import annotations

import math

import numpy as np
from fuzz_engine import (
    NOT_FUZZED,
    Anything,
    Array,
    Call,
    Choice,
    Function,
    Obj,
    Real,
    Text,
    call,
    method,
    spec,
)
from shapely.geometry import box

from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import LaserScan
from navkit.sim import (
    Circle,
    Compass,
    CompassReading,
    EncoderReading,
    Estimator,
    Event,
    Imu,
    ImuReading,
    Lidar,
    Metrics,
    MovingObstacle,
    Observation,
    RangeNoise,
    Robot,
    ScanReading,
    Simulation,
    Trace,
    WheelEncoders,
    World,
)

A = np.array
P = "navkit.sim."


def circle() -> Call:
    return call(Circle, A([2.0, 1.0]), 0.3)


def moving() -> Call:
    return call(
        MovingObstacle.constant_velocity, 0.2, start_xy=A([2.5, 0.5]), velocity_xy=A([0.0, 0.5])
    )


def world() -> Call:
    return call(World, [box(-1.0, -1.0, 3.0, 2.0).exterior, circle()], moving=[moving()])


def noise() -> Call:
    return call(
        RangeNoise, limits=(1.0, math.inf), sigma=(0.01, 0.02), bias=(0.0, 0.01),
        absolute=(0.005, 0.0),
    )  # fmt: skip


def lidar() -> Call:
    return call(Lidar, n_beams=8, range_max=5.0, noise=noise(), rate=10.0)


def diff_drive() -> Call:
    return call(DiffDrive, track=0.3, wheel_radius=0.05)


def robot() -> Call:
    return call(
        Robot,
        drive=diff_drive(),
        footprint=0.15,
        max_wheel_speed=30.0,
        max_wheel_acceleration=40.0,
        lidar=lidar(),
        compass=call(Compass, noise=0.5, rate=20.0),
        imu=call(Imu, gyro_noise=0.01, rate=50.0),
    )


def _forward(obs: Observation) -> Twist2D:
    return Twist2D(0.3, 0.0, 0.1)


def simulation() -> Call:
    return call(
        Simulation,
        world(),
        robot(),
        _forward,
        start=A([0.0, 0.0, 0.0]),
        goal=A([1.0, 0.0]),
        goal_tolerance=0.1,
        reference_path=A([[0.0, 0.0], [1.0, 0.0]]),
        rate=50.0,
        control_rate=10.0,
        duration=0.4,
        seed=0,
    )


def laser_scan() -> Call:
    return call(
        LaserScan,
        A([0.8, 1.5, 2.5]),
        angle_min=-0.5,
        angle_increment=0.5,
        range_min=0.1,
        range_max=4.0,
    )


def metrics() -> Call:
    return call(Metrics, True, "goal reached", 1.0, 0.9, 0.05, 0.06, 0.02, 0.01, 0.03, 0.2, 0, 1.2)


REASONS = Choice("goal reached", "collision", "timeout", "controller done", "wall-clock timeout")
FOOTPRINT = {"footprint": Real()}  # a radius here (polygons are covered by World.collides)

# --------------------------------------------------------------------------- world
NOT_FUZZED[P + "EndReason"] = "a typing.Literal alias, not a callable"
NOT_FUZZED[P + "Controller"] = "a typing.Callable alias, not a callable"
spec(P + "Circle", lambda c: circle(), kinds={"center_xy": Array()})
spec(
    P + "MovingObstacle",
    lambda c: call(MovingObstacle, 0.2, A([[0.0, 0.0], [1.0, 0.0]]), A([0.0, 1.0]), after="loop"),
    kinds={
        "shape": Real(),
        "path_xy": Array(),
        "times": Array(),
        "after": Choice("stop", "loop", "extend"),
    },
)
spec(P + "MovingObstacle.constant_velocity", lambda c: moving(), kinds={"shape": Real()})
spec(
    P + "MovingObstacle.scripted",
    lambda c: call(
        MovingObstacle.scripted,
        0.2,
        A([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]),
        times=A([0.0, 1.0, 3.0]),
        after="loop",
    ),
    kinds={
        "shape": Real(),
        "path_xy": Array(),
        "speed": Real(optional=True),
        "after": Choice("stop", "loop", "extend"),
    },
)
spec(P + "MovingObstacle.position_at", lambda c: method(moving(), "position_at", 0.7))
spec(P + "MovingObstacle.geometry_at", lambda c: method(moving(), "geometry_at", 0.7))
spec(P + "World", lambda c: world(), kinds={"obstacles": Anything(), "moving": Anything()})
spec(
    P + "World.raycast",
    lambda c: method(
        world(), "raycast", A([0.0, 0.0, 0.2]), A([-1.0, 0.0, 1.5]), range_max=5.0, t=0.3
    ),
    inf_ok="a ray that hits nothing within range_max reads inf",
)
spec(
    P + "World.clearance",
    lambda c: method(world(), "clearance", 0.15, A([0.0, 0.0, 0.3]), t=0.2),
    kinds=FOOTPRINT,
)
spec(
    P + "World.collides",
    lambda c: method(
        world(), "collides", A([[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1]]), A([0.0, 0.0, 0.3])
    ),
    kinds={"footprint": Array()},
)

# --------------------------------------------------------------------------- sensors
spec(
    P + "RangeNoise",
    lambda c: noise(),
    kinds={
        "limits": Array(allow={"posinf"}),
        "sigma": Array(),
        "bias": Array(),
        "absolute": Array(),
    },
)
spec(
    P + "RangeNoise.arrays",
    lambda c: method(noise(), "arrays"),
    inf_ok="the last band's limit is inf (open band)",
)
spec(
    P + "Lidar",
    lambda c: lidar(),
    kinds={"n_beams": Real(integer=True), "noise": Obj(RangeNoise, optional=True)},
)
spec(P + "Lidar.angles", lambda c: method(lidar(), "angles"))
spec(
    P + "Lidar.scan",
    lambda c: method(lidar(), "scan", world(), A([0.0, 0.0, 0.1]), t=0.2, seed=1),
    kinds={
        "seed": Real(integer=True, optional=True),
        "rng": Real(integer=True, optional=True),  # the deprecated name of seed
    },
)
spec(P + "Compass", lambda c: call(Compass, noise=1.0, bias=2.0, rate=10.0, latency=0.05))
spec(P + "Compass.heading_deg", lambda c: method(call(Compass, bias=1.0), "heading_deg", 0.4, 0.0))
spec(P + "Imu", lambda c: call(Imu, gyro_noise=0.01, gyro_bias=0.001, accel_noise=0.1, rate=50.0))
spec(
    P + "WheelEncoders",
    lambda c: call(WheelEncoders, ticks_per_rev=512.0, bits=12, rate=20.0),
    kinds={"bits": Real(integer=True, optional=True)},
)
spec(
    P + "WheelEncoders.ticks",
    lambda c: method(call(WheelEncoders, bits=12), "ticks", A([0.5, -20.0, 3.0])),
    kinds={"wheel_angles": Array()},
)
spec(  # the deprecated alias of ticks (it warns)
    P + "WheelEncoders.counts",
    lambda c: method(call(WheelEncoders, bits=12), "counts", A([0.5, -20.0, 3.0])),
    kinds={"wheel_angles": Array()},
)
spec(P + "ScanReading", lambda c: call(ScanReading, 0.1, laser_scan()))
spec(
    P + "EncoderReading",
    lambda c: call(EncoderReading, 0.02, A([10, -12])),
    kinds={"ticks": Array()},
)
spec(P + "CompassReading", lambda c: call(CompassReading, 0.05, 123.0))
spec(P + "ImuReading", lambda c: call(ImuReading, 0.01, 0.2, 0.1, -0.05))

# --------------------------------------------------------------------------- robot, loop, trace
spec(
    P + "Robot",
    lambda c: robot(),
    kinds={
        "footprint": Real(),
        "wheel_radius_error": Real(),
        "max_wheel_speed": Real(allow={"posinf"}),
        "max_wheel_acceleration": Real(allow={"posinf"}),
        "encoders": Obj(WheelEncoders, optional=True),
        "lidar": Obj(Lidar, optional=True),
        "compass": Obj(Compass, optional=True),
        "imu": Obj(Imu, optional=True),
    },
)
spec(P + "Estimator", lambda c: call(Estimator), expect_error=TypeError)
spec(
    P + "Observation",
    lambda c: call(
        Observation,
        0.1,
        None,
        None,
        call(CompassReading, 0.05, 90.0),
        None,
        (),
        None,
        call(Pose2D, 0.0, 0.0, 0.1),
        dt=0.05,
    ),
    kinds={
        "new": Anything(),
        "scan": Obj(ScanReading, optional=True),
        "encoders": Obj(EncoderReading, optional=True),
        "compass": Obj(CompassReading, optional=True),
        "imu": Obj(ImuReading, optional=True),
        "estimate": Obj(Pose2D, optional=True),
    },
)
spec(
    P + "Simulation",
    lambda c: simulation(),
    kinds={
        "controller": Function(),
        "estimator": Anything(optional=True),
        "seed": Real(integer=True, optional=True),
        "reference_path": Array(optional=True),
    },
)
spec(
    P + "Simulation.run",
    lambda c: method(simulation(), "run"),
    nan_ok="metrics without an estimator (estimate errors) are NaN",
)
spec(
    P + "Event",
    lambda c: call(Event, 1.5, "collision", "touched"),
    kinds={"kind": REASONS, "message": Text()},
)
_MAYBE_NAN = Real(allow={"nan"})
_NAN_METRICS = (
    "time_to_goal",
    "final_error",
    "final_error_estimated",
    "estimate_error",
    "cross_track_mean",
    "cross_track_max",
)

spec(
    P + "Metrics",
    lambda c: metrics(),
    kinds={
        "reason": REASONS,
        "collisions": Real(integer=True),
        "min_clearance": Real(allow={"posinf"}),
        **dict.fromkeys(_NAN_METRICS, _MAYBE_NAN),
    },
)
spec(
    P + "Trace",
    lambda c: call(
        Trace,
        A([0.0, 0.1]),
        np.zeros((2, 3)),
        np.full((2, 3), 0.01),
        np.zeros((2, 3)),
        (),
        (call(Event, 0.1, "timeout", "end"),),
        metrics(),
    ),
    kinds={"estimates": Array(allow={"nan"}), "scans": Anything(), "events": Anything()},
    nan_ok="estimates rows are NaN before the first estimate",
)
