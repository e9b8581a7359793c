"""ROS 1 ``.bag`` files and ROS 2 bag folders, read without ROS (the ``rosbags`` package).

One reader per message type, each returning a frozen result of time-stamped
arrays: :func:`read_bag_scans` (``sensor_msgs/LaserScan``),
:func:`read_bag_odometry` (``nav_msgs/Odometry``) and :func:`read_bag_imu`
(``sensor_msgs/Imu``); :func:`bag_topics` lists what a bag holds.

Times: ``times`` are the messages' header stamps (when the data was taken;
what robot_localization and tf use), ``record_times`` when the bag recorder
received them; messages stay in record order, which need not be stamp order.
A stamp's ``sec`` and ``nanosec`` become float64 seconds
``sec + nanosec · 1e-9``, which resolves nanoseconds only below 2**23 s
(97 days: simulation time); at wall-clock stamps (1.7e9 s in 2024) consecutive
float64 values lie 2.4e-7 s apart, so a stamp is rounded to within about
0.12 µs and a difference of stamps to within about 0.24 µs. A stamp of 0 (a driver that does not
set it) is kept as 0: use ``record_times`` for such topics.

Memory: bags are read one chunk at a time (a ROS 1 bag whose index rosbags
refuses too: navkit's chunk walker streams it), keeping the messages of the
topic read until each is converted.

Damaged or malicious bags: ROS 1 chunks are decompressed at most to the size
their header declares, and never past :data:`CHUNK_MAX`; a ROS 2 bag's
``metadata.yaml`` must be a regular file of at most :data:`METADATA_MAX` bytes
with topic names, types and counts of the right YAML types. ROS 2 bags
compressed with zstd (``compression_mode`` ``file`` or ``message``, both read)
are decompressed by ``rosbags`` with no bound on what comes out: in ``file``
mode every storage file into a temporary folder when the bag is opened, in
``message`` mode one message at a time in memory. Read such bags only from a
source you trust, or decompress them first (``ros2 bag convert``).

Files are read only if they are regular files, checked on the descriptor each
is read from (not by name before an open by name): navkit reads the ROS 1 bag
itself that way, and hands rosbags a path (:class:`_CheckedPath`) whose opens
do the same, for the ROS 1 bag, a ROS 2 bag's ``metadata.yaml`` and its MCAP
storage files. A FIFO put in their place is refused with a ``ValueError``,
never read (it would block for ever). One limit remains: rosbags has SQLite
open a ROS 2 bag's ``.db3`` files by name, so a FIFO swapped in for one between
rosbags' check and SQLite's open would block the read.
"""

from __future__ import annotations

import bz2
import importlib
import io
import os
import struct
import warnings
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager, suppress
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any, BinaryIO, NamedTuple, TypeVar

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.deprecation import renamed_keyword
from navkit._shared.dunders import bounded_repr
from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.text import as_text
from navkit._shared.times import as_times
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_bool, as_float_array, as_sequence
from navkit.geometry import imu_to_base, quaternion_to_matrix, quaternion_to_yaw, wrap_angle
from navkit.mapping import LaserScan
from navkit.mapping.io._paths import as_path, missing_file, open_regular
from navkit.mapping.io._ros_msgs import scan_from_msg

__all__ = [
    "BagImu",
    "BagOdometry",
    "BagScans",
    "bag_topics",
    "read_bag_imu",
    "read_bag_odometry",
    "read_bag_scans",
]

SCAN_TYPE = "sensor_msgs/msg/LaserScan"
ODOMETRY_TYPE = "nav_msgs/msg/Odometry"
IMU_TYPE = "sensor_msgs/msg/Imu"

_ROS1_MAGIC = b"#ROSBAG V2.0\n"
#: The most a ROS 1 bag chunk may declare to hold decompressed, bytes. roscpp sends
#: no message over 1e9 bytes and rosbag closes a chunk past 768 KiB by default, so
#: only a damaged or malicious bag declares more (a few kilobytes of bz2 can
#: decompress to gigabytes).
CHUNK_MAX = 1 << 30
#: The largest ROS 2 ``metadata.yaml`` read, bytes. rosbag2 writes some hundred
#: bytes a topic and a file (a bag split in 10,000 files: about 2 MB); rosbags
#: reads the file whole and parses it in pure Python.
METADATA_MAX = 1 << 24


# ---------------------------------------------------------------- result classes
def _frozen(value: ArrayLike, name: str, shape: tuple[int | None, ...]) -> FloatArray:
    arr = np.array(as_float_array(value, name, shape=shape), dtype=np.float64, copy=True)
    arr.flags.writeable = False
    return arr


def _check_fields(obj: Any, texts: tuple[str, ...], arrays: dict[str, tuple[int, ...]]) -> int:
    """Check the text fields, ``times`` and ``record_times`` and the ``arrays`` (trailing
    shapes after the time axis) of a result, freezing copies; return the number of messages."""
    for name in texts:
        # Plain str: an np.str_ topic printed as np.str_('/scan') in the record's repr.
        object.__setattr__(obj, name, as_text(getattr(obj, name), name))
    times = _frozen(obj.times, "times", (None,))
    n = int(times.shape[0])
    record_times = _frozen(obj.record_times, "record_times", (n,))
    # What float64 rounded (integer nanoseconds, float32 epoch stamps) is refused.
    as_times(obj.times, "times")
    as_times(obj.record_times, "record_times")
    object.__setattr__(obj, "times", times)
    object.__setattr__(obj, "record_times", record_times)
    for name, tail in arrays.items():
        object.__setattr__(obj, name, _frozen(getattr(obj, name), name, (n, *tail)))
    return n


# Trailing shapes (after the time axis) of the arrays of the odometry and IMU results.
_ODOMETRY_SHAPES = {
    "poses": (3,),
    "orientations": (4,),
    "twists": (3,),
    "pose_covariances": (6, 6),
    "twist_covariances": (6, 6),
}
_IMU_SHAPES = {
    "orientations": (4,),
    "angular_velocities": (3,),
    "linear_accelerations": (3,),
    "orientation_covariances": (3, 3),
    "angular_velocity_covariances": (3, 3),
    "linear_acceleration_covariances": (3, 3),
}
# (field, first column, column past its last) of the rows _read_rows gives the odometry
# and IMU readers (column 0: the record time), in the order the error names the first.
_ODOMETRY_COLUMNS = (
    ("stamp", 1, 2),
    ("position", 2, 5),
    ("orientation", 5, 9),
    ("twist", 9, 12),
    ("pose covariance", 12, 48),
    ("twist covariance", 48, 84),
)
_IMU_COLUMNS = (
    ("stamp", 1, 2),
    ("orientation", 2, 6),
    ("angular velocity", 6, 9),
    ("linear acceleration", 9, 12),
    ("orientation covariance", 12, 21),
    ("angular velocity covariance", 21, 30),
    ("linear acceleration covariance", 30, 39),
)
_ODOMETRY_ARRAYS = ("times", "record_times", *_ODOMETRY_SHAPES)
_IMU_ARRAYS = ("times", "record_times", *_IMU_SHAPES)


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class BagScans:
    """``sensor_msgs/LaserScan`` messages of one bag topic (:func:`read_bag_scans`).

    Attributes
    ----------
    topic : str
        The topic read.
    frame_id : str
        ``header.frame_id`` of the first message (empty for no messages).
    times : ndarray, shape (N,)
        Header stamps, s (``sec + nanosec · 1e-9``, rounded to float64: see
        the module notes), finite: the time of each scan's first beam, as
        ``sensor_msgs/LaserScan`` defines it.
    record_times : ndarray, shape (N,)
        Times the bag recorded the messages, s, finite. Both arrays of times
        are float64 seconds: integers beyond 2**53 (integer nanoseconds) and
        float16 / float32 times coarser than 1 ms are refused with a
        ``ValueError`` (float64 would round the one; the other has lost its
        timing already), as :class:`~navkit.estimation.PlanarFusion` does.
    scans : tuple of LaserScan
        The scans, in bag (record-time) order.

    Raises
    ------
    TypeError
        A text field not a str; an array not of real numbers; ``scans`` not
        a sequence of LaserScan.
    ValueError
        An array of the wrong shape (``times`` one-dimensional,
        ``record_times`` of its length), times that float64 cannot hold
        exactly, a value NaN or infinite, or not one scan per time.

    Notes
    -----
    Arrays are read-only float64 copies; lengths must agree. Memory: each
    scan is a :class:`~navkit.mapping.LaserScan` with its own float64 arrays,
    8 bytes a beam (16 with intensities) and some 330 bytes of objects a scan;
    :func:`read_bag_scans` builds each scan as its message is decoded and lets
    the message go, so that its peak is the scans and about one bag chunk
    (measured on the demo bag of 360 scans of 681 beams, 1.03 MB: 2.54 MB at
    the peak, 6.1 kB a scan kept, with :mod:`tracemalloc`; 2.25 MB before
    the walker handed out a topic's messages chunk by chunk; review 47: the
    decoded messages were all held until the scans were built, and a bag
    read by the chunk walker held whole, 3.51 MB).

    Examples
    --------
    >>> scan = LaserScan([1.0, 2.0], angle_min=0.0, angle_increment=0.1,
    ...                  range_min=0.1, range_max=5.0)
    >>> scans = BagScans("/scan", "laser", [1.5], [1.6], (scan,))
    >>> len(scans), scans.times
    (1, array([1.5]))
    """

    topic: str
    frame_id: str
    times: FloatArray
    record_times: FloatArray
    scans: tuple[LaserScan, ...]

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            topic: str,
            frame_id: str,
            times: ArrayLike,
            record_times: ArrayLike,
            scans: tuple[LaserScan, ...],
        ) -> None: ...

    __repr__ = bounded_repr  # a bag of 2000 scans printed 20 MB

    def __post_init__(self) -> None:
        n = _check_fields(self, ("topic", "frame_id"), {})
        scans = as_sequence(self.scans, "scans")
        for i, scan in enumerate(scans):
            if not isinstance(scan, LaserScan):
                raise TypeError(f"scans[{i}] must be a LaserScan, got {type(scan).__name__}")
        if len(scans) != n:
            raise ValueError(f"scans must hold {n} scans (one per time), got {len(scans)}")
        object.__setattr__(self, "scans", scans)

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("times", "record_times"))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, ("times", "record_times"))

    def __len__(self) -> int:
        return int(self.times.shape[0])


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class BagOdometry:
    """``nav_msgs/Odometry`` messages of one bag topic (:func:`read_bag_odometry`).

    Ready for :meth:`navkit.estimation.MeasurementLog.from_streams`, e.g.
    ``odometry=(odom.times, odom.twists[:, 0], odom.twists[:, 2])`` with
    ``odometry_variance=(odom.twist_covariances[:, 0, 0], odom.twist_covariances[:, 5, 5])``.

    Attributes
    ----------
    topic, frame_id, child_frame_id : str
        The topic, and ``header.frame_id`` (the odometry frame) and
        ``child_frame_id`` (the robot's frame, that of the twists) of the first
        message.
    times : ndarray, shape (N,)
        Header stamps, s.
    record_times : ndarray, shape (N,)
        Times the bag recorded the messages, s (both arrays of times refused
        as in :class:`BagScans` where float64 would round them).
    poses : ndarray, shape (N, 3)
        ``[x, y, yaw]`` (m, m, rad; yaw of the orientation by
        :func:`navkit.geometry.quaternion_to_yaw`, wrapped to (-π, π]).
    orientations : ndarray, shape (N, 4)
        The full 3-D orientation, quaternions ``(x, y, z, w)`` as in the bag.
    twists : ndarray, shape (N, 3)
        ``[vx, vy, omega]`` in the child (robot) frame, m/s and rad/s.
    pose_covariances, twist_covariances : ndarray, shape (N, 6, 6)
        The messages' covariances, row-major 6×6 as in the message, over ROS's
        order ``(x, y, z, rotation about x, about y, about z)`` (so the yaw
        variance is ``[:, 5, 5]`` and a planar ``(x, y, yaw)`` block is
        ``[:, [0, 1, 5]][:, :, [0, 1, 5]]``). As in the bag: drivers that do not
        know them write zeros, which
        :meth:`~navkit.estimation.MeasurementLog.from_streams` refuses as
        variances.

    Raises
    ------
    TypeError
        A text field not a str; an array not of real numbers.
    ValueError
        An array of the wrong shape (one row per message: ``times``
        one-dimensional, ``record_times`` and every other array of its
        length, with the trailing shapes above), times that float64 cannot
        hold exactly, or a value NaN or infinite.

    Notes
    -----
    Arrays are read-only float64 copies, finite, with matching lengths.

    Examples
    --------
    >>> odom = BagOdometry("/odom", "odom", "base_link", [0.0], [0.0], [[1.0, 2.0, 0.5]],
    ...                    [[0.0, 0.0, 0.247404, 0.968912]], [[0.3, 0.0, 0.1]],
    ...                    np.zeros((1, 6, 6)), np.eye(6)[None])
    >>> odom.twists[:, 0], odom.twist_covariances[:, 5, 5]
    (array([0.3]), array([1.]))
    """

    topic: str
    frame_id: str
    child_frame_id: str
    times: FloatArray
    record_times: FloatArray
    poses: FloatArray
    orientations: FloatArray
    twists: FloatArray
    pose_covariances: FloatArray
    twist_covariances: FloatArray

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            topic: str,
            frame_id: str,
            child_frame_id: str,
            times: ArrayLike,
            record_times: ArrayLike,
            poses: ArrayLike,
            orientations: ArrayLike,
            twists: ArrayLike,
            pose_covariances: ArrayLike,
            twist_covariances: ArrayLike,
        ) -> None: ...

    def __post_init__(self) -> None:
        _check_fields(self, ("topic", "frame_id", "child_frame_id"), _ODOMETRY_SHAPES)
        # Poses given directly (not read from a bag) may carry any yaw: wrap it too.
        poses = self.poses.copy()
        poses[:, 2] = wrap_angle(poses[:, 2])
        poses.flags.writeable = False
        object.__setattr__(self, "poses", poses)

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, _ODOMETRY_ARRAYS)

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, _ODOMETRY_ARRAYS)

    def __len__(self) -> int:
        return int(self.times.shape[0])


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class BagImu:
    """``sensor_msgs/Imu`` messages of one bag topic (:func:`read_bag_imu`).

    Attributes
    ----------
    topic, frame_id : str
        The topic and ``header.frame_id`` of the first message (the IMU's frame).
    times : ndarray, shape (N,)
        Header stamps, s.
    record_times : ndarray, shape (N,)
        Times the bag recorded the messages, s (both arrays of times refused
        as in :class:`BagScans` where float64 would round them).
    orientations : ndarray, shape (N, 4)
        Quaternions ``(x, y, z, w)``, as in the bag (all zero when the IMU gives
        none; its covariance then starts with -1).
    angular_velocities : ndarray, shape (N, 3)
        rad/s, IMU frame.
    linear_accelerations : ndarray, shape (N, 3)
        m/s², IMU frame, gravity included (REP 145).
    orientation_covariances, angular_velocity_covariances, linear_acceleration_covariances : \
ndarray, shape (N, 3, 3)
        Row-major 3×3 as in the message, about the x, y and z axes. As in the
        bag: a -1 in ``[i, 0, 0]`` means the reading is not given (REP 145,
        e.g. no orientation estimate), all zeros that its covariance is unknown
        (the message's comments).

    Raises
    ------
    TypeError
        A text field not a str; an array not of real numbers.
    ValueError
        An array of the wrong shape (one row per message: ``times``
        one-dimensional, ``record_times`` and every other array of its
        length, with the trailing shapes above), times that float64 cannot
        hold exactly, or a value NaN or infinite.

    Notes
    -----
    Arrays are read-only float64 copies, finite, with matching lengths.

    Examples
    --------
    >>> imu = BagImu("/imu", "imu_link", [0.0], [0.0], [[0.0, 0.0, 0.0, 1.0]],
    ...              [[0.0, 0.0, 0.2]], [[0.0, 0.0, 9.8]], *[np.eye(3)[None]] * 3)
    >>> imu.angular_velocities[:, 2]
    array([0.2])
    """

    topic: str
    frame_id: str
    times: FloatArray
    record_times: FloatArray
    orientations: FloatArray
    angular_velocities: FloatArray
    linear_accelerations: FloatArray
    orientation_covariances: FloatArray
    angular_velocity_covariances: FloatArray
    linear_acceleration_covariances: FloatArray

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            topic: str,
            frame_id: str,
            times: ArrayLike,
            record_times: ArrayLike,
            orientations: ArrayLike,
            angular_velocities: ArrayLike,
            linear_accelerations: ArrayLike,
            orientation_covariances: ArrayLike,
            angular_velocity_covariances: ArrayLike,
            linear_acceleration_covariances: ArrayLike,
        ) -> None: ...

    def __post_init__(self) -> None:
        _check_fields(self, ("topic", "frame_id"), _IMU_SHAPES)

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, _IMU_ARRAYS)

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, _IMU_ARRAYS)

    def __len__(self) -> int:
        return int(self.times.shape[0])

    def to_base(
        self,
        mount: ArrayLike | None = None,
        *,
        frame_id: str = "base_link",
        mounting: ArrayLike | None = None,
    ) -> BagImu:
        """The same readings rotated into the robot's base frame.

        Orientations, angular velocities and accelerations as
        :func:`navkit.geometry.imu_to_base` rotates them; each covariance ``C``
        becomes ``R C Rᵀ`` (``R`` the mounting rotation), except those marked
        "not given" (-1 first), which are kept. Orientations marked "not given"
        (orientation covariance -1 first, REP 145) are kept too, as in the bag
        (usually all zero), rather than turned into the mounting's inverse; so
        is an all-zero orientation whatever its covariance (no rotation: an
        orientation not given).

        Parameters
        ----------
        mount : array_like, shape (4,)
            Rotation of the IMU frame relative to the base frame, quaternion
            ``(x, y, z, w)`` (the ``base_link -> imu_link`` transform's rotation;
            :func:`navkit.geometry.rpy_to_quaternion` makes it from roll, pitch
            and yaw), non-zero; required.
        frame_id : str, default "base_link"
            ``frame_id`` of the result.

        Returns
        -------
        BagImu

        Raises
        ------
        TypeError
            ``mount`` missing or not numeric, both ``mount`` and ``mounting``
            given, ``frame_id`` not a str.
        ValueError
            ``mount`` not four finite values, or all zero.

        Other Parameters
        ----------------
        mounting : array_like, optional
            Deprecated name of `mount` (keyword-only).

        Examples
        --------
        >>> import math
        >>> from navkit.geometry import rpy_to_quaternion
        >>> imu = BagImu("/imu", "imu_link", [0.0], [0.0], [[0.0, 0.0, 0.0, 1.0]],
        ...              [[0.0, 0.0, 0.2]], [[0.0, 0.0, 9.8]], *[np.eye(3)[None]] * 3)
        >>> upside_down = imu.to_base(rpy_to_quaternion(math.pi, 0.0, 0.0))
        >>> upside_down.angular_velocities.round(6) + 0.0, upside_down.frame_id
        (array([[ 0. ,  0. , -0.2]]), 'base_link')
        """
        named = "mount" if mounting is None else "mounting"  # as the caller wrote it
        mount = renamed_keyword("mounting", mounting, "mount", mount, None)
        if mount is None:
            raise TypeError("to_base() missing required argument: 'mount'")
        # Checked here as imu_to_base checks it, so that its errors name the keyword
        # the caller wrote (imu_to_base would name "mount").
        mount = as_float_array(mount, named, shape=(4,))
        if not np.any(mount):
            raise ValueError(f"{named} must be a non-zero quaternion (x, y, z, w)")
        frame = as_text(frame_id, "frame_id")
        rotated = imu_to_base(
            self.orientations,
            self.angular_velocities,
            self.linear_accelerations,
            mount=mount,
        )
        rot = quaternion_to_matrix(mount)
        # An IMU without an orientation estimate gives a placeholder (all zero); rotating
        # it would fabricate the orientation m⁻¹ behind a still "not given" covariance.
        # An all-zero quaternion is no rotation even where its covariance says it is one
        # (a BagImu built by hand; read_bag_imu marks them): kept as it is too.
        no_orientation = (self.orientation_covariances[:, 0, 0] == -1.0) | (
            self.orientations == 0.0
        ).all(axis=1)
        orientations = np.where(no_orientation[:, None], self.orientations, rotated.orientations)

        def turn(cov: FloatArray) -> FloatArray:
            keep = cov[:, 0, 0] == -1.0
            with np.errstate(under="ignore"):  # tiny products: 0, whatever np.seterr says
                out = rot @ cov @ rot.T
            return np.asarray(np.where(keep[:, None, None], cov, out), dtype=np.float64)

        return BagImu(
            self.topic,
            frame,
            self.times,
            self.record_times,
            orientations,
            rotated.angular_velocities,
            rotated.linear_accelerations,
            turn(self.orientation_covariances),
            turn(self.angular_velocity_covariances),
            turn(self.linear_acceleration_covariances),
        )


# ---------------------------------------------------------------- reading
def _rosbags() -> Any:
    """The ``rosbags`` modules the readers need (imported lazily)."""
    try:
        import rosbags.rosbag1 as rosbag1
        import rosbags.rosbag2 as rosbag2
        from rosbags.typesys import Stores, get_typestore
    except ImportError:
        raise ImportError(
            "reading ROS bags needs the rosbags package: install navkit[ros] "
            "(python -m pip install 'navkit[ros]')"
        ) from None
    return rosbag1, rosbag2, Stores, get_typestore


def _normalize(msgtype: str) -> str:
    """``pkg/Type`` (ROS 1) as ``pkg/msg/Type`` (rosbags' and ROS 2's spelling)."""
    parts = msgtype.split("/")
    return f"{parts[0]}/msg/{parts[1]}" if len(parts) == 2 else msgtype


class _Bag(NamedTuple):
    """An opened bag: its message counts by ``(topic, type)``, a function yielding
    (record ns, raw message) of the messages of one topic and type, and, for a ROS 2
    bag, the bytes of the files in its folder (which hold its messages).

    A ROS 1 bag's counts are of records read from its file (rosbags counts the
    12-byte entries of its index, checked against the chunk-info records; the
    chunk walker counts the messages themselves); a ROS 2 bag's are what its
    ``metadata.yaml`` declares, checked only once the messages are read.
    """

    ros2: bool
    counts: dict[tuple[str, str], int]
    messages: Callable[[str, str], Iterator[tuple[int, bytes]]]
    stored: int | None = None

    def types(self) -> dict[str, dict[str, int]]:
        """``{topic: {type: count}}``, topics and types sorted.

        A ROS 1 bag may record one topic with connections of several types (a
        topic name reused by another node): each type is a stream of its own.
        """
        out: dict[str, dict[str, int]] = {}
        for (topic, msgtype), count in sorted(self.counts.items()):
            out.setdefault(topic, {})[msgtype] = count
        return out


_T = TypeVar("_T")


if TYPE_CHECKING:
    _ConcretePath = Path
else:  # PosixPath or WindowsPath: Python 3.11's Path itself cannot be subclassed
    _ConcretePath = type(Path())


class _CheckedPath(_ConcretePath):
    """A path whose files rosbags can open only as regular files, checked on the descriptor.

    rosbags opens what it reads by name, after navkit's own checks: a ROS 1 bag
    and a ROS 2 bag's storage files with ``path.open("rb")``, a ROS 2 bag's
    ``metadata.yaml`` with ``read_text()``. Handed this path (rosbags reads
    through any object of its ``RPath`` protocol; paths made from it with
    ``/`` are of this class too), every such read opens the file with
    :func:`open_regular`: a FIFO, a device or a folder put in place of a file
    after navkit's checks is refused instead of blocking the read, and
    ``read_text`` reads at most :data:`METADATA_MAX` bytes. Opens for writing
    are left to :class:`~pathlib.Path`.
    """

    def open(
        self,
        mode: str = "r",
        buffering: int = -1,
        encoding: str | None = None,
        errors: str | None = None,
        newline: str | None = None,
    ) -> Any:
        if set(mode) & set("wax+"):
            return super().open(mode, buffering, encoding, errors, newline)
        fh = open_regular(Path(self), "ROS bag file")
        if "b" in mode:
            return fh
        return io.TextIOWrapper(fh, encoding=encoding, errors=errors, newline=newline)

    def read_text(
        self, encoding: str | None = None, errors: str | None = None, newline: str | None = None
    ) -> str:
        # ``newline``: Path.read_text's since Python 3.13 (mypy --python-version 3.13 wants
        # it). Line endings are returned untranslated whatever it is, as before.
        with open_regular(Path(self), "ROS bag file") as fh:
            data = fh.read(METADATA_MAX + 1)
        if len(data) > METADATA_MAX:
            raise ValueError(f"{self}: larger than {METADATA_MAX} bytes")
        return data.decode(encoding or "utf-8", errors or "strict")


def _check_path(path: Any) -> Path:
    bag_path = as_path(path, "path")
    if not bag_path.exists():
        raise missing_file(bag_path, "ROS bag")
    return bag_path


class _RosbagsFailed(Exception):
    """rosbags could not open a bag or read its messages (the message says why)."""


def _failure(exc: Exception) -> Exception:
    """What to raise for an exception of rosbags: an error of the operating system that
    names its file (one it refuses to open) as it is, anything else as
    :class:`_RosbagsFailed`: a seek past the largest offset a damaged index asks for is
    an ``OSError`` (EINVAL) naming no file, which would reach the caller as "Invalid
    argument" alone."""
    if isinstance(exc, OSError) and exc.errno is not None and exc.filename is not None:
        return exc
    return _RosbagsFailed(str(exc) or type(exc).__name__)


@contextmanager
def _opened(reader_class: Any, bag_path: Path) -> Iterator[Any]:
    """An open rosbags reader of ``bag_path``, closed on exit."""
    # rosbags reacts to corrupt bytes with whatever its decoders raise (ReaderError,
    # OSError from bz2, UnicodeDecodeError, sqlite3 errors, ValueError of an enum ...).
    try:
        reader = reader_class(bag_path)
        reader.open()
    except Exception as exc:
        raise _failure(exc) from None
    try:
        yield reader
    finally:
        with suppress(Exception):
            reader.close()


def _guarded(messages: Callable[[], Iterable[tuple[Any, int, Any]]]) -> Iterator[tuple[int, bytes]]:
    """(record ns, raw message) of the rosbags messages ``messages()`` gives, its failures as
    :class:`_RosbagsFailed` (chunks are decompressed and checked only as they are read)."""
    try:
        for _, stamp, raw in messages():
            yield stamp, bytes(raw)
    except Exception as exc:
        raise _failure(exc) from None


def _counted(
    messages: Iterator[tuple[int, bytes]], declared: int, topic: str
) -> Iterator[tuple[int, bytes]]:
    """``messages``, then :class:`_RosbagsFailed` unless there were ``declared`` of them.

    A ROS 2 storage file without checksums (an MCAP written without chunk CRCs,
    as ``rosbags-convert`` writes them) can lose messages to damage without an
    error from the reader: the count in ``metadata.yaml`` tells.
    """
    read = 0
    for item in messages:
        read += 1
        yield item
    if read != declared:
        raise _RosbagsFailed(
            f"metadata.yaml declares {declared} messages on {topic[:200]!r} but {read} "
            "could be read: the bag is damaged, or its metadata.yaml is stale (`ros2 bag "
            "reindex` rewrites it)"
        )


def _check_index(reader: Any) -> None:
    """:class:`_RosbagsFailed` where an open ROS 1 bag's two message counts disagree.

    rosbags counts a connection's messages from the index records after each
    chunk; the chunk-info records at the end of the file count them too. A
    damaged index record loses messages without an error from rosbags, so a
    difference sends the bag to the chunk walker (:func:`_walk_ros1`), which
    reads the chunks themselves. A rosbags without these tables is not checked.
    """
    infos = getattr(reader, "chunk_infos", None)
    if not isinstance(infos, list):
        return
    declared: dict[Any, int] = {}
    for info in infos:
        counts = getattr(info, "connection_counts", None)
        if not isinstance(counts, dict):
            return
        for conn_id, count in counts.items():
            declared[conn_id] = declared.get(conn_id, 0) + count
    for c in reader.connections:
        want = declared.get(getattr(c, "id", None), 0)
        if c.msgcount != want:
            raise _RosbagsFailed(
                f"the index lists {c.msgcount} messages on {c.topic[:200]!r}, the chunk "
                f"records {want}"
            )


def _connection_counts(connections: Iterable[Any]) -> dict[tuple[str, str], int]:
    """``{(topic, type): count}`` of rosbags connections (a topic may have several, of one
    type or, in ROS 1, of different types).

    A ROS 2 bag's connections are its ``metadata.yaml`` as written: a topic, type
    or count of another YAML type (a list, a mapping) is :class:`_RosbagsFailed`,
    naming the field but not printing the value (YAML aliases can make a few
    hundred bytes a value of billions of shared parts).
    """
    counts: dict[tuple[str, str], int] = {}
    for c in connections:
        for field, value, kind in (("topic name", c.topic, str), ("topic type", c.msgtype, str),
                                   ("message count", c.msgcount, int)):  # fmt: skip
            if not isinstance(value, kind) or isinstance(value, bool):
                raise _RosbagsFailed(
                    f"a {field} is a {type(value).__name__}, not a {kind.__name__}"
                )
        if c.msgcount < 0:
            raise _RosbagsFailed(f"topic {c.topic[:200]!r} has a negative message count")
        key = (c.topic, _normalize(c.msgtype))
        counts[key] = counts.get(key, 0) + c.msgcount
    return counts


def _of_stream(connections: Iterable[Any], topic: str, msgtype: str) -> list[Any]:
    """The rosbags connections of ``topic`` with messages of ``msgtype``."""
    return [c for c in connections if c.topic == topic and _normalize(c.msgtype) == msgtype]


def _folder_bytes(folder: Path) -> int:
    """Bytes of the files in ``folder`` (where rosbags reads a ROS 2 bag's storage files
    from), a file that cannot be examined counted as none."""
    total = 0
    with suppress(OSError), os.scandir(folder) as entries:
        for entry in entries:
            with suppress(OSError):
                if entry.is_file():
                    total += entry.stat().st_size
    return total


def _with_bag(bag_path: Path, use: Callable[[_Bag], _T]) -> _T:
    """Open ``bag_path`` (ROS 1 file or ROS 2 folder) and call ``use`` on it."""
    rosbag1, rosbag2, _, _ = _rosbags()
    if bag_path.is_dir():
        if not (bag_path / "metadata.yaml").is_file():
            raise ValueError(f"{bag_path} is a folder without metadata.yaml, not a ROS 2 bag")
        _check_metadata(bag_path / "metadata.yaml")
        try:
            with _opened(rosbag2.Reader, _CheckedPath(bag_path)) as reader:

                def messages2(topic: str, msgtype: str) -> Iterator[tuple[int, bytes]]:
                    # Never empty (the stream was chosen from the counts): rosbags
                    # would read every connection for an empty list.
                    conns = _of_stream(reader.connections, topic, msgtype)
                    declared = sum(c.msgcount for c in conns)
                    return _counted(
                        _guarded(lambda: reader.messages(connections=conns)), declared, topic
                    )

                counts = _connection_counts(reader.connections)
                return use(_Bag(True, counts, messages2, _folder_bytes(bag_path)))
        except _RosbagsFailed as exc:
            raise ValueError(f"{bag_path}: cannot read the ROS 2 bag: {exc}") from None
    if not bag_path.is_file():
        raise ValueError(f"{bag_path} is neither a ROS 1 bag file nor a ROS 2 bag folder")
    with open_regular(bag_path, "ROS bag") as fh:
        magic = fh.read(len(_ROS1_MAGIC))
    if magic != _ROS1_MAGIC:
        raise ValueError(
            f"{bag_path} is not a ROS 1 bag (no '#ROSBAG V2.0' header); a ROS 2 bag is read "
            "from its folder"
        )
    try:
        with _opened(rosbag1.Reader, _CheckedPath(bag_path)) as reader:
            _bound_chunks(reader, bag_path)
            _check_index(reader)

            def messages1(topic: str, msgtype: str) -> Iterator[tuple[int, bytes]]:
                conns = _of_stream(reader.connections, topic, msgtype)
                return _guarded(lambda: reader.messages(connections=conns))

            return use(_Bag(False, _connection_counts(reader.connections), messages1))
    except _RosbagsFailed as exc:
        # rosbags refuses bags whose index records are damaged (e.g. an index
        # data record longer than its entries): read the chunks directly.
        try:
            bag = _walk_ros1(bag_path)
        except _Corrupt as walk_exc:
            detail = str(exc) if str(exc) == str(walk_exc) else f"{exc}; {walk_exc}"
            raise ValueError(f"{bag_path}: cannot read the ROS 1 bag: {detail}") from None
        try:
            return use(bag)
        except _Corrupt as walk_exc:  # the walker reads a stream's chunks as it is used
            raise ValueError(f"{bag_path}: cannot read the ROS 1 bag: {walk_exc}") from None


def _check_metadata(path: Path) -> None:
    """Refuse a ROS 2 ``metadata.yaml`` that is not a regular file or is over
    :data:`METADATA_MAX` bytes, which rosbags would read whole (or block on)."""
    with open_regular(path, "ROS 2 bag metadata") as fh:
        size = os.fstat(fh.fileno()).st_size
    if size > METADATA_MAX:
        raise ValueError(
            f"{path}: {size} bytes is too large for a ROS 2 bag's metadata.yaml "
            f"(at most {METADATA_MAX} bytes)"
        )


class _Corrupt(Exception):
    """The chunk walker met something it cannot read."""


def _inflate(compression: bytes, size: int, chunk_pos: int, body: bytes) -> bytes:
    """The data of the chunk at ``chunk_pos``, decompressed, within its declared ``size``.

    Never more than the ``size`` its header declares (as rosbag's own buffer of
    that size), nor than :data:`CHUNK_MAX` bytes, so that a decompression bomb
    fails before it is inflated.
    """
    if compression == b"none":
        return body
    if compression not in (b"bz2", b"lz4"):
        raise _Corrupt(f"unknown chunk compression {compression!r}")
    if size > CHUNK_MAX:
        raise _Corrupt(
            f"the chunk at byte {chunk_pos} declares {size} bytes decompressed, more than "
            f"the {CHUNK_MAX} a bag chunk may hold"
        )
    try:
        if compression == b"bz2":
            decompressor: Any = bz2.BZ2Decompressor()
        else:
            decompressor = importlib.import_module("lz4.frame").LZ4FrameDecompressor()
        out = bytes(decompressor.decompress(body, max_length=size + 1))
        complete = decompressor.eof
    except (OSError, ValueError, RuntimeError, EOFError) as exc:
        raise _Corrupt(f"corrupt compressed chunk: {exc}") from None
    if len(out) > size:
        raise _Corrupt(
            f"the chunk at byte {chunk_pos} decompresses to more than the {size} bytes "
            "its header declares"
        )
    if not complete:
        raise _Corrupt(f"corrupt compressed chunk at byte {chunk_pos}: its data is cut off")
    return out


def _bound_chunks(reader: Any, bag_path: Path) -> None:
    """Make rosbags decompress the chunks of an open ROS 1 bag with :func:`_inflate`.

    rosbags decompresses a whole chunk at once, however much comes out. Its
    chunk table (``reader.chunks``: position → (data size, data position,
    decompressor)) gets bounded decompressors, from each chunk header's
    compression and size; a rosbags without that table is left as it is.
    """
    chunks = getattr(reader, "chunks", None)
    if not isinstance(chunks, dict):
        return
    with open_regular(bag_path, "ROS bag") as fh:
        for chunk_pos, chunk in list(chunks.items()):
            if not hasattr(chunk, "_replace") or not hasattr(chunk, "decompressor"):
                return
            fh.seek(chunk_pos)
            head = fh.read(4)
            try:
                (header_len,) = struct.unpack("<I", head)
                fields = _fields(fh.read(min(header_len, 1 << 20)))
                compression = fields.get("compression", b"none")
                size = _int(fields, "size", "<I")
            except (struct.error, _Corrupt) as exc:
                raise _RosbagsFailed(f"chunk at byte {chunk_pos}: {exc}") from None
            chunks[chunk_pos] = chunk._replace(
                decompressor=partial(_rosbags_inflate, compression, size, chunk_pos)
            )


def _rosbags_inflate(compression: bytes, size: int, chunk_pos: int, body: bytes) -> bytes:
    try:
        return _inflate(compression, size, chunk_pos, body)
    except _Corrupt as exc:
        raise _RosbagsFailed(str(exc)) from None


def _fields(block: bytes) -> dict[str, bytes]:
    """The ``name=value`` fields of a ROS 1 record header."""
    out = {}
    i = 0
    while i < len(block):
        if i + 4 > len(block):
            raise _Corrupt("truncated record header")
        (n,) = struct.unpack_from("<I", block, i)
        field = block[i + 4 : i + 4 + n]
        if len(field) != n or b"=" not in field:
            raise _Corrupt("malformed record header field")
        name, _, value = field.partition(b"=")
        out[name.decode("ascii", "replace")] = value
        i += 4 + n
    return out


def _record(data: bytes, pos: int, where: str = "") -> tuple[dict[str, bytes], bytes, int]:
    """Header fields, data and next position of the ROS 1 record at ``pos`` of ``data``.

    ``data`` is the file, or the decompressed chunk ``where`` names (see
    :func:`_record_at`).
    """
    return _record_at(lambda start, n: data[start : start + n], len(data), pos, where)


def _record_at(
    read: Callable[[int, int], bytes], end: int, pos: int, where: str = ""
) -> tuple[dict[str, bytes], bytes, int]:
    """Header fields, data and next position of the ROS 1 record at ``pos`` of something
    ``end`` bytes long, whose ``n`` bytes at ``start`` ``read(start, n)`` gives.

    ``pos`` is a position in the file, or in the decompressed chunk ``where``
    names. Both declared lengths are checked against the bytes there: a cut or
    lying length is refused here, naming the record, rather than read as a
    shorter header or message (or, in a file, as a read of gigabytes).
    """
    what = f"record at byte {pos}{where}"

    def take(start: int, n: int) -> bytes:
        got = read(start, n)
        if len(got) != n:  # a file cut while it is read
            raise _Corrupt(f"{what} is cut off")
        return got

    if pos < 0 or pos + 4 > end:
        raise _Corrupt(f"{what} lies beyond the end")
    (header_len,) = struct.unpack("<I", take(pos, 4))
    start = pos + 4
    if header_len > end - start:
        raise _Corrupt(
            f"{what} declares a {header_len}-byte header, only {end - start} bytes remain"
        )
    header = take(start, header_len)
    pos = start + header_len
    if pos + 4 > end:
        raise _Corrupt(f"{what} is cut off before its data length")
    (data_len,) = struct.unpack("<I", take(pos, 4))
    start = pos + 4
    if data_len > end - start:
        raise _Corrupt(f"{what} declares {data_len} data bytes, only {end - start} bytes remain")
    try:
        fields = _fields(header)
    except _Corrupt as exc:
        raise _Corrupt(f"{what}: {exc}") from None
    return fields, take(start, data_len), start + data_len


def _int(fields: dict[str, bytes], name: str, fmt: str) -> int:
    try:
        (value,) = struct.unpack(fmt, fields[name])
    except (KeyError, struct.error):
        raise _Corrupt(f"record without a valid {name!r} field") from None
    return int(value)


def _op(fields: dict[str, bytes]) -> int:
    return _int(fields, "op", "<B")


def _file_reader(fh: BinaryIO) -> Callable[[int, int], bytes]:
    """``read(start, n)``: the ``n`` bytes of ``fh`` at ``start`` (fewer at its end)."""

    def read(start: int, n: int) -> bytes:
        fh.seek(start)
        return fh.read(n)

    return read


def _identity(fh: BinaryIO) -> tuple[int, int, int, int, int]:
    """What tells an open file from itself rewritten: device, inode, size, modification
    and status-change times (a tool may put the modification time back; the change
    time, which follows every write and ``utime``, cannot be set). Either time may
    stay the same within its resolution, whence the walker's second order check."""
    st = os.fstat(fh.fileno())
    return st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns, st.st_ctime_ns


def _chunk_messages(
    read: Callable[[int, int], bytes], end: int, chunk_pos: int, declared: dict[int, int],
    wanted: Callable[[int], bool],
) -> Iterator[tuple[int, int, bytes]]:  # fmt: skip
    """(record ns, connection, raw message) of the messages of the chunk at ``chunk_pos``
    whose connection is ``wanted``, in chunk order; then :class:`_Corrupt` unless the chunk
    holds, connection by connection, the messages its chunk-info record ``declared``."""
    found = dict.fromkeys(declared, 0)
    fields, body, _ = _record_at(read, end, chunk_pos)
    if _op(fields) != 5:
        raise _Corrupt(f"no chunk record at byte {chunk_pos}")
    compression = fields.get("compression", b"none")
    body = _inflate(compression, _int(fields, "size", "<I"), chunk_pos, body)
    inner = 0
    whole = len(body)
    while inner < whole:
        rec, payload, inner = _record(body, inner, f" of the chunk at byte {chunk_pos}")
        if _op(rec) == 2:
            stamp = _int(rec, "time", "<Q")
            ns = (stamp & 0xFFFFFFFF) * 1_000_000_000 + (stamp >> 32)
            conn_id = _int(rec, "conn", "<I")
            found[conn_id] = found.get(conn_id, 0) + 1
            if wanted(conn_id):
                yield ns, conn_id, payload
    for conn_id in sorted(found.keys() | declared.keys()):
        if found.get(conn_id, 0) != declared.get(conn_id, 0):
            raise _Corrupt(
                f"the chunk at byte {chunk_pos} holds {found.get(conn_id, 0)} messages "
                f"of connection {conn_id}, its chunk info record "
                f"{declared.get(conn_id, 0)}"
            )


def _walk_ros1(bag_path: Path) -> _Bag:
    """Read a ROS 1 bag through its connection and chunk-info records (the chunks' own indexes
    are not used).

    Each chunk must hold, connection by connection, the messages its chunk-info
    record counts: a message record whose ``op`` or ``conn`` field is damaged
    (ROS 1 bags carry no checksum) was otherwise dropped without a word.

    The bag is streamed, one chunk in memory at a time (review 47: it was read
    whole, and every message copied out of it, some 3.4 times the file at the
    peak): this call reads the index and checks every chunk, keeping only the
    counts; ``messages(topic, msgtype)`` reads the chunks again, once the file is
    checked to be the one counted (same device, inode, size, modification and
    status-change times; else :class:`_Corrupt`), handing out that stream's
    messages chunk by chunk when the bag's messages are in record-time order (as
    rosbag records them), else gathering and sorting them (the stream's messages
    held). Time stamps of a coarse resolution (1 s on ext3 and HFS+, 2 s on FAT)
    can keep a file rewritten in place at its size looking the same: the record
    times handed out chunk by chunk are checked again as they are read, and a
    message out of order is :class:`_Corrupt` (review 47). A chunk is
    decompressed twice: this walker reads bags whose index rosbags refuses, where
    memory matters more than time.
    """
    with open_regular(bag_path, "ROS bag") as fh:
        identity = _identity(fh)
        end = identity[2]
        read = _file_reader(fh)
        header, _, _ = _record_at(read, end, len(_ROS1_MAGIC))
        if _op(header) != 3:
            raise _Corrupt("no bag header record")
        pos = _int(header, "index_pos", "<Q")
        if pos == 0:
            raise _Corrupt("the bag is not indexed (run `rosbag reindex`)")
        conns: dict[int, tuple[str, str]] = {}
        for _ in range(_int(header, "conn_count", "<I")):
            fields, body, pos = _record_at(read, end, pos)
            if _op(fields) != 7:
                raise _Corrupt("expected a connection record in the index")
            conn = _fields(body)
            topic = fields.get("topic", b"").decode("utf-8", "replace")
            msgtype = conn.get("type", b"").decode("utf-8", "replace")
            conns[_int(fields, "conn", "<I")] = (topic, _normalize(msgtype))
        chunks = []
        for _ in range(_int(header, "chunk_count", "<I")):
            fields, body, pos = _record_at(read, end, pos)
            if _op(fields) != 6:
                raise _Corrupt("expected a chunk info record in the index")
            chunk_pos = _int(fields, "chunk_pos", "<Q")
            listed = _int(fields, "count", "<I")
            if len(body) != 8 * listed:
                raise _Corrupt(
                    f"the chunk info record of the chunk at byte {chunk_pos} lists {listed} "
                    f"connections in {len(body)} bytes (8 bytes each)"
                )
            declared: dict[int, int] = {}
            for conn_id, count in struct.iter_unpack("<II", body):
                declared[conn_id] = declared.get(conn_id, 0) + count
            chunks.append((chunk_pos, declared))
        # Tabulated as rosbags does: by (topic, type), connections of both alike summed; a
        # connection without messages still lists its stream (count 0). Messages of a
        # connection the index does not declare have no type and belong to no stream.
        counts = dict.fromkeys(conns.values(), 0)
        # Whether the messages of every stream come in record-time order already (as
        # rosbag records them): then a stream is handed out chunk by chunk as read.
        ordered = True
        last = -1
        for chunk_pos, declared in chunks:
            for ns, conn_id, _ in _chunk_messages(
                read, end, chunk_pos, declared, conns.__contains__
            ):
                counts[conns[conn_id]] += 1
                ordered = ordered and ns >= last
                last = ns

    def stream(ids: set[int]) -> Iterator[tuple[int, bytes]]:
        """(record ns, raw message) of the connections ``ids``, in file order."""
        with open_regular(bag_path, "ROS bag") as fh:
            if _identity(fh) != identity:
                raise _Corrupt("the bag file changed while it was read")
            read = _file_reader(fh)
            for chunk_pos, declared in chunks:
                if any(declared.get(conn_id, 0) for conn_id in ids):
                    for ns, _, raw in _chunk_messages(
                        read, end, chunk_pos, declared, ids.__contains__
                    ):
                        yield ns, raw

    def walked(topic: str, msgtype: str) -> Iterator[tuple[int, bytes]]:
        ids = {conn_id for conn_id, stream in conns.items() if stream == (topic, msgtype)}
        if ordered:
            # The order was seen on the first pass: a file changed since then without
            # its identity telling could hand messages out unsorted.
            last = -1
            for ns, raw in stream(ids):
                if ns < last:
                    raise _Corrupt(
                        "the bag file changed while it was read (its messages are no "
                        "longer in record-time order)"
                    )
                last = ns
                yield ns, raw
            return
        # Record-time order, stable (chunk order, then order in the chunk), as rosbags gives
        # them; handed out last first from the reversed list, each message is let go once
        # it is yielded (its decoded form is what the reader keeps).
        selected = sorted(stream(ids), key=lambda m: m[0])
        selected.reverse()
        while selected:
            yield selected.pop()

    return _Bag(False, counts, walked)


def _describe(types: dict[str, dict[str, int]]) -> str:
    if not types:
        return "the bag has no topics"
    return "topics: " + ", ".join(f"{t} ({', '.join(v)})" for t, v in types.items())


def _select(bag_path: Path, bag: _Bag, msgtype: str, topic: str | None) -> str:
    """The topic to read ``msgtype`` messages from: ``topic``, checked, or the only one
    with messages of that type (a topic counts once per type it was recorded with)."""
    types = bag.types()
    if topic is None:
        candidates = [t for t, v in types.items() if msgtype in v]
        if not candidates:
            raise ValueError(f"{bag_path}: no {msgtype} topic; {_describe(types)}")
        if len(candidates) > 1:
            raise ValueError(
                f"{bag_path}: several {msgtype} topics ({', '.join(candidates)}); choose one "
                "with topic="
            )
        return candidates[0]
    if topic not in types:
        raise ValueError(f"topic {topic!r} is not in {bag_path}; {_describe(types)}")
    if msgtype not in types[topic]:
        have = " and ".join(types[topic])
        raise ValueError(f"topic {topic!r} of {bag_path} holds {have} messages, not {msgtype}")
    return topic


def _decoded(
    path: Any,
    topic: Any,
    msgtype: str,
    use: Callable[[str, Iterator[tuple[int, Any]], int, int | None], _T],
) -> _T:
    """Hand ``use`` the selected topic's name, an iterator deserializing its ``msgtype``
    messages (those of other types recorded on it left alone) one at a time, the
    number of them the bag declares (its index or metadata: checked against the
    messages read where the bag allows, but a damaged bag may hold more or fewer, and
    a ROS 2 bag's is checked only once they are read) and the bag's ``stored`` bytes
    (see :class:`_Bag`)."""
    if topic is not None and not isinstance(topic, str):
        raise TypeError(f"topic must be a str or None, got {type(topic).__name__}")
    bag_path = _check_path(path)
    _, _, stores, get_typestore = _rosbags()

    def opened(bag: _Bag) -> _T:
        name = _select(bag_path, bag, msgtype, topic)
        store = get_typestore(stores.ROS2_HUMBLE if bag.ros2 else stores.ROS1_NOETIC)
        deserialize = store.deserialize_cdr if bag.ros2 else store.deserialize_ros1

        def decode() -> Iterator[tuple[int, Any]]:
            for i, (ns, raw) in enumerate(bag.messages(name, msgtype)):
                try:
                    msg = deserialize(raw, msgtype)
                except Exception as exc:  # rosbags raises many kinds on corrupt bytes
                    raise ValueError(
                        f"{bag_path}: message {i} of {name} cannot be decoded as {msgtype}: {exc}"
                    ) from None
                yield ns, msg

        return use(name, decode(), bag.counts.get((name, msgtype), 0), bag.stored)

    return _with_bag(bag_path, opened)


def _read_rows(
    path: Any,
    topic: Any,
    msgtype: str,
    width: int,
    fill: Callable[[Any, FloatArray], None],
    convert: Callable[[str, Any, FloatArray], _T],
) -> _T:
    """Read the selected topic's ``msgtype`` messages into one float64 row each, dropping
    every message once ``fill`` has copied its values into ``row[1:]`` (``row[0]``: the
    record time), and hand ``convert`` the topic, the first message (None if none) and the
    ``(N, width)`` rows.

    A deserialized message is a tree of Python objects several times the size of its
    numbers (an Odometry some 5 kB for 83 values): holding them all until the arrays
    are built would need that much a message. The rows are one block of the count the
    bag declares (review 47: they grew in blocks, each twice the last, then joined,
    some 2.4 times their size at the peak); past it (a damaged index or metadata)
    they grow in blocks, each twice the last, joined at the end.

    A ROS 2 bag's declared count (its ``metadata.yaml``, checked only once the
    messages are read) is believed only as far as the files of its folder could
    hold that many messages (review 47: one declaring 10**12 was a ``MemoryError``
    before its count was checked): every value of a row but the record time comes
    from a float64 of the message, or from its stamp's two 32-bit integers, and a
    CDR message starts with a 4-byte encapsulation header and holds a frame id
    after its 4-byte length, so an uncompressed message takes at least
    ``8 * width`` bytes, and the first block is no larger than the files. A
    compressed ROS 2 bag whose messages take fewer grows its rows past that block
    as above. A ROS 1 bag's counts are of records read from its file
    (:class:`_Bag`).
    """

    def use(
        name: str, messages: Iterator[tuple[int, Any]], declared: int, stored: int | None
    ) -> _T:
        if stored is not None:
            declared = min(declared, stored // (8 * width))
        first = None
        blocks: list[FloatArray] = []
        used = size = 0
        for ns, msg in messages:
            if first is None:
                first = msg
            if used == size:
                size = 2 * size or max(declared, 64)
                blocks.append(np.empty((size, width), dtype=np.float64))
                used = 0
            blocks[-1][used, 0] = _record_time(ns)
            fill(msg, blocks[-1][used])  # a view not kept: it would keep its block alive
            used += 1
        if blocks:
            blocks[-1] = blocks[-1][:used]
        if len(blocks) == 1:
            rows = blocks[0]
        else:
            rows = np.concatenate(blocks) if blocks else np.empty((0, width), dtype=np.float64)
        del blocks
        return convert(name, first, rows)

    return _decoded(path, topic, msgtype, use)


def _stamp(msg: Any) -> float:
    stamp = msg.header.stamp
    return float(stamp.sec) + float(stamp.nanosec) * 1e-9


def _record_time(ns: int) -> float:
    # As _stamp computes a stamp, so that the same instant gives the same float
    # (``ns * 1e-9`` rounds ns to a multiple of 256 first: often one float off).
    return float(ns // 1_000_000_000) + float(ns % 1_000_000_000) * 1e-9


def _xyz(v: Any) -> tuple[float, float, float]:
    return float(v.x), float(v.y), float(v.z)


def _xyzw(q: Any) -> tuple[float, float, float, float]:
    return float(q.x), float(q.y), float(q.z), float(q.w)


def _finite(arr: FloatArray, what: str, bag_path: Any, topic: str) -> FloatArray:
    # Reduced over the trailing axes, not reshaped: a topic without messages has N = 0.
    bad = ~np.isfinite(arr).all(axis=tuple(range(1, arr.ndim)))
    if bad.any():
        raise ValueError(
            f"{bag_path}: message {int(np.argmax(bad))} of {topic} has a non-finite {what}"
        )
    return arr


class _Skipped(NamedTuple):
    """Messages :func:`_finite_rows` left out: how many, of how many, and the first one's
    index (in record order), record time (s) and non-finite field."""

    left_out: int
    total: int
    first: int
    record_time: float
    what: str


def _finite_rows(
    rows: FloatArray,
    columns: tuple[tuple[str, int, int], ...],
    skip: bool,
    bag_path: Any,
    topic: str,
    skipped: list[_Skipped],
) -> FloatArray:
    """``rows`` (record time, then the message's values), refused where a message holds a
    NaN or infinity, or without those messages (reported in ``skipped``) if ``skip``.

    ``columns`` names the fields: ``(what, start, stop)`` of ``rows``' columns. The
    error names the first such message by its index and record time, and its first
    non-finite field.
    """
    bad = ~np.isfinite(rows[:, 1:]).all(axis=1)
    if not bad.any():
        return rows
    first = int(np.argmax(bad))
    what = next(w for w, a, b in columns if not np.isfinite(rows[first, a:b]).all())
    when = float(rows[first, 0])
    if not skip:
        raise ValueError(
            f"{bag_path}: message {first} of {topic} has a non-finite {what} (recorded at "
            f"{when:.9f} s); skip_nonfinite=True leaves such messages out"
        )
    skipped.append(_Skipped(int(bad.sum()), int(rows.shape[0]), first, when, what))
    return rows[~bad]


def _warn_skipped(skipped: list[_Skipped], bag_path: Any, topic: str | None) -> None:
    """Report what :func:`_finite_rows` left out, as a ``RuntimeWarning`` of the caller's
    call (a reader's ``stacklevel=3``)."""
    for s in skipped:
        warnings.warn(
            f"{bag_path}: left out {s.left_out} of the {s.total} messages of "
            f"{topic if topic is not None else 'the topic'} holding a NaN or infinity "
            f"(skip_nonfinite=True); the first: message {s.first}, recorded at "
            f"{s.record_time:.9f} s, its {s.what}",
            RuntimeWarning,
            stacklevel=3,
        )


def read_bag_scans(path: str | os.PathLike[str], *, topic: str | None = None) -> BagScans:
    """Read the ``sensor_msgs/LaserScan`` messages of a ROS 1 or ROS 2 bag.

    Parameters
    ----------
    path : str or path-like
        A ROS 1 ``.bag`` file or a ROS 2 bag folder (with ``metadata.yaml``,
        SQLite or MCAP storage).
    topic : str, optional
        Topic to read; by default the bag's only LaserScan topic. Only its
        LaserScan messages are read (a ROS 1 topic may hold several types).

    Returns
    -------
    BagScans
        :class:`~navkit.mapping.LaserScan` objects (ranges and intensities as
        float64 copies of the message's float32 values) with their header
        stamps and record times, in record order.

    Raises
    ------
    ImportError
        The ``rosbags`` package is missing (install ``navkit[ros]``).
    FileNotFoundError
        ``path`` does not exist, or is a loop of symbolic links.
    TypeError
        ``path`` or ``topic`` of the wrong type.
    ValueError
        Not a bag, a corrupt bag; ``topic`` missing from the bag or
        without messages of this type; no LaserScan topic, or several and no
        ``topic``; a message that is not a valid LaserScan (the message says
        which); a ROS 2 bag whose messages on the topic are not as many as
        its ``metadata.yaml`` declares (damaged, or stale metadata). ROS 1
        bags whose index records are damaged (which ``rosbags`` refuses, or
        reads short of the counts the chunk-info records give) are read
        through their chunk records, each of which must hold the messages
        its chunk-info record counts (a damaged message record is refused,
        not dropped).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     read_bag_scans(Path(folder) / "missing.bag")
    Traceback (most recent call last):
    ...
    FileNotFoundError: ROS bag .../missing.bag does not exist
    """

    def convert(
        name: str, messages: Iterator[tuple[int, Any]], _declared: int, _stored: int | None
    ) -> BagScans:
        # One message at a time: a decoded message (its float32 readings and some kB of
        # objects) is let go once its scan is built.
        scans = []
        stamps = []
        record_times = []
        frame = None
        for i, (ns, msg) in enumerate(messages):
            if frame is None:
                frame = str(msg.header.frame_id)
            try:
                scans.append(scan_from_msg(msg))
            except (TypeError, ValueError) as exc:
                raise ValueError(f"{path}: message {i} of {name}: {exc}") from None
            stamps.append(_stamp(msg))
            record_times.append(_record_time(ns))
        times = _finite(np.array(stamps, dtype=np.float64), "stamp", path, name)
        return BagScans(
            name, frame or "", times, np.array(record_times, dtype=np.float64), tuple(scans)
        )

    return _decoded(path, topic, SCAN_TYPE, convert)


def read_bag_odometry(
    path: str | os.PathLike[str], *, topic: str | None = None, skip_nonfinite: bool = False
) -> BagOdometry:
    """Read the ``nav_msgs/Odometry`` messages of a ROS 1 or ROS 2 bag.

    Parameters
    ----------
    path : str or path-like
        A ROS 1 ``.bag`` file or a ROS 2 bag folder.
    topic : str, optional
        Topic to read; by default the bag's only Odometry topic. Only its
        Odometry messages are read (a ROS 1 topic may hold several types).
    skip_nonfinite : bool, default False
        Leave out the messages holding a NaN or an infinity (in any field
        read: stamp, pose, twist or a covariance), with a ``RuntimeWarning``
        saying how many and naming the first, instead of refusing the topic.
        Such a message is a driver's fault (an odometry node dividing by a
        zero time step); by default the error names it, so that it is seen.

    Returns
    -------
    BagOdometry
        Stamps, planar poses ``[x, y, yaw]``, orientations, twists
        ``[vx, vy, omega]`` and both 6×6 covariances, in record order.

    Raises
    ------
    ImportError
        The ``rosbags`` package is missing (install ``navkit[ros]``).
    FileNotFoundError
        ``path`` does not exist, or is a loop of symbolic links.
    TypeError
        ``path`` or ``topic`` of the wrong type; ``skip_nonfinite`` not a bool.
    ValueError
        As :func:`read_bag_scans`, and (unless ``skip_nonfinite``) a message
        with a non-finite value, named by its index in record order and its
        record time.

    Warns
    -----
    RuntimeWarning
        ``skip_nonfinite`` left messages out (how many, the first's index,
        record time and non-finite field).

    Examples
    --------
    >>> read_bag_odometry("missing.bag", topic=3)  # type: ignore[arg-type]
    Traceback (most recent call last):
    ...
    TypeError: topic must be a str or None, got int

    A bag of three messages, the second with a NaN speed:

    >>> import tempfile, warnings
    >>> from pathlib import Path
    >>> from rosbags.rosbag1 import Writer
    >>> from rosbags.typesys import Stores, get_typestore
    >>> store = get_typestore(Stores.ROS1_NOETIC)
    >>> T = store.types
    >>> def odometry(k, speed):
    ...     cov = np.eye(6).ravel()
    ...     vector = T["geometry_msgs/msg/Vector3"]
    ...     pose = T["geometry_msgs/msg/Pose"](
    ...         position=T["geometry_msgs/msg/Point"](x=float(k), y=0.0, z=0.0),
    ...         orientation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0))
    ...     twist = T["geometry_msgs/msg/Twist"](
    ...         linear=vector(x=speed, y=0.0, z=0.0), angular=vector(x=0.0, y=0.0, z=0.0))
    ...     stamp = T["builtin_interfaces/msg/Time"](sec=k, nanosec=0)
    ...     return T[ODOMETRY_TYPE](
    ...         header=T["std_msgs/msg/Header"](seq=k, stamp=stamp, frame_id="odom"),
    ...         child_frame_id="base_link",
    ...         pose=T["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=cov),
    ...         twist=T["geometry_msgs/msg/TwistWithCovariance"](twist=twist, covariance=cov))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = Path(folder) / "odom.bag"
    ...     with Writer(path) as writer:
    ...         conn = writer.add_connection("/odom", ODOMETRY_TYPE, typestore=store)
    ...         for k, speed in enumerate([1.0, float("nan"), 1.0]):
    ...             raw = store.serialize_ros1(odometry(k, speed), ODOMETRY_TYPE)
    ...             writer.write(conn, k * 10**9, raw)
    ...     try:
    ...         read_bag_odometry(path)
    ...     except ValueError as exc:
    ...         print(str(exc).split(": ", 1)[1])
    ...     with warnings.catch_warnings(record=True) as caught:
    ...         warnings.simplefilter("always")
    ...         odom = read_bag_odometry(path, skip_nonfinite=True)
    message 1 of /odom has a non-finite twist (recorded at 1.000000000 s);
    skip_nonfinite=True leaves such messages out
    >>> odom.times
    array([0., 2.])
    >>> print(str(caught[0].message).split(": ", 1)[1])
    left out 1 of the 3 messages of /odom holding a NaN or infinity
    (skip_nonfinite=True); the first: message 1, recorded at 1.000000000 s, its twist
    """

    def fill(m: Any, row: FloatArray) -> None:
        row[1] = _stamp(m)
        row[2:5] = _xyz(m.pose.pose.position)
        row[5:9] = _xyzw(m.pose.pose.orientation)
        row[9:12] = (*_xyz(m.twist.twist.linear)[:2], float(m.twist.twist.angular.z))
        row[12:48] = np.asarray(m.pose.covariance, float).reshape(36)
        row[48:84] = np.asarray(m.twist.covariance, float).reshape(36)

    def convert(name: str, first: Any, rows: FloatArray) -> BagOdometry:
        rows = _finite_rows(rows, _ODOMETRY_COLUMNS, skip, path, name, skipped)
        n = rows.shape[0]
        times = rows[:, 1]
        position = rows[:, 2:5]
        quat = rows[:, 5:9]
        twist = rows[:, 9:12]
        pose_cov = rows[:, 12:48].reshape(n, 6, 6)
        twist_cov = rows[:, 48:84].reshape(n, 6, 6)
        yaw = np.asarray(quaternion_to_yaw(quat), dtype=np.float64).reshape(n)
        return BagOdometry(
            name,
            "" if first is None else str(first.header.frame_id),
            "" if first is None else str(first.child_frame_id),
            times,
            rows[:, 0],
            np.column_stack((position[:, :2], yaw)),
            quat,
            twist,
            pose_cov,
            twist_cov,
        )

    skip = as_bool(skip_nonfinite, "skip_nonfinite")
    skipped: list[_Skipped] = []
    odometry = _read_rows(path, topic, ODOMETRY_TYPE, 84, fill, convert)
    _warn_skipped(skipped, path, odometry.topic)
    return odometry


def read_bag_imu(
    path: str | os.PathLike[str], *, topic: str | None = None, skip_nonfinite: bool = False
) -> BagImu:
    """Read the ``sensor_msgs/Imu`` messages of a ROS 1 or ROS 2 bag.

    Readings stay in the IMU's frame; :meth:`BagImu.to_base` rotates them into
    the robot's base frame, :func:`navkit.geometry.quaternion_to_yaw` gives the
    yaw of the orientations.

    Parameters
    ----------
    path : str or path-like
        A ROS 1 ``.bag`` file or a ROS 2 bag folder.
    topic : str, optional
        Topic to read; by default the bag's only Imu topic. Only its
        Imu messages are read (a ROS 1 topic may hold several types).
    skip_nonfinite : bool, default False
        Leave out the messages holding a NaN or an infinity, with a
        ``RuntimeWarning``, as :func:`read_bag_odometry` does.

    Returns
    -------
    BagImu
        Stamps, orientations, angular velocities, linear accelerations and
        their 3×3 covariances, in record order. A message whose orientation
        is all zero but whose ``orientation_covariance[0]`` is not -1 has its
        orientation marked not given (``orientation_covariances[i, 0, 0]`` set
        to -1, the rest as in the bag), with a ``RuntimeWarning``.

    Raises
    ------
    ImportError
        The ``rosbags`` package is missing (install ``navkit[ros]``).
    FileNotFoundError
        ``path`` does not exist, or is a loop of symbolic links.
    TypeError
        ``path`` or ``topic`` of the wrong type; ``skip_nonfinite`` not a bool.
    ValueError
        As :func:`read_bag_scans`, and (unless ``skip_nonfinite``) a message
        with a non-finite value, named by its index and record time.

    Warns
    -----
    RuntimeWarning
        ``skip_nonfinite`` left messages out (how many, the first's index,
        record time and non-finite field); messages with an all-zero
        orientation were marked "no orientation" (how many, the first's index
        and record time).

    Notes
    -----
    An IMU without an orientation estimate sends an all-zero quaternion with
    ``orientation_covariance[0] = -1`` (REP 145, ``sensor_msgs/Imu``'s
    comments). A driver that leaves the covariance unset sends the zero
    quaternion with a covariance that claims an orientation; a zero quaternion
    is no rotation, and read as one it would be yaw 0 (what
    :func:`navkit.geometry.quaternion_to_yaw` makes of it) and, turned by
    :meth:`BagImu.to_base`, the mounting's inverse. Such messages are marked
    "no orientation" as REP 145 asks, so that code honouring the -1 skips
    them; robot_localization instead fuses them as the identity rotation,
    with a diagnostic warning. Their angular velocities and accelerations are
    kept. Non-zero quaternions are kept as in the bag and normalised by
    whatever reads them (as tf2 and robot_localization do, float32 rounding
    included); NaN or infinite ones are refused, or left out with
    ``skip_nonfinite``, as every other non-finite value.

    Examples
    --------
    >>> read_bag_imu(b"imu.bag")  # type: ignore[arg-type]
    Traceback (most recent call last):
    ...
    TypeError: path must be a str or an os.PathLike, got bytes
    >>> read_bag_imu("imu.bag", skip_nonfinite="yes")  # type: ignore[arg-type]
    Traceback (most recent call last):
    ...
    TypeError: skip_nonfinite must be a bool, got str
    """

    def fill(m: Any, row: FloatArray) -> None:
        row[1] = _stamp(m)
        row[2:6] = _xyzw(m.orientation)
        row[6:9] = _xyz(m.angular_velocity)
        row[9:12] = _xyz(m.linear_acceleration)
        row[12:21] = np.asarray(m.orientation_covariance, float).reshape(9)
        row[21:30] = np.asarray(m.angular_velocity_covariance, float).reshape(9)
        row[30:39] = np.asarray(m.linear_acceleration_covariance, float).reshape(9)

    def convert(name: str, first: Any, rows: FloatArray) -> BagImu:
        # Found before _finite_rows so that the warning names the message's index among
        # all the topic's messages, as its errors do; a message it refuses or leaves out
        # is not counted (rows are this reader's own array, changed in place).
        unset = (
            (rows[:, 2:6] == 0.0).all(axis=1)
            & (rows[:, 12] != -1.0)
            & np.isfinite(rows[:, 1:]).all(axis=1)
        )
        if unset.any():
            first_unset = int(np.argmax(unset))
            when = float(rows[first_unset, 0])
            unmarked.append((int(unset.sum()), int(rows.shape[0]), first_unset, when))
            rows[unset, 12] = -1.0
        rows = _finite_rows(rows, _IMU_COLUMNS, skip, path, name, skipped)
        n = rows.shape[0]
        arrays = {
            "stamp": rows[:, 1],
            "orientation": rows[:, 2:6],
            "angular velocity": rows[:, 6:9],
            "linear acceleration": rows[:, 9:12],
            "orientation covariance": rows[:, 12:21].reshape(n, 3, 3),
            "angular velocity covariance": rows[:, 21:30].reshape(n, 3, 3),
            "linear acceleration covariance": rows[:, 30:39].reshape(n, 3, 3),
        }
        values = list(arrays.values())
        return BagImu(
            name,
            "" if first is None else str(first.header.frame_id),
            values[0],
            rows[:, 0],
            *values[1:],
        )

    skip = as_bool(skip_nonfinite, "skip_nonfinite")
    skipped: list[_Skipped] = []
    # (how many, of how many, the first's index and record time)
    unmarked: list[tuple[int, int, int, float]] = []
    imu = _read_rows(path, topic, IMU_TYPE, 39, fill, convert)
    _warn_skipped(skipped, path, imu.topic)
    for count, total, index, when in unmarked:
        warnings.warn(
            f"{path}: {count} of the {total} messages of {imu.topic} give an all-zero orientation "
            "quaternion (no rotation) without orientation_covariance[0] = -1, REP 145's "
            "'no orientation': marked so (orientation_covariances[i, 0, 0] = -1); the "
            f"first: message {index}, recorded at {when:.9f} s",
            RuntimeWarning,
            stacklevel=2,
        )
    return imu


def bag_topics(
    path: str | os.PathLike[str],
) -> dict[str, tuple[str, int] | tuple[tuple[str, int], ...]]:
    """Topics of a ROS 1 or ROS 2 bag with their message types and message counts.

    Parameters
    ----------
    path : str or path-like
        A ROS 1 ``.bag`` file or a ROS 2 bag folder.

    Returns
    -------
    dict
        ``{topic: (message type, count)}``, topics sorted, types spelled
        ``pkg/msg/Type``, counts summed over the topic's connections of that
        type. A bag may record one topic with connections of different message
        types (in ROS 1, a topic name reused by another node); such a topic's
        entry is instead a tuple of one ``(message type, count)`` pair per
        type, sorted by type, e.g. ``{"/x": (("nav_msgs/msg/Odometry", 4),
        ("sensor_msgs/msg/Imu", 5))}`` (check ``isinstance(entry[0], str)``
        to tell the two forms apart). A type declared by a connection without
        messages counts, with 0. The readers take from such a topic only the
        messages of their own type.

    Raises
    ------
    ImportError
        The ``rosbags`` package is missing (install ``navkit[ros]``).
    FileNotFoundError
        ``path`` does not exist, or is a loop of symbolic links.
    TypeError
        ``path`` of the wrong type.
    ValueError
        Not a bag or a corrupt bag.

    Examples
    --------
    >>> bag_topics("no-such.bag")
    Traceback (most recent call last):
    ...
    FileNotFoundError: ROS bag no-such.bag does not exist (relative to the working directory ...)
    """
    bag_path = _check_path(path)

    def entries(bag: _Bag) -> dict[str, tuple[str, int] | tuple[tuple[str, int], ...]]:
        out: dict[str, tuple[str, int] | tuple[tuple[str, int], ...]] = {}
        for topic, counts in bag.types().items():
            pairs = tuple(counts.items())
            out[topic] = pairs[0] if len(pairs) == 1 else pairs
        return out

    return _with_bag(bag_path, entries)
