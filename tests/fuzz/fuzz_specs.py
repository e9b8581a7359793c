"""Fuzz specifications: one valid call of every public callable of navkit.

How to add one (``test_public_api_fuzz.py`` fails until every public function,
class and method has an entry here or in ``NOT_FUZZED``)::

    spec("navkit.geometry.integrate",                     # the canonical public name
         lambda c: call(integrate, pose(), twist(), 0.5), # a fresh valid call, every time
         kinds={"dt": Real()})                            # only where the annotation is not enough

The canonical name is the deepest public package that exports the object and
holds its module (``navkit.planning.grid.astar``, not ``navkit.planning.astar``);
the failing test prints the missing names.

* ``call(f, ...)`` calls a function, class or classmethod; ``method(receiver, "name", ...)``
  calls a method, the receiver usually being a lazy ``call(...)`` of its constructor.
  Lazy navkit objects in arguments are fuzzed too (their constructor's numeric
  arguments get the extreme values), so build them with ``call`` rather than eagerly.
* Argument kinds are inferred from annotations (``float``, ``bool``, ``ArrayLike``,
  ``Pose2D | ArrayLike``, a navkit class, ``... | None``); give ``kinds=`` for the
  rest: ``Real(integer=True)``, ``Array(boolean=True, allow={"nan"})``, ``Cell()``,
  ``Choice("arc", "midpoint")``, ``Function()``, ``FileKind(files=...)``, ``OutPath()``...
* ``inf_ok`` / ``nan_ok`` say (with the reason, or as a predicate on the result)
  where the documented answer holds infinities or NaN from finite input; a kind's
  ``allow={"nan", "posinf", "neginf"}`` where an argument documents them (REP 117
  scan ranges); ``mutates=("self",)`` where the call is meant to change its
  receiver (or a named argument); ``expect_error=TypeError`` for abstract classes.
* ``NOT_FUZZED[name] = "why"`` only for what cannot be called (a ``typing`` alias).
* ``c.tmp`` (the ``Ctx``) is a fresh folder for files.
"""

from __future__ import annotations

import gzip
import math
from functools import partial
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
from fuzz_engine import (
    NOT_FUZZED,
    Anything,
    Array,
    Call,
    Cell,
    Choice,
    Ctx,
    FileKind,
    Flag,
    Function,
    Ignored,
    IntSequence,
    MatrixOrFunction,
    Namespace,
    Obj,
    OutPath,
    PoseLike,
    Real,
    SequenceOf,
    Text,
    call,
    method,
    spec,
)

from navkit import errors
from navkit.behaviours import BehaviourTarget, GameState, attack, defend, support
from navkit.control import PotentialFieldController, limit_velocity_change
from navkit.estimation import (
    CompassCalibration,
    DiffOdometry,
    ExtendedKalmanFilter,
    FusionResult,
    FusionStatus,
    MeasurementLog,
    OmniOdometry,
    PlanarFusion,
    UpdateResult,
    compass_to_yaw,
)
from navkit.geometry import (
    Pose2D,
    Twist2D,
    angle_diff,
    as_pose,
    as_twist,
    integrate,
    rollout,
    wrap_angle,
)
from navkit.kinematics import DiffDrive, OmniDrive, tick_delta, ticks_to_distance
from navkit.mapping import (
    LaserScan,
    LocalGrid,
    OccupancyGrid,
    costmap,
    distance_transform,
    integrate_scan,
    rasterize_polygons,
    traversal_costs,
    validate_costs,
)
from navkit.mapping.io import (
    CarmenLog,
    OccupancyGridMsgFields,
    grid_from_msg,
    grid_to_msg_fields,
    map_image_path,
    read_carmen,
    read_map,
    scan_from_msg,
    write_map,
)
from navkit.planning import (
    AStarPlanner,
    AttractiveField,
    BlendedAttraction,
    CellPlanner,
    CompositeField,
    ConicAttraction,
    FieldDStar,
    GreedyStep,
    KhatibRepulsion,
    MapPlanner,
    ParaboloidAttraction,
    Path2D,
    PiecewiseAttraction,
    PiecewiseRepulsion,
    PotentialField,
    SampledField,
    astar,
    distance_field,
    field_dstar,
    greedy_step,
    piecewise_repulsive_force_from_scan,
    plan_path,
    repulsive_force_from_scan,
    sample_field,
)

A = np.array

# --------------------------------------------------------------------------- shared valid values


def pose() -> Call:
    return call(Pose2D, 1.0, 2.0, 0.5)


def twist() -> Call:
    return call(Twist2D, 0.4, 0.1, 0.3)


def scan() -> Call:
    return call(
        LaserScan,
        A([0.8, 1.5, 2.5, 0.6, 3.0]),
        angle_min=-1.0,
        angle_increment=0.5,
        range_min=0.1,
        range_max=4.0,
    )


OCCUPIED = np.zeros((8, 10), dtype=bool)
OCCUPIED[2:6, 5] = True
UNKNOWN = np.zeros((8, 10), dtype=bool)
UNKNOWN[7, :3] = True


def grid() -> Call:
    return call(
        OccupancyGrid.from_occupancy,
        OCCUPIED.copy(),
        resolution=0.1,
        origin=(-0.2, -0.1, 0.0),
        unknown=UNKNOWN.copy(),
    )


def costs() -> np.ndarray:
    out = np.ones((6, 7))
    out[1:5, 3] = np.inf
    out[0, 0:2] = 2.5
    return out


def local_grid() -> Call:
    return call(LocalGrid.from_points, A([[0.5, 0.0], [0.3, 0.3]]), half_width=0.6, resolution=0.1)


def diff_drive() -> Call:
    return call(DiffDrive, track=0.3, wheel_radius=0.05)


def omni_drive() -> Call:
    return call(OmniDrive, A([0.5, 2.6, 4.7]), wheel_radius=0.05, base_radius=0.2)


def log() -> Call:
    return call(
        MeasurementLog.from_streams,
        odometry=(A([0.1, 0.2, 0.3]), A([1.0, 1.0, 0.9]), A([0.0, 0.1, 0.1])),
        yaw=(A([0.15]), A([0.05])),
    )


def game_state() -> Call:
    return call(
        GameState,
        robot_xy=A([0.0, 0.0]),
        ball_xy=A([1.0, 0.2]),
        teammates_xy=A([[-2.0, 1.0]]),
        opponents_xy=A([[2.0, 0.5], [3.0, -1.0]]),
        own_goal_xy=A([-4.5, 0.0]),
        opponent_goal_xy=A([4.5, 0.0]),
    )


def _uncomputed_nis(result: Any) -> bool:
    """UpdateResult.nis is documented NaN when it was never computed (a rejected update)."""
    return isinstance(result, UpdateResult) and not result.accepted and result.residual.size == 0


def _rejected(result: Any) -> bool:
    """A rejected update may report nis = inf (an overflowing innovation, with its reason)."""
    return isinstance(result, UpdateResult) and not result.accepted


POSE = PoseLike("Pose2D")
OPT_POSE = PoseLike("Pose2D", optional=True)
REAL = Real()
INT = Real(integer=True)

# --------------------------------------------------------------------------- errors

spec("navkit.errors.NavkitError", lambda c: call(errors.NavkitError, "boom"))
spec("navkit.errors.FilterError", lambda c: call(errors.FilterError, "boom"))
spec("navkit.errors.KernelCacheWarning", lambda c: call(errors.KernelCacheWarning, "boom"))
spec(
    "navkit.errors.NoPathError",
    lambda c: call(errors.NoPathError, "no path", expanded=3),
    kinds={"message": Text()},
)

# --------------------------------------------------------------------------- geometry

spec("navkit.geometry.Pose2D", lambda c: call(Pose2D, 1.0, 2.0, 0.5))
spec("navkit.geometry.Pose2D.compose", lambda c: method(pose(), "compose", A([0.5, -1.0, 1.0])))
spec(
    "navkit.geometry.Pose2D.__matmul__", lambda c: method(pose(), "__matmul__", A([0.5, -1.0, 1.0]))
)
spec(
    "navkit.geometry.Pose2D.__rmatmul__",
    lambda c: method(pose(), "__rmatmul__", A([0.5, -1.0, 1.0])),
)
spec(
    "navkit.geometry.Pose2D.relative_to",
    lambda c: method(pose(), "relative_to", A([0.5, -1.0, 1.0])),
)
spec("navkit.geometry.Pose2D.inverse", lambda c: method(pose(), "inverse"))
spec("navkit.geometry.Pose2D.as_array", lambda c: method(pose(), "as_array"))
spec("navkit.geometry.Pose2D.from_array", lambda c: call(Pose2D.from_array, A([1.0, 2.0, 0.5])))
spec(
    "navkit.geometry.Pose2D.transform_points",
    lambda c: method(pose(), "transform_points", A([[1.0, 0.0], [0.5, -2.0]])),
)
spec("navkit.geometry.Twist2D", lambda c: call(Twist2D, 0.4, 0.1, 0.3))
spec("navkit.geometry.Twist2D.as_array", lambda c: method(twist(), "as_array"))
spec("navkit.geometry.Twist2D.from_array", lambda c: call(Twist2D.from_array, A([0.4, 0.1, 0.3])))
# ``record + offset`` has no meaning: a TypeError with a hint for every operand (review 36).
for _key, _record in (("Pose2D", pose), ("Twist2D", twist)):
    for _op in ("__add__", "__radd__"):
        spec(
            f"navkit.geometry.{_key}.{_op}",
            lambda c, r=_record, op=_op: method(r(), op, A([0.5, -1.0, 1.0])),
            kinds={"other": Anything()},
            expect_error=TypeError,
        )
spec("navkit.geometry.angle_diff", lambda c: call(angle_diff, A([0.1, 3.0]), A([-3.0, 0.2])))
spec("navkit.geometry.wrap_angle", lambda c: call(wrap_angle, A([0.1, 4.0, -7.0])))
spec(
    "navkit.geometry.as_pose",
    lambda c: call(as_pose, A([1.0, 2.0, 0.5]), "pose"),
    kinds={"name": Text()},
)
spec(
    "navkit.geometry.as_twist",
    lambda c: call(as_twist, A([0.4, 0.1, 0.3]), "twist"),
    kinds={"name": Text()},
)
spec(
    "navkit.geometry.integrate",
    lambda c: call(integrate, pose(), twist(), 0.5),
    kinds={"dt": REAL},
)
spec(
    "navkit.geometry.rollout",
    lambda c: call(rollout, pose(), A([[0.5, 0.0, 0.1], [0.4, 0.1, -0.2]]), A([0.1, 0.2])),
    kinds={"twists": Array()},
)

# --------------------------------------------------------------------------- kinematics

ODOMETRY_METHOD = Choice("arc", "midpoint", "first_order")
NOT_FUZZED["navkit.kinematics.OdometryMethod"] = "a typing.Literal alias, not a callable"
spec("navkit.kinematics.DiffDrive", lambda c: call(DiffDrive, track=0.3, wheel_radius=0.05))
spec(
    "navkit.kinematics.DiffDrive.forward",
    lambda c: method(diff_drive(), "forward", A([10.0, 12.0])),
)
spec(
    "navkit.kinematics.DiffDrive.forward_batch",
    lambda c: method(diff_drive(), "forward_batch", A([[10.0, 12.0], [-1.0, 3.0]])),
)
spec(
    "navkit.kinematics.DiffDrive.inverse",
    lambda c: method(diff_drive(), "inverse", call(Twist2D, 0.4, 0.0, 0.3)),
    kinds={"twist": PoseLike("Twist2D")},
)
spec(
    "navkit.kinematics.DiffDrive.inverse_batch",
    lambda c: method(diff_drive(), "inverse_batch", A([[0.4, 0.0, 0.3], [0.1, 0.0, -1.0]])),
)
spec(
    "navkit.kinematics.DiffDrive.odometry_step",
    lambda c: method(diff_drive(), "odometry_step", 0.1, 0.12),
    kinds={"method": ODOMETRY_METHOD},
)
spec(
    "navkit.kinematics.DiffDrive.odometry_step_batch",
    lambda c: method(diff_drive(), "odometry_step_batch", A([0.1, 0.2]), A([0.12, 0.18])),
    kinds={"method": ODOMETRY_METHOD},
)
spec(
    "navkit.kinematics.OmniDrive",
    lambda c: call(OmniDrive, A([0.5, 2.6, 4.7]), wheel_radius=0.05, base_radius=0.2),
)
spec(
    "navkit.kinematics.OmniDrive.forward",
    lambda c: method(omni_drive(), "forward", A([3.0, -2.0, 1.0])),
)
spec(
    "navkit.kinematics.OmniDrive.forward_batch",
    lambda c: method(omni_drive(), "forward_batch", A([[3.0, -2.0, 1.0], [0.0, 1.0, 2.0]])),
)
spec("navkit.kinematics.OmniDrive.inverse", lambda c: method(omni_drive(), "inverse", twist()))
spec(
    "navkit.kinematics.OmniDrive.inverse_batch",
    lambda c: method(omni_drive(), "inverse_batch", A([[0.4, 0.1, 0.3], [0.0, 0.0, 1.0]])),
)
spec(
    "navkit.kinematics.OmniDrive.saturate",
    lambda c: method(omni_drive(), "saturate", A([10.0, -20.0, 5.0]), max_wheel_speed=8.0),
)
spec(
    "navkit.kinematics.OmniDrive.three_wheel",
    lambda c: call(OmniDrive.three_wheel, wheel_radius=0.05, base_radius=0.2),
)
spec(
    "navkit.kinematics.tick_delta",
    lambda c: call(tick_delta, A([65535, 10]), A([2, 20]), bits=16),
)
spec(
    "navkit.kinematics.ticks_to_distance",
    lambda c: call(ticks_to_distance, A([1024, -10]), ticks_per_rev=2048, wheel_radius=0.1),
)

# --------------------------------------------------------------------------- mapping

for _alias in ("mapping.io.MapMode", "mapping.ScanMatchReason"):
    NOT_FUZZED["navkit." + _alias] = "a typing.Literal alias, not a callable"


def _pgm(folder: Path, name: str, body: bytes) -> Path:
    path = folder / name
    path.write_bytes(body)
    return path


def _map_yaml(folder: Path, text: str, name: str = "map.yaml") -> Path:
    _pgm(folder, "ok.pgm", b"P5\n2 2\n255\n" + bytes([0, 254, 205, 0]))
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


_YAML = (
    "image: {image}\nresolution: {res}\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
    "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
)

MAP_FILES = FileKind(
    files=[
        (
            "a PGM passed as the YAML",
            lambda d: _pgm(d, "map.pgm", b"P5\n2 2\n255\n\x00\xfe\xcd\x00"),
        ),
        (
            "non-UTF-8 YAML",
            lambda d: _pgm(
                d, "bad.yaml", b"image: \xff\xfe.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n"
            ),
        ),
        (
            "YAML whose image is itself",
            lambda d: _map_yaml(d, _YAML.format(image="map.yaml", res=0.1)),
        ),
        (
            "YAML whose image is a text file",
            lambda d: (
                _pgm(d, "host.txt", b"myhost\n"),
                _map_yaml(d, _YAML.format(image="host.txt", res=0.1)),
            )[1],
        ),
        (
            "YAML whose image is missing",
            lambda d: _map_yaml(d, _YAML.format(image="nothere.pgm", res=0.1)),
        ),
        (
            "YAML whose image is garbage PNG",
            lambda d: (
                _pgm(d, "g.png", b"\x89PNG\r\n\x1a\n" + bytes(40)),
                _map_yaml(d, _YAML.format(image="g.png", res=0.1)),
            )[1],
        ),
        (
            "YAML with resolution .nan",
            lambda d: _map_yaml(d, _YAML.format(image="ok.pgm", res=".nan")),
        ),
        ("YAML with resolution -1", lambda d: _map_yaml(d, _YAML.format(image="ok.pgm", res=-1))),
        (
            "YAML with resolution 1e-320",
            lambda d: _map_yaml(d, _YAML.format(image="ok.pgm", res="1e-320")),
        ),
        (
            "YAML with resolution 'abc'",
            lambda d: _map_yaml(d, _YAML.format(image="ok.pgm", res="abc")),
        ),
        (
            "YAML with a NaN origin",
            lambda d: _map_yaml(
                d, _YAML.format(image="ok.pgm", res=0.1).replace("[0.0, 0.0, 0.0]", "[.nan, 0, 0]")
            ),
        ),
        (
            "YAML with a 2-element origin",
            lambda d: _map_yaml(
                d, _YAML.format(image="ok.pgm", res=0.1).replace("[0.0, 0.0, 0.0]", "[0, 0]")
            ),
        ),
        (
            "YAML with negate: 2",
            lambda d: _map_yaml(
                d, _YAML.format(image="ok.pgm", res=0.1).replace("negate: 0", "negate: 2")
            ),
        ),
        (
            "YAML with thresholds reversed",
            lambda d: _map_yaml(d, _YAML.format(image="ok.pgm", res=0.1).replace("0.65", "0.1")),
        ),
        (
            "YAML with mode: bogus",
            lambda d: _map_yaml(d, _YAML.format(image="ok.pgm", res=0.1) + "mode: bogus\n"),
        ),
        ("YAML that is a list", lambda d: _map_yaml(d, "- 1\n- 2\n")),
        ("YAML that is a scalar", lambda d: _map_yaml(d, "42\n")),
        ("YAML with a syntax error", lambda d: _map_yaml(d, "image: [unclosed\n")),
        ("YAML without an image", lambda d: _map_yaml(d, "resolution: 0.1\norigin: [0, 0, 0]\n")),
        (
            "P2 image with a value of 10**26",
            lambda d: (
                _pgm(d, "p2.pgm", b"P2\n2 1\n255\n0 100000000000000000000000000\n"),
                _map_yaml(d, _YAML.format(image="p2.pgm", res=0.1)),
            )[1],
        ),
        (
            "P5 image claiming 10**6 x 10**6",
            lambda d: (
                _pgm(d, "big.pgm", b"P5\n1000000 1000000\n255\n\x00"),
                _map_yaml(d, _YAML.format(image="big.pgm", res=0.1)),
            )[1],
        ),
        (
            "P5 image truncated",
            lambda d: (
                _pgm(d, "t.pgm", b"P5\n4 4\n255\n\x00\x00"),
                _map_yaml(d, _YAML.format(image="t.pgm", res=0.1)),
            )[1],
        ),
        (
            "P5 image with maxval 0",
            lambda d: (
                _pgm(d, "z.pgm", b"P5\n1 1\n0\n\x00"),
                _map_yaml(d, _YAML.format(image="z.pgm", res=0.1)),
            )[1],
        ),
        (
            "PNG claiming 10**5 x 10**5",
            lambda d: (
                _pgm(d, "bomb.png", _png_header(100_000, 100_000)),
                _map_yaml(d, _YAML.format(image="bomb.png", res=0.1)),
            )[1],
        ),
    ]
)


#: MAP_FILES but for those whose fault is the image's content: map_image_path reads
#: and checks the YAML (and that the image is a regular file), not the image.
_IMAGE_CONTENT = ("YAML whose image is a text file", "YAML whose image is garbage PNG")
MAP_YAML_FILES = FileKind(
    files=[
        (label, make)
        for label, make in MAP_FILES.files
        if label not in _IMAGE_CONTENT and not label.startswith(("P2 ", "P5 ", "PNG "))
    ]
)


def _png_header(width: int, height: int) -> bytes:
    import struct
    import zlib

    ihdr = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    chunk = b"IHDR" + ihdr
    return (
        b"\x89PNG\r\n\x1a\n"
        + struct.pack(">I", len(ihdr))
        + chunk
        + struct.pack(">I", zlib.crc32(chunk))
        + struct.pack(">I", 0)
        + b"IEND"
        + struct.pack(">I", zlib.crc32(b"IEND"))
    )


def _carmen(folder: Path, text: str | bytes, name: str = "log.txt") -> Path:
    path = folder / name
    path.write_bytes(text.encode() if isinstance(text, str) else text)
    return path


_FLASER = "FLASER 3 1.0 2.0 5.0 0.5 0 0 0.5 0 0 12.5 host 12.6\n"
CARMEN_FILES = FileKind(
    files=[
        ("corrupt .gz", lambda d: _carmen(d, b"\x1f\x8b\x08\x00garbage", "log.gz")),
        (
            "truncated .gz",
            lambda d: _carmen(d, gzip.compress(_FLASER.encode() * 20)[:30], "log.gz"),
        ),
        (
            "non-UTF-8 line",
            lambda d: _carmen(d, _FLASER.encode() + b"FLASER 1 \xff\xfe 0 0 0 0 0 0 0 1 h 1\n"),
        ),
        (
            "NaN timestamp",
            lambda d: _carmen(d, "FLASER 3 1.0 2.0 5.0 0.5 0 0 0.5 0 0 nan host 12.6\n"),
        ),
        ("inf range", lambda d: _carmen(d, "FLASER 3 1.0 inf 5.0 0.5 0 0 0.5 0 0 1.0 host 1.0\n")),
        ("NaN pose", lambda d: _carmen(d, "FLASER 3 1.0 2.0 5.0 nan 0 0 0.5 0 0 1.0 host 1.0\n")),
        ("negative count", lambda d: _carmen(d, "FLASER -2 1.0 2.0 0 0 0 0 0 0 1.0 host 1.0\n")),
        (
            "count 10**26",
            lambda d: _carmen(d, "FLASER 100000000000000000000000000 1.0 0 0 0 0 0 0 1.0 h 1.0\n"),
        ),
        ("count 10**9", lambda d: _carmen(d, "FLASER 1000000000 1.0 0 0 0 0 0 0 1.0 h 1.0\n")),
        ("short line", lambda d: _carmen(d, "FLASER 3 1.0 2.0\n")),
        (
            "ROBOTLASER1 with n_rem = -2",
            lambda d: _carmen(
                d,
                "ROBOTLASER1 0 -1.5 3.0 1.0 0 5.0 0.01 0 3 1.0 2.0 3.0 -2 0.1 0.2"
                " 0 0 0 0 0 0 0 0 0 0 0 1.0 host 1.0\n",
            ),
        ),
        (
            "ROBOTLASER1 in degrees",
            lambda d: _carmen(
                d,
                "ROBOTLASER1 0 -90 180 1 0 5.0 0.01 0 3 1.0 2.0 3.0"
                " 0 0 0 0 0 0 0 0 0 0 0 0 0 1.0 host 1.0\n",
            ),
        ),
        ("count 1.5", lambda d: _carmen(d, "FLASER 1.5 1.0 2.0 0 0 0 0 0 0 1.0 host 1.0\n")),
        ("only comments", lambda d: _carmen(d, "# nothing\nODOM 0 0 0 0 0 0 1.0 h 1.0\n")),
    ]
)

spec(
    "navkit.mapping.LaserScan",
    lambda c: call(
        LaserScan,
        A([0.8, 1.5, 2.5]),
        angle_min=-1.0,
        angle_increment=0.5,
        range_min=0.1,
        range_max=4.0,
    ),
    # REP 117: NaN an erroneous reading, +inf no return, -inf an object closer than range_min.
    # Intensities are kept as the driver gave them, non-finite ones too (documented).
    kinds={
        "ranges": Array(allow={"nan", "posinf", "neginf"}),
        "intensities": Array(optional=True, allow={"nan", "posinf", "neginf"}),
    },
)
spec("navkit.mapping.LaserScan.angles", lambda c: method(scan(), "angles"))
spec("navkit.mapping.LaserScan.valid_mask", lambda c: method(scan(), "valid_mask"))
spec(
    "navkit.mapping.LaserScan.to_points",
    lambda c: method(scan(), "to_points", pose()),
    kinds={"pose": OPT_POSE},
)
spec(
    "navkit.mapping.LaserScan.to_local_grid",
    lambda c: method(
        scan(), "to_local_grid", half_width=1.0, resolution=0.1, mount=call(Pose2D, 0.1, 0.0, 0.3)
    ),
    kinds={"mount": OPT_POSE},
)
spec(
    "navkit.mapping.LocalGrid",
    lambda c: call(LocalGrid, np.eye(7, dtype=bool), resolution=0.1, half_width=0.3),
)
spec(
    "navkit.mapping.LocalGrid.from_points",
    lambda c: call(
        LocalGrid.from_points, A([[0.5, 0.0], [0.3, 0.3]]), half_width=0.6, resolution=0.1
    ),
)
spec(
    "navkit.mapping.LocalGrid.cell_to_world",
    lambda c: method(local_grid(), "cell_to_world", A([[1, 2], [6, 6]])),
)
spec(
    "navkit.mapping.LocalGrid.world_to_cell",
    lambda c: method(local_grid(), "world_to_cell", A([[0.1, 0.2], [-0.5, 0.55]])),
)
spec(
    "navkit.mapping.LocalGrid.contains",
    lambda c: method(local_grid(), "contains", A([[0.1, 0.2], [-5.0, 0.0]])),
)

spec(
    "navkit.mapping.OccupancyGrid",
    lambda c: call(
        OccupancyGrid, np.linspace(-3, 3, 12).reshape(3, 4), resolution=0.1, origin=(1.0, -2.0, 0.3)
    ),
)
spec(
    "navkit.mapping.OccupancyGrid.empty",
    lambda c: call(OccupancyGrid.empty, width=1.0, height=0.5, resolution=0.1),
)
spec(
    "navkit.mapping.OccupancyGrid.from_occupancy",
    lambda c: call(
        OccupancyGrid.from_occupancy,
        OCCUPIED.copy(),
        resolution=0.1,
        origin=(-0.2, -0.1, 0.0),
        unknown=UNKNOWN.copy(),
    ),
    kinds={"occupied": Array(boolean=True), "unknown": Array(boolean=True, optional=True)},
)
spec(
    "navkit.mapping.OccupancyGrid.from_probabilities",
    lambda c: call(
        OccupancyGrid.from_probabilities, A([[0.1, 0.5, 0.9], [0.0, 1.0, 0.3]]), resolution=0.1
    ),
)


def _box() -> Any:
    from shapely.geometry import box

    return box(0.2, 0.2, 0.6, 0.5)


GEOMETRIES = Anything()
spec(
    "navkit.mapping.OccupancyGrid.from_polygons",
    lambda c: call(
        OccupancyGrid.from_polygons, [_box()], bounds=A([0.0, 0.0, 1.0, 1.0]), resolution=0.1
    ),
    kinds={"geometries": GEOMETRIES},
)
spec(
    "navkit.mapping.rasterize_polygons",
    lambda c: call(rasterize_polygons, [_box()], bounds=A([0.0, 0.0, 1.0, 1.0]), resolution=0.1),
    kinds={"geometries": GEOMETRIES},
)
spec(
    "navkit.mapping.OccupancyGrid.cell_to_world",
    lambda c: method(grid(), "cell_to_world", A([[1, 2], [7, 9]])),
)
spec(
    "navkit.mapping.OccupancyGrid.world_to_cell",
    lambda c: method(grid(), "world_to_cell", A([[0.1, 0.2], [-5.0, 0.3]])),
)
spec(
    "navkit.mapping.OccupancyGrid.contains",
    lambda c: method(grid(), "contains", A([[0.1, 0.2], [-5.0, 0.3]])),
)
spec("navkit.mapping.OccupancyGrid.copy", lambda c: method(grid(), "copy"))
spec("navkit.mapping.OccupancyGrid.probability", lambda c: method(grid(), "probability"))
spec(
    "navkit.mapping.OccupancyGrid.occupied",
    lambda c: method(grid(), "occupied", 0.6),
    kinds={"threshold": Real(optional=True)},
)
spec(
    "navkit.mapping.OccupancyGrid.free",
    lambda c: method(grid(), "free", 0.3),
    kinds={"threshold": Real(optional=True)},
)
spec(
    "navkit.mapping.OccupancyGrid.unknown",
    lambda c: method(grid(), "unknown", occupied_thresh=0.7, free_thresh=0.2),
)
spec("navkit.mapping.OccupancyGrid.inflate", lambda c: method(grid(), "inflate", 0.15))
# CLEARANCE (review 45): the distance to obstacles, inf everywhere when none is occupied
# (occupied_thresh=1 leaves no cell occupied).
spec(
    "navkit.mapping.OccupancyGrid.obstacle_distance",
    lambda c: method(grid(), "obstacle_distance", occupied_thresh=0.6),
    kinds={"occupied_thresh": Real(optional=True)},
    inf_ok="a grid with no occupied cell is infinitely far from obstacles",
)
# EDT2 (review 46): the same transform of any mask (the diff-astar localiser's
# blocked and free cells); inf everywhere for a mask with no True cell.
spec(
    "navkit.mapping.distance_transform",
    lambda c: call(distance_transform, OCCUPIED.copy(), resolution=0.1),
    kinds={"mask": Array(boolean=True)},
    inf_ok="a mask with no True cell is infinitely far from every cell",
)
# CELLS (session 25): OccupancyGrid.cells_near, the cells new obstacle points block.
# Points inside, outside (0.6 m left of the map: its cells near the edge) and in one cell.
spec(
    "navkit.mapping.OccupancyGrid.cells_near",
    lambda c: method(
        grid(), "cells_near", A([[0.1, 0.2], [-0.8, 0.3], [0.12, 0.21]]), robot_radius=0.15
    ),
)
spec(
    "navkit.mapping.OccupancyGrid.costmap",
    lambda c: method(grid(), "costmap", robot_radius=0.1, inflation_radius=0.3),
)
spec(
    "navkit.mapping.costmap",
    lambda c: call(costmap, grid(), robot_radius=0.1, inflation_radius=0.3),
)
spec(
    "navkit.mapping.OccupancyGrid.traversal_costs",
    lambda c: method(
        grid(), "traversal_costs", robot_radius=0.1, inflation_radius=0.3, unknown_cost=5.0
    ),
    kinds={"unknown_cost": Real(allow={"posinf"})},
    inf_ok="occupied cells cost inf",
)
spec(
    "navkit.mapping.traversal_costs",
    lambda c: call(
        traversal_costs, grid(), robot_radius=0.1, inflation_radius=0.3, unknown_cost=5.0
    ),
    kinds={"unknown_cost": Real(allow={"posinf"})},
    inf_ok="occupied cells cost inf",
)
spec(
    "navkit.mapping.validate_costs",
    lambda c: call(validate_costs, costs()),
    kinds={"costs": Array(allow={"posinf"})},
)
INTEGRATE_KINDS = {"clamp": Array(), "range_max": Real(optional=True)}
spec(
    "navkit.mapping.OccupancyGrid.integrate_scan",
    lambda c: method(grid(), "integrate_scan", scan(), pose()),
    kinds=INTEGRATE_KINDS,
    mutates=("self",),
)
spec(
    "navkit.mapping.integrate_scan",
    lambda c: call(integrate_scan, grid(), scan(), (0.3, 0.3, 0.2)),
    kinds=INTEGRATE_KINDS,
    mutates=("grid",),
)
spec(
    "navkit.mapping.OccupancyGrid.load",
    lambda c: call(OccupancyGrid.load, _saved_map(c)),
    kinds={"path": MAP_FILES},
)
spec(
    "navkit.mapping.io.read_map", lambda c: call(read_map, _saved_map(c)), kinds={"path": MAP_FILES}
)
spec(
    "navkit.mapping.io.map_image_path",
    lambda c: call(map_image_path, _saved_map(c)),
    kinds={"path": MAP_YAML_FILES},
)
MAP_MODE = Choice("trinary", "scale")
spec(
    "navkit.mapping.OccupancyGrid.save",
    lambda c: method(grid(), "save", c.tmp / "out.yaml"),
    kinds={"path": OutPath(), "mode": MAP_MODE},
)
spec(
    "navkit.mapping.io.write_map",
    lambda c: call(write_map, grid(), c.tmp / "out.yaml"),
    kinds={"path": OutPath(), "mode": MAP_MODE},
)


def _saved_map(c: Ctx) -> Path:
    g = OccupancyGrid.from_occupancy(OCCUPIED, resolution=0.1, unknown=UNKNOWN)
    path = c.tmp / "saved.yaml"
    write_map(g, path)
    return path


def _carmen_log(c: Ctx) -> Path:
    return _carmen(c.tmp, _FLASER * 2 + "ODOM 0.5 0 0 0 0 0 12.7 host 12.7\n")


spec(
    "navkit.mapping.io.read_carmen",
    lambda c: call(read_carmen, _carmen_log(c), range_max=4.0),
    kinds={"path": CARMEN_FILES, "range_max": Real(optional=True)},
)
spec(
    "navkit.mapping.io.CarmenLog",
    lambda c: call(
        CarmenLog,
        (scan(),),
        (pose(),),
        (pose(),),
        A([12.5]),
        A([[0.5, 0.0, 0.0, 12.7]]),
    ),
    kinds={
        "scans": SequenceOf(LaserScan),
        "laser_poses": SequenceOf(Pose2D),
        "robot_poses": SequenceOf(Pose2D),
        "times": Array(),  # required: None only lets the deprecated timestamps stand in
        "odometry": Array(),
    },
)


def _grid_msg() -> SimpleNamespace:
    return SimpleNamespace(
        info=SimpleNamespace(
            width=3,
            height=2,
            resolution=0.1,
            origin=SimpleNamespace(
                position=SimpleNamespace(x=1.0, y=-1.0, z=0.0),
                orientation=SimpleNamespace(x=0.0, y=0.0, z=0.0, w=1.0),
            ),
        ),
        data=[0, 100, -1, 50, 0, 0],
    )


def _scan_msg() -> SimpleNamespace:
    return SimpleNamespace(
        ranges=[1.0, 2.0, 0.5],
        intensities=[],
        angle_min=-0.5,
        angle_max=0.5,
        angle_increment=0.5,
        range_min=0.1,
        range_max=4.0,
    )


spec(
    "navkit.mapping.io.grid_from_msg",
    lambda c: call(grid_from_msg, _grid_msg()),
    kinds={"msg": Namespace()},
)
spec(
    "navkit.mapping.io.scan_from_msg",
    lambda c: call(scan_from_msg, _scan_msg()),
    kinds={"msg": Namespace()},
)
spec(
    "navkit.mapping.io.grid_to_msg_fields",
    lambda c: call(grid_to_msg_fields, grid(), mode="trinary"),
    kinds={"mode": MAP_MODE},
)
spec(
    "navkit.mapping.io.OccupancyGridMsgFields",
    lambda c: call(
        OccupancyGridMsgFields,
        2,
        1,
        0.1,
        (0.0, 0.0, 0.0),
        (0.0, 0.0, 0.0, 1.0),
        A([100, 0], dtype=np.int8),
    ),
    kinds={
        "width": INT,
        "height": INT,
        "origin_position": Array(),
        "origin_orientation": Array(),
        "data": Array(),
    },
)

# --------------------------------------------------------------------------- estimation

spec("navkit.estimation.CompassCalibration", lambda c: call(CompassCalibration, unwrap=True))
spec(
    "navkit.estimation.CompassCalibration.__call__",
    lambda c: method(call(CompassCalibration), "__call__", A([45.0, 50.0])),
    kinds={"raw_deg": Array()},
    mutates=("self",),
)
spec(
    "navkit.estimation.CompassCalibration.reset",
    lambda c: method(call(CompassCalibration), "reset", prepare=lambda cal: cal(10.0)),
    mutates=("self",),
)
spec(
    "navkit.estimation.compass_to_yaw",
    lambda c: call(compass_to_yaw, A([10.0, 350.0]), initial_deg=20.0),
)


def _diff_odometry() -> Call:
    return call(DiffOdometry, diff_drive(), ticks_per_rev=1000, bits=16)


spec(
    "navkit.estimation.DiffOdometry",
    lambda c: call(DiffOdometry, diff_drive(), ticks_per_rev=1000, bits=16, pose=pose()),
    kinds={
        "bits": Real(integer=True, optional=True),
        "pose": OPT_POSE,
        "method": ODOMETRY_METHOD,
    },
)
spec(
    "navkit.estimation.DiffOdometry.update",
    lambda c: method(_diff_odometry(), "update", 500, 520, prepare=lambda o: o.update(400, 400)),
    kinds={"left_ticks": INT, "right_ticks": INT},
    mutates=("self",),
)
spec(
    "navkit.estimation.DiffOdometry.update_batch",
    lambda c: method(_diff_odometry(), "update_batch", A([0, 100, 200]), A([0, 110, 230])),
    mutates=("self",),
)
spec(
    "navkit.estimation.DiffOdometry.reset",
    lambda c: method(_diff_odometry(), "reset", pose()),
    kinds={"pose": OPT_POSE},
    mutates=("self",),
)


def _omni_odometry() -> Call:
    return call(OmniOdometry, omni_drive(), pose=pose())


spec(
    "navkit.estimation.OmniOdometry",
    lambda c: call(OmniOdometry, omni_drive(), pose=pose()),
    kinds={"pose": OPT_POSE},
)
# APIFIX (review 21): OmniOdometry.reset(pose), as DiffOdometry.reset.
spec(
    "navkit.estimation.OmniOdometry.reset",
    lambda c: method(_omni_odometry(), "reset", pose()),
    kinds={"pose": OPT_POSE},
    mutates=("self",),
)
spec(
    "navkit.estimation.OmniOdometry.update",
    lambda c: method(_omni_odometry(), "update", A([0.3, -0.2, 0.1]), 0.4),
    kinds={"yaw": REAL},
    mutates=("self",),
)
spec(
    "navkit.estimation.OmniOdometry.update_batch",
    lambda c: method(
        _omni_odometry(), "update_batch", A([[0.3, -0.2, 0.1], [0.1, 0.1, 0.1]]), A([0.4, 0.5])
    ),
    mutates=("self",),
)

F_MATRIX = A([[1.0, 0.1], [0.0, 1.0]])


def _f(x: np.ndarray) -> np.ndarray:
    return F_MATRIX @ x


def _h(x: np.ndarray) -> np.ndarray:
    return x[:1]


def _ekf() -> Call:
    return call(ExtendedKalmanFilter, A([0.0, 1.0]), np.eye(2), angle_states=())


EKF_KINDS = {"angle_states": IntSequence()}


def _past_float64(ekf: ExtendedKalmanFilter) -> bool:
    """The documented limit: a covariance whose condition number nears 1/eps (class notes)."""
    return bool(np.linalg.cond(ekf.P) > 1e15)


spec(
    "navkit.estimation.ExtendedKalmanFilter",
    lambda c: call(
        ExtendedKalmanFilter, A([0.0, 1.0]), A([[1.0, 0.1], [0.1, 2.0]]), angle_states=(0,)
    ),
    kinds=EKF_KINDS,
)
spec(
    "navkit.estimation.ExtendedKalmanFilter.predict",
    lambda c: method(_ekf(), "predict", _f, F_MATRIX.copy(), 0.01 * np.eye(2)),
    kinds={"f": Function(), "F": MatrixOrFunction()},
    mutates=("self",),
    degenerate=_past_float64,
)
spec(
    "navkit.estimation.ExtendedKalmanFilter.update",
    lambda c: method(_ekf(), "update", A([0.12]), _h, A([[1.0, 0.0]]), A([[0.01]]), gate=20.0),
    kinds={
        "h": Function(),
        "H": MatrixOrFunction(),
        "angle_measurements": IntSequence(),
        "gate": Real(optional=True),
    },
    mutates=("self",),
    nan_ok=_uncomputed_nis,
    inf_ok=_rejected,
    degenerate=_past_float64,
)
spec(
    "navkit.estimation.UpdateResult",
    lambda c: call(UpdateResult, False, 30.2, A([5.0]), "rejected by the gate"),
    kinds={"reason": Text(optional=True), "nis": Real(allow={"nan", "posinf"})},
)
spec(
    "navkit.estimation.FusionStatus",
    lambda c: call(FusionStatus, 1),
    kinds={"value": INT}
    | {p: Ignored() for p in ("names", "module", "qualname", "type", "start", "boundary")},
)
spec(
    "navkit.estimation.FusionResult",
    lambda c: call(
        FusionResult,
        A([0.1, 0.2]),
        np.zeros((2, 6)),
        np.stack([np.eye(6)] * 2),
        A([0, 1], dtype=np.int8),
        A([0.5, 3.0]),
    ),
    # nis: NaN when not computed, inf when it overflowed (documented).
    kinds={"nis": Array(allow={"nan", "posinf"}), "status": Array()},
)
spec(
    "navkit.estimation.MeasurementLog",
    lambda c: call(
        MeasurementLog,
        A([0.1, 0.2]),
        A([[0.0, 1.0, 0.1, 0.0], [0.05, 0.0, 0.0, 0.0]]),
        np.full((2, 4), 1e-3),
        A([[False, True, True, False], [True, False, False, False]]),
    ),
    kinds={
        "observed": Array(boolean=True),
        # Entries not observed are ignored, whatever they hold.
        "values": Array(allow={"nan", "posinf", "neginf"}),
        "variances": Array(allow={"nan", "posinf", "neginf"}),
    },
)
STREAM = Array(optional=True)
spec(
    "navkit.estimation.MeasurementLog.from_streams",
    lambda c: call(
        MeasurementLog.from_streams,
        odometry=(A([0.0, 0.1]), A([1.0, 1.0]), A([0.0, 0.0])),
        yaw=(A([0.05]), A([0.0])),
        yaw_rate=(A([0.07]), A([0.1])),
        acceleration=(A([0.08]), A([0.2])),
    ),
    kinds={
        "odometry": STREAM,
        "odometry_variance": Array(),
        "yaw": STREAM,
        "yaw_variance": Array(),
        "yaw_rate": STREAM,
        "yaw_rate_variance": Array(),
        "acceleration": STREAM,
        "acceleration_variance": Array(),
    },
)


def _fusion() -> Call:
    return call(PlanarFusion, t0=0.0)


spec(
    "navkit.estimation.PlanarFusion",
    lambda c: call(
        PlanarFusion,
        np.zeros(6),
        np.eye(6) * 0.1,
        process_noise=np.full(6, 1e-3),
        t0=0.0,
        gate_probability=0.99,
        history=0.5,  # FUSION (review 22): late measurements within 0.5 s
    ),
    kinds={
        "x0": Array(optional=True),
        "P0": Array(optional=True),
        "process_noise": Array(optional=True),
        "t0": Real(optional=True),
        "gate_probability": Real(optional=True),
        "pose": OPT_POSE,
        "history": Real(),  # FUSION (review 22)
    },
)
FUSION: dict[str, Any] = {"mutates": ("self",), "nan_ok": _uncomputed_nis, "inf_ok": _rejected}
spec(
    "navkit.estimation.PlanarFusion.predict", lambda c: method(_fusion(), "predict", 0.5), **FUSION
)
spec(
    "navkit.estimation.PlanarFusion.update_odometry",
    lambda c: method(
        _fusion(), "update_odometry", 0.1, 1.0, 0.1, v_variance=1e-3, omega_variance=1e-3
    ),
    **FUSION,
)
spec(
    "navkit.estimation.PlanarFusion.update_speed",
    lambda c: method(_fusion(), "update_speed", 0.1, 1.0, variance=1e-3),
    **FUSION,
)
spec(
    "navkit.estimation.PlanarFusion.update_yaw",
    lambda c: method(_fusion(), "update_yaw", 0.1, 0.2, variance=1e-3),
    **FUSION,
)
spec(
    "navkit.estimation.PlanarFusion.update_yaw_rate",
    lambda c: method(_fusion(), "update_yaw_rate", 0.1, 0.2, variance=1e-3),
    **FUSION,
)
spec(
    "navkit.estimation.PlanarFusion.update_acceleration",
    lambda c: method(_fusion(), "update_acceleration", 0.1, 0.3, variance=1e-2),
    **FUSION,
)
spec(
    "navkit.estimation.PlanarFusion.update_batch",
    lambda c: method(_fusion(), "update_batch", log()),
    nan_ok="FusionResult.nis is NaN for out-of-order rows",
    mutates=("self",),
)
# FUSION (review 23): reset(x0, P0, *, t0, pose), the constructor's state arguments, on
# a filter with steps kept for history (a refused reset keeps them).
spec(
    "navkit.estimation.PlanarFusion.reset",
    lambda c: method(
        call(PlanarFusion, t0=0.0, history=0.5),
        "reset",
        A([1.0, 2.0, 0.5, 0.3, 0.0, 0.0]),
        np.eye(6) * 0.1,
        t0=1.0,
        prepare=lambda f: f.update_odometry(0.1, 1.0, 0.1, v_variance=1e-3, omega_variance=1e-3),
    ),
    kinds={
        "x0": Array(optional=True),
        "P0": Array(optional=True),
        "t0": Real(optional=True),
        "pose": OPT_POSE,
    },
    mutates=("self",),
)

# --------------------------------------------------------------------------- planning.grid

CONNECTIVITY = Choice(8, 4)
COSTS = Array(allow={"posinf"})
spec(
    "navkit.planning.grid.AStarPlanner",
    lambda c: call(
        AStarPlanner, costs(), connectivity=8, corner_cutting=False, heuristic_weight=1.0
    ),
    kinds={"costs": COSTS, "connectivity": CONNECTIVITY},
)


def _astar_planner() -> Call:
    return call(AStarPlanner, costs())


spec(
    "navkit.planning.grid.AStarPlanner.plan",
    lambda c: method(_astar_planner(), "plan", (5, 0), (0, 6)),
    kinds={"start_cell": Cell(), "goal_cell": Cell()},
)
spec(
    "navkit.planning.grid.AStarPlanner.distance_field",
    lambda c: method(_astar_planner(), "distance_field", (0, 6)),
    kinds={"goal_cell": Cell()},
    inf_ok="unreachable cells",
)
spec(
    "navkit.planning.grid.astar",
    lambda c: call(astar, costs(), (5, 0), (0, 6), corner_cutting=True, heuristic_weight=1.5),
    kinds={"costs": COSTS, "start_cell": Cell(), "goal_cell": Cell(), "connectivity": CONNECTIVITY},
)
spec(
    "navkit.planning.grid.distance_field",
    lambda c: call(distance_field, costs(), (0, 6), connectivity=4),
    kinds={"costs": COSTS, "goal_cell": Cell(), "connectivity": CONNECTIVITY},
    inf_ok="unreachable cells",
)
NODE = Cell(integer=False)
spec(
    "navkit.planning.grid.field_dstar",
    lambda c: call(field_dstar, costs(), (6, 0), (0, 7)),
    kinds={"costs": COSTS, "start_node": NODE, "goal_node": NODE},
)


# STARTTOL (session 25): FieldDStar(obstacles=) and the world methods' start_tolerance.
# Cell (1, 3) of costs() is impassable but no obstacle (the inflation): a start
# there, (2.75, 2.65) at 0.5 m cells from (1, 2), escapes to cell (0, 3), 0.4 m away.
def _fd_obstacles() -> np.ndarray:
    out = ~np.isfinite(costs())
    out[1, 3] = False
    return out


def _fd_escaping(name: str, *args: Any, planned: bool = False) -> Call:
    receiver = call(
        FieldDStar, costs(), resolution=0.5, origin=(1.0, 2.0, 0.0), obstacles=_fd_obstacles()
    )
    prepare = (lambda p: p.plan((6, 0), (0, 7))) if planned else None
    return method(receiver, name, *args, prepare=prepare, start_tolerance=0.5)


FD_OBSTACLES = {"obstacles": Array(boolean=True, optional=True)}


class _FlagsKind(Array):
    """``update_costs(obstacles=)``: a bool (every cell listed) or a boolean array."""

    refuse_always = Array.refuse_always - {"bool"}

spec(
    "navkit.planning.grid.FieldDStar",
    lambda c: call(
        FieldDStar,
        costs(),
        interpolate=True,
        lookahead=False,
        smooth=True,
        resolution=0.5,
        origin=(1.0, 2.0, 0.0),
        obstacles=_fd_obstacles(),
    ),
    kinds={"costs": COSTS, **FD_OBSTACLES},
)


def _field_dstar(planned: bool = False) -> Call:
    prepare = (lambda p: p.plan((6, 0), (0, 7))) if planned else None
    return call(FieldDStar, costs(), resolution=0.5, origin=(1.0, 2.0, 0.0)), prepare


def _fd_method(name: str, *args: Any, planned: bool = False, **kwargs: Any) -> Call:
    receiver, prepare = _field_dstar(planned)
    return method(receiver, name, *args, prepare=prepare, **kwargs)


FD = {"mutates": ("self",)}
spec(
    "navkit.planning.grid.FieldDStar.plan",
    lambda c: _fd_method("plan", (6, 0), (0, 7)),
    kinds={"start_node": NODE, "goal_node": NODE},
    **FD,
)
spec(
    "navkit.planning.grid.FieldDStar.plan_cells",
    lambda c: _fd_method("plan_cells", (5, 0), (0, 6)),
    kinds={"start_cell": Cell(), "goal_cell": Cell()},
    **FD,
)
spec(
    "navkit.planning.grid.FieldDStar.plan_world",
    lambda c: _fd_escaping("plan_world", A([2.75, 2.65]), A([4.3, 4.8])),
    **FD,
)
spec(
    "navkit.planning.grid.FieldDStar.replan",
    lambda c: _fd_method("replan", (5, 0), planned=True),
    kinds={"start_node": Cell(integer=False, optional=True)},
    **FD,
)
spec(
    "navkit.planning.grid.FieldDStar.replan_world",
    lambda c: _fd_escaping("replan_world", A([2.75, 2.65]), planned=True),
    kinds={"start_xy": Array(optional=True)},
    **FD,
)
spec(
    "navkit.planning.grid.FieldDStar.update_costs",
    lambda c: _fd_method(
        "update_costs", A([[2, 1], [2, 2]]), A([np.inf, 3.0]), planned=True,
        obstacles=A([True, False]),
    ),
    kinds={
        "new_costs": Array(allow={"posinf"}),
        "obstacles": _FlagsKind(boolean=True, optional=True),
    },
    **FD,
)
spec(
    "navkit.planning.grid.FieldDStar.world_to_node",
    lambda c: _fd_method("world_to_node", A([[1.6, 2.2], [-9.0, 0.0]])),
)
spec(
    "navkit.planning.grid.FieldDStar.node_to_world",
    lambda c: _fd_method("node_to_world", A([[2, 1], [0, 7]])),
)

PLANNER = Choice("astar", "field_dstar", callable_ok=True)


def _plan_args(c: Ctx) -> tuple[Call, tuple[float, float], tuple[float, float, float]]:
    return grid(), (0.1, 0.2), (0.6, 0.5, 0.0)


spec(
    "navkit.planning.grid.plan_path",
    lambda c: call(
        plan_path, grid(), A([0.1, 0.2]), A([0.6, 0.5, 0.0]), robot_radius=0.05, unknown_cost=5.0
    ),
    kinds={
        "start": PoseLike("Pose2D"),
        "goal": PoseLike("Pose2D"),
        "planner": PLANNER,
        "unknown_cost": Real(allow={"posinf"}),
    },
)
spec(
    "navkit.planning.grid.MapPlanner",
    lambda c: call(
        MapPlanner,
        grid(),
        robot_radius=0.05,
        inflation_radius=0.2,
        unknown_cost=5.0,
        planner="field_dstar",
    ),
    kinds={"planner": PLANNER, "unknown_cost": Real(allow={"posinf"})},
    inf_ok="MapPlanner.costs: occupied cells cost inf",
)
spec(
    "navkit.planning.grid.MapPlanner.plan",
    # The start lies within robot_radius of the obstacle column: the call
    # escapes (start_tolerance) to the free cell beside it.
    lambda c: method(
        call(MapPlanner, grid(), robot_radius=0.1),
        "plan",
        A([0.24, 0.2]),
        call(Pose2D, 0.6, 0.5, 1.0),
        start_tolerance=0.15,
    ),
    kinds={"start": PoseLike("Pose2D"), "goal": PoseLike("Pose2D")},
)
spec(
    "navkit.planning.grid.Path2D",
    lambda c: call(
        Path2D,
        A([[0.0, 0.0], [1.0, 1.0], [1.0, 2.0]]),
        "grid",
        cost=2.414,
        length=2.414,
        expanded=3,
    ),
    kinds={"frame": Choice("grid", "world"), "expanded": INT},
)
# Review 53: a path converts itself between the frames of the map it is on.
spec(
    "navkit.planning.grid.Path2D.to_world",
    lambda c: method(
        call(
            Path2D,
            A([[0.0, 0.0], [1.0, 1.0], [1.0, 2.0]]),
            "grid",
            cost=2.4,
            length=2.4,
            expanded=3,
        ),
        "to_world",
        grid(),
    ),
    kinds={"frame": Choice("grid"), "expanded": INT, "grid": Obj((OccupancyGrid, LocalGrid))},
)
spec(
    "navkit.planning.grid.Path2D.to_grid",
    lambda c: method(
        call(Path2D, A([[0.0, 0.0], [0.3, 0.2]]), "world", cost=0.4, length=0.36, expanded=3),
        "to_grid",
        local_grid(),
    ),
    kinds={"frame": Choice("world"), "expanded": INT, "grid": Obj((OccupancyGrid, LocalGrid))},
)
spec(
    "navkit.planning.grid.CellPlanner",
    lambda c: call(CellPlanner),
    expect_error=TypeError,
)

# --------------------------------------------------------------------------- planning.reactive

GOAL = A([1.0, 0.5])
POINTS = A([[0.0, 0.0], [2.0, -1.0], [1.0, 0.4]])
OBSTACLES = A([[0.5, 0.5], [1.5, -0.5]])

FIELDS: dict[str, Any] = {
    "ParaboloidAttraction": lambda: call(
        ParaboloidAttraction, GOAL.copy(), k_att=2.0, c=1.0, a=1.0, b=2.0
    ),
    "ConicAttraction": lambda: call(
        ConicAttraction, GOAL.copy(), m=2.0, u_trans=1.0, threshold_radius=0.2
    ),
    "BlendedAttraction": lambda: call(
        BlendedAttraction, GOAL.copy(), threshold_radius=1.0, width=0.1
    ),
    "PiecewiseAttraction": lambda: call(
        PiecewiseAttraction, GOAL.copy(), alpha=2.0, goal_radius=0.5, spread=1.0
    ),
    "KhatibRepulsion": lambda: call(
        KhatibRepulsion, OBSTACLES.copy(), k_rep=1.0, influence_radius=1.0
    ),
    "PiecewiseRepulsion": lambda: call(
        PiecewiseRepulsion, OBSTACLES.copy(), delta=5.0, beta=2.0, obstacle_radius=0.3, spread=1.0
    ),
    "CompositeField": lambda: call(
        CompositeField,
        [
            call(ConicAttraction, GOAL.copy()),
            call(KhatibRepulsion, OBSTACLES.copy(), influence_radius=2.0),
        ],
    ),
}
REPULSIVE = {"KhatibRepulsion": "a Khatib potential is inf on an obstacle"}
for _name, _make in FIELDS.items():
    _key = f"navkit.planning.reactive.{_name}"
    _inf = REPULSIVE.get(_name)
    spec(
        _key,
        lambda c, m=_make: m(),
        kinds={"fields": SequenceOf(PotentialField)} if _name == "CompositeField" else {},
    )
    spec(f"{_key}.force", lambda c, m=_make: method(m(), "force", POINTS.copy()), inf_ok=_inf)
    spec(
        f"{_key}.potential", lambda c, m=_make: method(m(), "potential", POINTS.copy()), inf_ok=_inf
    )
    spec(
        f"{_key}.__add__",
        lambda c, m=_make: method(m(), "__add__", call(ConicAttraction, GOAL.copy())),
        kinds={"other": Obj(PotentialField)},
    )
    spec(
        f"{_key}.__radd__",
        lambda c, m=_make: method(m(), "__radd__", 0),
        kinds={"other": Anything()},
    )
    if "Attraction" in _name:
        spec(f"{_key}.with_goal", lambda c, m=_make: method(m(), "with_goal", A([-1.0, 2.0])))
spec(
    "navkit.planning.reactive.BlendedAttraction.sigma",
    lambda c: method(FIELDS["BlendedAttraction"](), "sigma", A([0.5, 1.0, 3.0])),
)
spec(
    "navkit.planning.reactive.PotentialField",
    lambda c: call(PotentialField),
    expect_error=TypeError,
)
spec(
    "navkit.planning.reactive.AttractiveField",
    lambda c: call(AttractiveField, GOAL.copy()),
    expect_error=TypeError,
)


def _sampled() -> Call:
    return call(
        sample_field,
        FIELDS["ConicAttraction"](),
        xlim=A([-1.0, 1.0]),
        ylim=A([-0.5, 0.5]),
        resolution=0.5,
    )


spec(
    "navkit.planning.reactive.sample_field",
    lambda c: call(
        sample_field,
        FIELDS["BlendedAttraction"](),
        xlim=A([-1.0, 1.0]),
        ylim=A([-0.5, 0.5]),
        resolution=0.25,
    ),
    kinds={"field": Obj(PotentialField)},
)
spec(
    "navkit.planning.reactive.SampledField",
    lambda c: call(
        SampledField,
        A([-0.75, -0.25, 0.25, 0.75]),
        A([-0.25, 0.25]),
        np.ones((2, 4)),
        np.zeros((2, 4, 2)),
        resolution=0.5,
    ),
    kinds={"potential": Array(allow={"posinf"})},  # a Khatib potential is inf on an obstacle
)
spec(
    "navkit.planning.reactive.SampledField.world_to_cell",
    lambda c: method(_sampled(), "world_to_cell", A([[0.3, 0.2], [-1.0, 0.0]])),
)
spec(
    "navkit.planning.reactive.SampledField.cell_to_world",
    lambda c: method(_sampled(), "cell_to_world", A([[1, 2], [0, 0]])),
)
spec(
    "navkit.planning.reactive.SampledField.contains",
    lambda c: method(_sampled(), "contains", A([[0.3, 0.2], [-1.0, 0.0]])),
)
spec(
    "navkit.planning.reactive.GreedyStep",
    lambda c: call(GreedyStep, (10, 12), A([0.2, 0.0]), g=0.2, h=1.8, candidates=440),
    kinds={"cell": Cell(), "candidates": INT},
)
spec(
    "navkit.planning.reactive.greedy_step",
    lambda c: call(greedy_step, local_grid(), A([2.0, 0.3]), require_progress=True),
)
spec(
    "navkit.planning.reactive.repulsive_force_from_scan",
    # A LiDAR mounted off the robot's centre and turned (review 46).
    lambda c: call(
        repulsive_force_from_scan,
        scan(),
        k_rep=1.0,
        influence_radius=1.0,
        mount=call(Pose2D, -0.2, 0.1, 0.3),
    ),
    kinds={"mount": OPT_POSE},
)
spec(
    "navkit.planning.reactive.piecewise_repulsive_force_from_scan",
    lambda c: call(
        piecewise_repulsive_force_from_scan,
        scan(),
        delta=1.0,
        beta=2.0,
        obstacle_radius=0.2,
        spread=1.0,
        mount=call(Pose2D, 0.15, 0.0, -0.4),
    ),
    kinds={"mount": OPT_POSE},
)

# --------------------------------------------------------------------------- control


def _controller() -> Call:
    return call(
        PotentialFieldController, call(ConicAttraction, A([0.0, 0.0])), max_speed=0.5, drive="omni"
    )


CONTROLLER_MODE = Choice("omni", "diff")
# Rows with NaN/inf are skipped (documented): players not seen.
OBSTACLES_ARG = Array(optional=True, allow={"nan", "posinf", "neginf"})
spec(
    "navkit.control.PotentialFieldController",
    lambda c: call(
        PotentialFieldController,
        call(ConicAttraction, A([0.0, 0.0])),
        k_rep=0.05,
        max_speed=0.5,
        drive="diff",
    ),
    kinds={"drive": CONTROLLER_MODE, "attraction": Obj(AttractiveField, optional=True)},
)
spec(
    "navkit.control.PotentialFieldController.desired_velocity",
    lambda c: method(
        _controller(),
        "desired_velocity",
        pose(),
        A([2.0, 1.0]),
        obstacles=A([[1.5, 1.5], [0.0, 3.0]]),
        mount=call(Pose2D, 0.1, 0.0, 0.0),  # checked; used with a scan only
    ),
    kinds={"obstacles": OBSTACLES_ARG, "mount": OPT_POSE},
)
spec(
    "navkit.control.PotentialFieldController.step",
    lambda c: method(
        _controller(),
        "step",
        pose(),
        call(Pose2D, 2.0, 1.0, 0.0),
        dt=0.1,
        obstacles=A([[1.5, 1.5]]),
        velocity=A([0.1, 0.0, 0.0]),
        mount=call(Pose2D, 0.1, 0.0, 0.0),  # checked; used with a scan only
    ),
    kinds={
        "obstacles": OBSTACLES_ARG,
        "velocity": PoseLike("Twist2D", optional=True),
        "mount": OPT_POSE,
    },
    mutates=("self",),
)
spec(
    "navkit.control.PotentialFieldController.reset",
    lambda c: method(
        _controller(), "reset", prepare=lambda ctl: ctl.step((0, 0, 0), (1, 0, 0), dt=0.1)
    ),
    mutates=("self",),
)
spec(
    "navkit.control.limit_velocity_change",
    lambda c: call(
        limit_velocity_change, A([0.0, 0.0]), A([1.0, 0.2]), max_accel=0.5, max_decel=2.0, dt=0.1
    ),
)

# --------------------------------------------------------------------------- behaviours

spec(
    "navkit.behaviours.GameState",
    lambda c: call(
        GameState,
        robot_xy=A([0.0, 0.0]),
        ball_xy=A([1.0, 0.2]),
        teammates_xy=A([[-2.0, 1.0]]),
        opponents_xy=A([[2.0, 0.5], [3.0, -1.0]]),
        own_goal_xy=A([-4.5, 0.0]),
        opponent_goal_xy=A([4.5, 0.0]),
        has_ball=False,
        opponent_with_ball=None,
    ),
    kinds={
        "has_ball": Flag(optional=True),
        "opponent_with_ball": Real(integer=True, optional=True),
        "teammates_xy": Array(allow={"nan"}),  # NaN rows: players not seen
        "opponents_xy": Array(allow={"nan"}),
    },
)
spec(
    "navkit.behaviours.BehaviourTarget",
    lambda c: call(BehaviourTarget, A([1.0, 0.0]), A([[2.0, 1.0], [3.0, -1.0]])),
    kinds={"obstacles_xy": Array(allow={"nan"})},
)
for _role in (attack, support, defend):
    spec(f"navkit.behaviours.{_role.__name__}", lambda c, r=_role: call(r, game_state()))

# Unused helpers kept importable for new specs.
_ = (partial, math)
import fuzz_specs_bags  # noqa: E402, F401 - registers the ROS bag readers and quaternion specs
import fuzz_specs_cli  # noqa: E402, F401
import fuzz_specs_control  # noqa: E402, F401 - registers navkit.control's tracker specs
import fuzz_specs_framework  # noqa: E402, F401 - registers the experiment framework's specs
import fuzz_specs_jps  # noqa: E402, F401
import fuzz_specs_movingai  # noqa: E402, F401
import fuzz_specs_plot  # noqa: E402, F401
import fuzz_specs_scan_matching  # noqa: E402, F401
import fuzz_specs_scn_diff_astar  # noqa: E402, F401
import fuzz_specs_scn_indoor  # noqa: E402, F401
import fuzz_specs_scn_omni_greedy  # noqa: E402, F401
import fuzz_specs_scn_soccer  # noqa: E402, F401
import fuzz_specs_sim  # noqa: E402, F401 - registers navkit.sim specs
import fuzz_specs_sim_adapters  # noqa: E402, F401
import fuzz_specs_warmup  # noqa: E402, F401
