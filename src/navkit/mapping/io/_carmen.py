"""Reader for CARMEN laser log files (FLASER, ROBOTLASER1 and ODOM lines)."""

from __future__ import annotations

import bz2
import codecs
import gzip
import io
import math
import os
import warnings
import zlib
from array import array
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, BinaryIO, NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.counts import counted
from navkit._shared.deprecation import renamed_keyword
from navkit._shared.dunders import bounded_repr
from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.times import as_times
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array, as_sequence, positive_float
from navkit.geometry import Pose2D, as_pose, wrap_angle
from navkit.mapping import LaserScan
from navkit.mapping.io._paths import as_path, missing_file, open_regular

if TYPE_CHECKING:
    import lzma  # imported when an xz file is read: optional in Python builds

__all__ = ["CarmenLog", "read_carmen"]

_TURN = 2.0 * math.pi
#: The largest ``range_max`` a LaserScan accepts, m.
_RANGE_LIMIT = 1e9
#: The longest line read, characters: a ROBOTLASER1 line of 100,000 beams and
#: remissions is about 2 MB. A line is held whole in memory (and split into
#: tokens of ~50 bytes each), so a file, or a small gzip'd one (gigabytes of a
#: byte repeated compress to megabytes), with no newline for gigabytes would
#: otherwise exhaust the memory.
LINE_MAX = 1 << 23
_NO_RANGES: FloatArray = np.empty(0)


def _guess_fov(n: int) -> float:
    """CARMEN's ``carmen_laser_guess_fov`` for FLASER lines, which carry no geometry."""
    table = {
        181: math.pi,
        180: math.radians(179.0),
        361: math.pi,
        360: math.radians(179.5),
        401: math.radians(100.0),
        400: math.radians(99.75),
    }
    return table.get(n, math.pi)


def _guess_increment(n: int) -> float:
    """CARMEN's ``carmen_laser_guess_angle_increment``."""
    if n in (180, 181):
        return math.pi / 180.0
    if n in (360, 361):
        return math.pi / 360.0
    if n in (400, 401):
        return math.pi / 720.0
    return _guess_fov(n) / (n - 1) if n > 1 else math.pi


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class CarmenLog:
    """Laser scans of a CARMEN log with their poses and times.

    Attributes
    ----------
    scans : tuple of LaserScan
        One scan per FLASER / ROBOTLASER1 line, in file order.
    laser_poses : tuple of Pose2D
        World pose of the laser for each scan (the pose to ray-cast from);
        ``[x, y, theta]`` sequences are converted.
    robot_poses : tuple of Pose2D
        Robot (odometry) pose logged with each scan.
    times : ndarray, shape (N,)
        Scan times, s (the line's own ``timestamp`` field), finite: ``times``
        as in the bag readers (:class:`BagScans`, :class:`BagOdometry`) and
        :class:`~navkit.estimation.MeasurementLog`. Stored as a read-only copy
        (the caller's array is neither kept nor frozen); refused where float64
        would round them, as in the bag readers. Required (its default
        None only lets the deprecated ``timestamps`` stand in for it).
        :func:`read_carmen` keeps them in file order as logged, each the
        float64 nearest its text (within 1.2e-7 s at epoch stamps, 1.7e9 s),
        neither sorted nor checked for order: real logs step back (Radish's
        intel log four times, by up to 0.86 s), and one printed with few
        digits (``1.13486e+09``) gives runs of equal times.
    odometry : ndarray, shape (M, 4)
        ODOM records ``(x, y, theta, time)`` (time in s), finite, ``theta``
        wrapped to (-π, π] (as the poses' headings are); an empty sequence
        gives shape (0, 4). Stored as a read-only copy. Required.
        :func:`read_carmen` keeps them in file order as logged, neither
        sorted nor checked for order, as ``times``: Radish's corrected logs
        follow scans with an ODOM line stamped 0 that repeats the scan's
        corrected pose (aces 440 rows, one per scan; csail 406; intel 841),
        and intel's other ODOM times step back 696 times. To look the
        odometry up at scan times, drop the rows stamped 0 and sort the
        rest by time (``np.argsort(odometry[:, 3], kind="stable")``) first.

    Other Parameters
    ----------------
    timestamps : array_like, shape (N,), optional
        Deprecated name of `times` (the :attr:`timestamps` property too).

    Raises
    ------
    TypeError
        A scan that is not a LaserScan, a pose that is not a pose, arrays that
        are not real-valued, a missing ``times`` or ``odometry``, both
        ``times`` and ``timestamps``.
    ValueError
        Non-finite times or odometry, wrong shapes, different lengths.

    Notes
    -----
    The poses are one :class:`~navkit.geometry.Pose2D` per scan, to pair with
    :attr:`scans` as :func:`~navkit.mapping.integrate_scan` and
    :meth:`~navkit.mapping.ScanMapper.update` take them (``for scan, pose in
    zip(log.scans, log.laser_poses)``); the numeric streams (``times``,
    ``odometry``) are arrays. :attr:`laser_trajectory` and
    :attr:`robot_trajectory` give the poses as an (N, 3) array ``[x, y,
    theta]``, the layout of the other trajectories (:attr:`BagOdometry.poses`,
    :attr:`~navkit.mapping.ScanMapper.trajectory`, ``Trace.poses`` of
    :mod:`navkit.sim`).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = Path(folder) / "log.txt"
    ...     _ = path.write_text("FLASER 3 1.0 2.0 5.0 0.5 0 0 0.5 0 0 12.5 host 12.6\\n")
    ...     log = read_carmen(path)
    >>> len(log), log.laser_poses[0], log.times
    (1, Pose2D(x=0.5, y=0.0, theta=0.0), array([12.5]))
    >>> log.laser_trajectory  # the poses as an (N, 3) array
    array([[0.5, 0. , 0. ]])
    """

    scans: tuple[LaserScan, ...]
    laser_poses: tuple[Pose2D, ...]
    robot_poses: tuple[Pose2D, ...]
    times: FloatArray
    odometry: FloatArray

    # Fields renamed since a release, for pickles made before (see
    # navkit._shared.frozen.rebuild_record). Not annotated: a ClassVar would still
    # be listed in __dataclass_fields__.
    _renamed_fields = MappingProxyType({"timestamps": "times"})

    def __init__(
        self,
        scans: tuple[LaserScan, ...],
        laser_poses: tuple[Pose2D, ...],
        robot_poses: tuple[Pose2D, ...],
        times: ArrayLike | None = None,
        odometry: ArrayLike | None = None,
        *,
        timestamps: ArrayLike | None = None,
    ) -> None:
        # Written out (the dataclass keeps a class's own __init__) for the deprecated
        # keyword; the checks stay in __post_init__, which dataclass subclasses'
        # generated __init__ call too.
        times = renamed_keyword("timestamps", timestamps, "times", times, None)
        for name, value in (("times", times), ("odometry", odometry)):
            if value is None:
                raise TypeError(f"CarmenLog() missing the argument {name}")
        object.__setattr__(self, "scans", scans)
        object.__setattr__(self, "laser_poses", laser_poses)
        object.__setattr__(self, "robot_poses", robot_poses)
        object.__setattr__(self, "times", times)
        object.__setattr__(self, "odometry", odometry)
        self.__post_init__()

    __repr__ = bounded_repr  # a log of thousands of scans printed megabytes

    def __post_init__(self) -> None:
        scans = as_sequence(self.scans, "scans")
        for i, scan in enumerate(scans):
            if not isinstance(scan, LaserScan):
                raise TypeError(f"scans[{i}] must be a LaserScan, got {type(scan).__name__}")
        laser = tuple(
            as_pose(p, f"laser_poses[{i}]")
            for i, p in enumerate(as_sequence(self.laser_poses, "laser_poses"))
        )
        robot = tuple(
            as_pose(p, f"robot_poses[{i}]")
            for i, p in enumerate(as_sequence(self.robot_poses, "robot_poses"))
        )
        stamps = np.array(as_times(self.times, "times"), copy=True)
        odometry_in = as_float_array(self.odometry, "odometry")
        if odometry_in.size == 0:
            odometry_in = odometry_in.reshape(0, 4)
        odometry = np.array(as_float_array(odometry_in, "odometry", shape=(None, 4)), copy=True)
        # Logs write the integrated odometry heading unwrapped (csail's reaches 11 rad).
        odometry[:, 2] = wrap_angle(odometry[:, 2])
        if not len(scans) == len(laser) == len(robot) == stamps.shape[0]:
            raise ValueError(
                "scans, laser_poses, robot_poses and times must have the same length, got "
                f"{len(scans)}, {len(laser)}, {len(robot)} and {stamps.shape[0]}"
            )
        stamps.flags.writeable = False
        odometry.flags.writeable = False
        object.__setattr__(self, "scans", scans)
        object.__setattr__(self, "laser_poses", laser)
        object.__setattr__(self, "robot_poses", robot)
        object.__setattr__(self, "times", stamps)
        object.__setattr__(self, "odometry", odometry)

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("times", "odometry"))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from an older pickle, the arrays read-only again."""
        restore_read_only(self, state, ("times", "odometry"))

    @property
    def timestamps(self) -> FloatArray:
        """Deprecated alias of :attr:`times`.

        Examples
        --------
        >>> import tempfile
        >>> from pathlib import Path
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     path = Path(folder) / "log.txt"
        ...     _ = path.write_text("FLASER 1 1.0 0 0 0 0 0 0 12.5 host 12.6\\n")
        ...     read_carmen(path).times  # the new name
        array([12.5])
        """
        warnings.warn(
            "CarmenLog.timestamps is deprecated and will be removed in a future release: "
            "use CarmenLog.times",
            DeprecationWarning,
            stacklevel=2,
        )
        return self.times

    @property
    def laser_trajectory(self) -> FloatArray:
        """:attr:`laser_poses` as rows ``[x, y, theta]``, (N, 3) float64, a read-only copy.

        The layout of :attr:`~navkit.mapping.ScanMapper.trajectory` and
        :attr:`BagOdometry.poses`: compare a mapper's poses with the log's,
        plot them or take their points (``[:, :2]``). Built at each access
        (about 0.2 µs a pose); keep it in a variable to use it more than once.

        Examples
        --------
        >>> log = CarmenLog((), (), (), times=[], odometry=[])
        >>> log.laser_trajectory.shape
        (0, 3)
        """
        return _pose_rows(self.laser_poses)

    @property
    def robot_trajectory(self) -> FloatArray:
        """:attr:`robot_poses` as rows ``[x, y, theta]``, (N, 3) float64, a read-only copy.

        As :attr:`laser_trajectory`, for the robot (odometry) poses logged
        with the scans.

        Examples
        --------
        >>> import tempfile
        >>> from pathlib import Path
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     path = Path(folder) / "log.txt"
        ...     _ = path.write_text("FLASER 1 1.0 0.5 0 0 0.25 0 0.1 12.5 host 12.6\\n")
        ...     read_carmen(path).robot_trajectory
        array([[0.25, 0.  , 0.1 ]])
        """
        return _pose_rows(self.robot_poses)

    def __len__(self) -> int:
        return len(self.scans)


def _pose_rows(poses: tuple[Pose2D, ...]) -> FloatArray:
    """Rows ``[x, y, theta]`` of checked poses, (N, 3), read-only."""
    out = np.array([(p.x, p.y, p.theta) for p in poses], dtype=np.float64).reshape(-1, 3)
    out.flags.writeable = False
    return out


# ---------------------------------------------------------------- parsing
class _LineError(ValueError):
    """A problem with one log line (the reader adds the file and line number)."""


class _Record(NamedTuple):
    """One laser line, parsed and checked."""

    line: int
    ranges: FloatArray
    angle_min: float
    angle_increment: float
    range_max: float | None  # None: a FLASER line (no geometry)
    intensities: FloatArray | None
    laser_pose: tuple[float, float, float]
    robot_pose: tuple[float, float, float]
    timestamp: float


#: The first bytes of the compressed files read (their format's name), and of those
#: named when refused: decompressed as text, the others read as "no FLASER lines".
_COMPRESSIONS = ((b"\x1f\x8b", "gzip"), (b"\xfd7zXZ\x00", "xz"))
_NOT_READ = (
    (b"PK\x03\x04", "zip archive"),
    (b"\x28\xb5\x2f\xfd", "zstd-compressed file"),
    (b"7z\xbc\xaf\x27\x1c", "7z archive"),
    (b"\x04\x22\x4d\x18", "lz4-compressed file"),
)


class _CorruptFile(ValueError):
    """A compressed log that cannot be decompressed (the reader adds the file and line)."""

    def __init__(self, compression: str, exc: BaseException) -> None:
        super().__init__(f"{type(exc).__name__}: {exc}")
        self.compression = compression


def _compression(head: bytes, path: Path) -> str:
    """The compression of a file starting with ``head`` ("" for none)."""
    for magic, name in _COMPRESSIONS:
        if head.startswith(magic):
            return name
    if head[:3] == b"BZh" and head[3:4].isdigit() and head[3:4] != b"0":
        return "bzip2"
    for magic, what in _NOT_READ:
        if head.startswith(magic):
            raise ValueError(
                f"{path}: a {what}, not a CARMEN log: read_carmen reads plain, gzip, bzip2 "
                "and xz files; extract or decompress the log first"
            )
    return ""


def _decompressed(
    raw: BinaryIO, compression: str, path: Path
) -> tuple[BinaryIO | gzip.GzipFile | bz2.BZ2File | lzma.LZMAFile, tuple[type[Exception], ...]]:
    """``raw`` decompressed as ``compression`` says, and the errors its damage raises."""
    if compression == "gzip":
        return gzip.GzipFile(fileobj=raw, mode="rb"), (EOFError, zlib.error, gzip.BadGzipFile)
    if compression == "bzip2":
        # A damaged stream is an OSError without an errno; a failing disk's has one.
        return bz2.BZ2File(raw, mode="rb"), (EOFError, OSError)
    if compression == "xz":
        try:
            import lzma  # optional: Python builds without liblzma lack it
        except ImportError:
            raise ValueError(
                f"{path}: an xz-compressed file, and this Python has no lzma module: "
                "decompress it first (xz -d)"
            ) from None
        return lzma.LZMAFile(raw, mode="rb"), (EOFError, lzma.LZMAError)
    return raw, ()


def _lines(path: Path, found: list[str] | None = None) -> Iterator[str]:
    """Lines of a plain, gzip, bzip2 or xz log, read lazily (bytes not ASCII are replaced).

    A line longer than :data:`LINE_MAX` is given cut to ``LINE_MAX + 1`` characters.
    A damaged compressed file raises :class:`_CorruptFile`. The compression ("" for
    none) is appended to ``found`` before the first line.
    """
    # Opened once and checked on its descriptor: a FIFO swapped in after
    # read_carmen's check by name is refused instead of read (which blocked for ever).
    with open_regular(path, "CARMEN log") as raw:
        compression = _compression(raw.read(6), path)
        if found is not None:
            found.append(compression)
        raw.seek(0)
        binary, damage = _decompressed(raw, compression, path)
        with io.TextIOWrapper(binary, encoding="ascii", errors="replace") as fh:
            try:
                # A UTF-8 byte-order mark (as Windows Notepad writes) is skipped: read
                # as ASCII it made a first FLASER line an unknown kind, dropped unseen.
                head = binary.read(len(codecs.BOM_UTF8))
                # UTF-32-LE's mark starts as UTF-16-LE's; UTF-32-BE's (00 00 fe ff) does
                # not (review 51: such a copy read as "no FLASER lines").
                if head[:2] in (codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE) or (
                    head == codecs.BOM_UTF32_BE[:3]
                ):
                    # Windows PowerShell 5's ">" writes UTF-16 (with its mark): read as
                    # ASCII, every line was an unknown kind ("no FLASER lines").
                    raise ValueError(
                        f"{path}: UTF-16 text (or UTF-32), not a CARMEN log, whose lines "
                        "are ASCII: save it as ASCII or UTF-8"
                    )
                if head != codecs.BOM_UTF8:
                    binary.seek(0)
                lines = iter(lambda: fh.readline(LINE_MAX + 1), "")
                first = next(lines, "")
                if _is_tar_header(first):
                    compressed = f" ({compression}-compressed)" if compression else ""
                    raise ValueError(
                        f"{path}: a tar archive{compressed}, not a CARMEN log: extract the "
                        "log from it first"
                    )
                if first:
                    yield first
                yield from lines
            except damage as exc:
                if isinstance(exc, OSError) and exc.errno is not None:
                    raise  # the disk's, not the data's
                raise _CorruptFile(compression, exc) from None


def _is_tar_header(line: str) -> bool:
    """Whether the first line of a file is a tar header (POSIX or GNU, "ustar" at 257).

    Read as text, a tar archive of one log (``.tar.gz``) gave the log's lines after a
    header line the parser skipped, and one of several logs gave them all, run
    together as one. The header's NUL bytes tell it from a log line holding "ustar".
    """
    return line[257:262] == "ustar" and "\x00" in line[:257]


def _count(token: str, what: str) -> int:
    """A count field: a non-negative integer written as one."""
    if not (token.isascii() and token.isdigit()):
        raise _LineError(f"{what} must be a non-negative integer, got {token[:20]!r}")
    if len(token) > 12:
        raise _LineError(f"{what} {token[:20]}... is out of range")
    return int(token)


def _values(tokens: list[str], what: str, hint: str = "") -> FloatArray:
    """``tokens`` as finite float64 numbers."""
    # Python (and so NumPy) reads "1_0" as 10; CARMEN's strtod stops at the underscore.
    # (One search of the joined tokens: a generator over a scan's 180 tokens cost a third
    # of the parse.)
    if "_" in "".join(tokens):
        raise _LineError(f"{what} must be numbers{hint}")
    try:
        out = np.array(tokens, dtype=np.float64)
    except ValueError:
        raise _LineError(f"{what} must be numbers{hint}") from None
    finite = np.isfinite(out)
    if not finite.all():
        raise _LineError(f"{what} must be finite, got {tokens[int(np.argmin(finite))]!r}")
    return out


def _fields(tokens: list[str], need: int, what: str, terminated: bool) -> None:
    """``tokens`` must hold ``need`` fields, then at most a host name and a logger timestamp.

    A line without its newline (the file's last) that ends right after the
    timestamp may have been cut inside it (``480.86`` read as ``480``), so is
    refused; with the host after it, the timestamp is known to be whole.
    """
    if not need <= len(tokens) <= need + 2:
        raise _LineError(
            f"{len(tokens)} fields where the counts give {need} (+ host and logger "
            f"timestamp); {what}"
        )
    if not terminated and len(tokens) == need:
        raise _LineError(
            "the file ends inside this line (no newline, nor host and logger timestamp "
            "after the timestamp): it looks truncated; end the line with a newline if "
            "it is whole"
        )


def _triple(values: FloatArray, start: int) -> tuple[float, float, float]:
    return float(values[start]), float(values[start + 1]), float(values[start + 2])


def _flaser(number: int, tokens: list[str], terminated: bool) -> _Record:
    """``FLASER n r_1 .. r_n x y theta odom_x odom_y odom_theta timestamp [host logger_ts]``."""
    if not tokens:
        raise _LineError("no beam count")
    n = _count(tokens[0], "the beam count")
    if n == 0:
        raise _LineError("the beam count must be at least 1")
    _fields(tokens, n + 8, "is the beam count right?", terminated)
    vals = _values(tokens[1 : n + 8], "ranges, poses and timestamp", " (is the beam count right?)")
    return _Record(
        number,
        vals[:n],
        -math.pi / 2.0,
        _guess_increment(n),
        None,
        None,
        _triple(vals, n),
        _triple(vals, n + 3),
        float(vals[n + 6]),
    )


def _robotlaser1(number: int, tokens: list[str], terminated: bool) -> _Record:
    """``ROBOTLASER1 type start fov increment max_range accuracy remission_mode n r_1..r_n
    n_rem rem_1..rem_n_rem laser_x laser_y laser_theta robot_x robot_y robot_theta tv rv
    forward_safety side_safety turn_axis timestamp [host logger_ts]``."""
    if len(tokens) < 9:
        raise _LineError(f"only {counted(len(tokens), 'field')}")
    head = _values(tokens[0:7], "laser type, angles, range and accuracy")
    start, fov, inc, maxr = (float(v) for v in head[1:5])
    if abs(fov) > _TURN + 1e-5:
        raise _LineError(
            f"field of view {fov:g} rad exceeds a full turn (2π): the angles look like "
            "degrees; CARMEN logs give radians"
        )
    n = _count(tokens[7], "the beam count")
    if n == 0:
        raise _LineError("the beam count must be at least 1")
    if len(tokens) < 9 + n:
        raise _LineError(f"{counted(len(tokens) - 8, 'field')} after the beam count {n}")
    n_rem = _count(tokens[8 + n], "the remission count")
    _fields(tokens, 9 + n + n_rem + 12, "are the beam and remission counts right?", terminated)
    hint = " (are the beam and remission counts right?)"
    ranges = _values(tokens[8 : 8 + n], "ranges", hint)
    remissions = _values(tokens[9 + n : 9 + n + n_rem], "remissions", hint)
    tail = _values(tokens[9 + n + n_rem : 21 + n + n_rem], "poses, speeds and timestamp", hint)
    return _Record(
        number,
        ranges,
        start,
        inc,
        maxr,
        remissions if n_rem == n else None,
        _triple(tail, 0),
        _triple(tail, 3),
        float(tail[11]),
    )


def _odom(tokens: list[str], terminated: bool) -> tuple[float, float, float, float]:
    """``ODOM x y theta tv rv accel timestamp [host logger_ts]``."""
    _fields(tokens, 7, "expected x y theta tv rv accel timestamp", terminated)
    what = "pose, speeds and timestamp"
    # _values's checks on Python floats: an array for 7 numbers cost most of the time of
    # a log (10-20 ODOM lines a scan). NumPy parses a str with float(), so the values
    # and the strings refused are the same.
    head = tokens[0:7]
    if "_" in "".join(head):
        raise _LineError(f"{what} must be numbers")
    try:
        vals = [float(token) for token in head]
    except ValueError:
        raise _LineError(f"{what} must be numbers") from None
    for token, value in zip(head, vals, strict=True):
        if not math.isfinite(value):
            raise _LineError(f"{what} must be finite, got {token!r}")
    return vals[0], vals[1], vals[2], vals[6]


#: The message names read; a line naming one in another letter case is skipped, as
#: CARMEN's readers skip it, and named when the log holds no laser line.
_KINDS = frozenset(("FLASER", "ROBOTLASER1", "ODOM"))


def _parse(log_path: Path) -> tuple[list[_Record], array[float], tuple[int, str] | None]:
    """Every laser line of the log, its ODOM lines' ``x y theta timestamp`` one after
    another, and the first line whose message name is one of those in another letter
    case (its number and name, or None); errors name the file and line."""
    records: list[_Record] = []
    other_case: tuple[int, str] | None = None
    # 32 bytes an ODOM line, not the 150 of a tuple of floats (logs hold 10-20 a scan).
    odometry = array("d")
    number = 0
    kind = ""
    compression: list[str] = []
    lines = _lines(log_path, compression)
    try:
        for number, line in enumerate(lines, start=1):
            if len(line) > LINE_MAX:
                raise ValueError(
                    f"{log_path}:{number}: line longer than {LINE_MAX} characters: not a "
                    "CARMEN log line (no newline for megabytes: binary data or a damaged file?)"
                )
            # The kind ends at any blank, as MRPT's and GMapping's readers split it:
            # a hand edit's tab after it (or a blank before it) made the line an
            # unknown kind, dropped unseen. CARMEN's own playback splits at a space.
            named = line.split(None, 1)
            kind = named[0] if named else ""
            rest = named[1] if len(named) == 2 else ""
            # Only the last line can lack it (text mode reads \r\n and \r as \n).
            terminated = line.endswith("\n")
            if kind == "ODOM":
                odometry.extend(_odom(rest.split(), terminated))
            elif kind == "FLASER":
                records.append(_flaser(number, rest.split(), terminated))
            elif kind == "ROBOTLASER1":
                records.append(_robotlaser1(number, rest.split(), terminated))
            elif other_case is None and kind.upper() in _KINDS:
                # Skipped as CARMEN's readers skip it (they compare names case-sensitively),
                # but kept to name in the error of a log holding no laser line else.
                other_case = (number, kind)
    except _LineError as exc:
        _refuse_damaged(lines, compression, log_path, number)
        raise ValueError(f"{log_path}:{number}: malformed {kind} line: {exc}") from None
    except _CorruptFile as exc:
        raise ValueError(
            f"{log_path}: corrupt or truncated {exc.compression} file (after "
            f"{counted(number, 'line')}: {exc})"
        ) from None
    return records, odometry, other_case


def _refuse_damaged(lines: Iterator[str], compression: list[str], path: Path, number: int) -> None:
    """Raise the damage of a compressed log whose line ``number`` is malformed, if it has any.

    A compressed file's check (gzip's CRC at its end, bzip2's at each 900 kB block's)
    comes after the damaged data has been decompressed: a flipped byte read as a
    malformed line, and only the rest of the file tells the two apart (review 27:
    of 40 random single-bit flips each, 34 in a gzip log, 33 in a bzip2 one and 12
    in an xz one were reported as malformed lines). Read on this error path only,
    plain files never: at most what reading the whole file costs. (Not for a line
    beyond LINE_MAX: binary data, as a decompression bomb, is refused at once, and
    the check stops at one, where the parser would: read through, 1 GB of zeros
    after a malformed line took 0.8 s; review 28.)
    """
    if not compression or not compression[0]:
        return
    try:
        for line in lines:
            if len(line) > LINE_MAX:
                return
    except _CorruptFile as exc:
        raise ValueError(
            f"{path}: corrupt or truncated {exc.compression} file (line {number} came out "
            f"malformed, and the file then failed its check: {exc})"
        ) from None


def _scan(log_path: Path, record: _Record, range_min: float, range_max: float | None) -> LaserScan:
    rmax = record.range_max
    if rmax is None:  # FLASER: the reader's range_max or the largest FLASER reading
        if range_max is None or range_max <= range_min:
            raise ValueError(
                f"{log_path}: cannot determine a maximum range of the FLASER scans above "
                f"range_min ({range_min} m); give range_max"
            )
        rmax = range_max
    # A ROBOTLASER1 line's own maximum range is checked by LaserScan, naming the line.
    try:
        return LaserScan(
            record.ranges,
            angle_min=record.angle_min,
            angle_increment=record.angle_increment,
            range_min=range_min,
            range_max=rmax,
            intensities=record.intensities,
        )
    except ValueError as exc:
        raise ValueError(f"{log_path}:{record.line}: {exc}") from None


def read_carmen(
    path: str | os.PathLike[str],
    *,
    range_max: float | None = None,
    range_min: float = 0.0,
) -> CarmenLog:
    """Read the laser scans, poses and odometry of a CARMEN log (plain or compressed).

    ``FLASER n r_1 .. r_n x y theta odom_x odom_y odom_theta timestamp host
    logger_timestamp`` lines carry no scanner geometry, so CARMEN's own guesses
    are used: the first beam at -90° and an increment of 1° for 180/181 beams,
    0.5° for 360/361, 0.25° for 400/401, otherwise 180° spread over ``n - 1``
    gaps. ``ROBOTLASER1`` lines carry their start angle, increment, maximum
    range and remissions (as intensities). ``ODOM`` lines give ``odometry``.
    Every count must match the fields that follow it (the host name and
    logger timestamp at the end of a line are optional, except on a last line
    without its newline: a file cut inside the timestamp would otherwise read
    as a wrong timestamp).

    Parameters
    ----------
    path : str or path-like
        Log file: plain text, or compressed with gzip, bzip2 or xz (told by
        its first bytes, whatever its name). Line ends may be ``\\n``,
        ``\\r\\n`` or ``\\r``; a UTF-8 byte-order mark starting the (decompressed)
        text is skipped. Fields are separated by spaces or tabs, and blanks
        before a line's message name are skipped (as MRPT's and GMapping's
        readers do; CARMEN's own playback wants one space after the name).
        Message names are upper case, matched exactly as CARMEN's readers
        (and MRPT's and GMapping's) match them: a line starting ``flaser`` is
        of another kind, skipped as ``PARAM`` or ``SYNC`` lines are.
    range_max : float, optional
        Maximum range of FLASER scans, m, in (``range_min``, 1e9]. Readings
        equal to or beyond it are "no return". By default the largest FLASER
        reading in the file is used, since CARMEN logs store "no return" as
        the scanner's maximum value.
    range_min : float, default 0.0
        Minimum valid range, m (>= 0): every reading is kept by default (a
        CARMEN log says nothing of its scanner's minimum). Hector mapping
        drops readings below 0.4 m (``laser_min_dist``, against returns from
        the robot's own body); pass ``range_min=0.4`` for that. Measured on the
        Radish aces log (review 54): 54 of its 79,200 readings (in 9 scans,
        0.32-0.39 m) lie below 0.4 m, and dropping them moved
        :class:`~navkit.mapping.ScanMapper`'s mean distance from the corrected
        poses (odometry off by 5 cm and 2° a step, 12 seeds) from 1.37 to
        1.27 m on the mean over seeds, by 0.59 m a seed on the mean either
        way, as much as dropping 54 readings picked at random does (to 0.98 m,
        by 0.62 m a seed): a change within the mapper's spread, so the
        default keeps them.

    Returns
    -------
    CarmenLog
        The scans in file order with their laser and robot poses and
        times, and the ODOM records.

    Raises
    ------
    TypeError
        A ``path`` that is not a str or path-like; a ``range_min`` or
        ``range_max`` that is not a real number.
    FileNotFoundError
        Missing file, or a loop of symbolic links.
    ValueError
        A corrupt or truncated compressed file; a zip, 7z, zstd or lz4 file
        (named: decompress it first); UTF-16 or UTF-32 text with its
        byte-order mark; a line longer than 2**23 characters
        (binary data: lines are read whole); a malformed FLASER, ROBOTLASER1 or
        ODOM line (the message names the file and line number): fields that
        are not numbers, NaN or infinite values, negative counts, counts that
        do not match the number of fields, a last line that may have been
        cut (no newline and nothing after the timestamp), angles in degrees (a field of view
        or beams spanning more than 2π, a start angle beyond ±2π), a maximum
        range beyond 1e9 m (a ROBOTLASER1 line's or, without ``range_max``,
        the largest FLASER reading); a log without laser lines (naming the
        first line whose message name is FLASER, ROBOTLASER1 or ODOM in
        another letter case); a bad ``range_min`` or ``range_max``.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = Path(folder) / "log.txt"
    ...     _ = path.write_text("FLASER 3 1.0 2.0 5.0 0 0 0 0 0 0 1.0 host 1.0\\n")
    ...     scan = read_carmen(path).scans[0]
    >>> scan.range_max, scan.valid_mask()
    (5.0, array([ True,  True, False]))
    """
    log_path = as_path(path, "path")
    if not log_path.exists():
        raise missing_file(log_path, "CARMEN log")
    if not log_path.is_file():
        raise ValueError(f"CARMEN log {log_path} is not a regular file")
    rmin = positive_float(range_min, "range_min", allow_zero=True)
    rmax_user = None if range_max is None else positive_float(range_max, "range_max")
    if rmax_user is not None:  # LaserScan's own range checks, before reading the file
        LaserScan(
            np.ones(1), angle_min=0.0, angle_increment=1.0, range_min=rmin, range_max=rmax_user
        )
    records, odometry, other_case = _parse(log_path)
    if not records:
        hint = ""
        if other_case is not None:
            hint = (
                f" (line {other_case[0]} starts with {other_case[1]!r}: CARMEN's message "
                "names are upper case, and its readers take no other)"
            )
        raise ValueError(f"{log_path}: no FLASER or ROBOTLASER1 lines{hint}")

    flaser_max = rmax_user
    if flaser_max is None:
        # A generator: a list would keep every parsed reading alive below.
        flaser = (r for r in records if r.range_max is None)
        # The first line holding the largest reading, named if it is out of range
        # (every FLASER scan would otherwise be refused for it, naming the first).
        top = max(flaser, key=lambda r: (float(r.ranges.max()), -r.line), default=None)
        if top is not None:
            flaser_max = float(top.ranges.max())
            if flaser_max > _RANGE_LIMIT:
                raise ValueError(
                    f"{log_path}:{top.line}: FLASER reading {flaser_max} m exceeds 1e9 m, so "
                    "cannot be the scans' maximum range (taken from the largest reading "
                    "when range_max is not given); give range_max"
                )
    scans = []
    for i, record in enumerate(records):
        scans.append(_scan(log_path, record, rmin, flaser_max))
        # The scan holds its own copy: drop the parsed one, so that the log's
        # readings are not held twice.
        records[i] = record._replace(ranges=_NO_RANGES, intensities=None)
    return CarmenLog(
        scans=tuple(scans),
        laser_poses=tuple(Pose2D(*r.laser_pose) for r in records),
        robot_poses=tuple(Pose2D(*r.robot_pose) for r in records),
        times=np.array([r.timestamp for r in records], dtype=np.float64),
        odometry=np.frombuffer(odometry, dtype=np.float64).reshape(-1, 4),
    )
