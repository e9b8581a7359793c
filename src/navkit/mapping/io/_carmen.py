"""Reader for CARMEN laser log files (FLASER, ROBOTLASER1 and ODOM lines)."""

from __future__ import annotations

import gzip
import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array, positive_float
from navkit.geometry import Pose2D
from navkit.mapping import LaserScan

__all__ = ["CarmenLog", "read_carmen"]


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


@dataclass(frozen=True, slots=True, eq=False)
class CarmenLog:
    """Laser scans of a CARMEN log with their poses and timestamps.

    Attributes
    ----------
    scans : tuple of LaserScan
        One scan per FLASER / ROBOTLASER1 line, in file order.
    laser_poses : tuple of Pose2D
        World pose of the laser for each scan (the pose to ray-cast from).
    robot_poses : tuple of Pose2D
        Robot (odometry) pose logged with each scan.
    timestamps : ndarray, shape (N,)
        Scan timestamps, s (the message's own ``timestamp`` field).
    odometry : ndarray, shape (M, 4)
        ODOM records ``(x, y, theta, timestamp)``.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = Path(folder) / "log.txt"
    ...     _ = path.write_text("FLASER 3 1.0 2.0 5.0 0.5 0 0 0.5 0 0 12.5 host 12.6\\n")
    ...     log = read_carmen(path)
    >>> len(log), log.laser_poses[0], log.timestamps
    (1, Pose2D(x=0.5, y=0.0, theta=0.0), array([12.5]))
    """

    scans: tuple[LaserScan, ...]
    laser_poses: tuple[Pose2D, ...]
    robot_poses: tuple[Pose2D, ...]
    timestamps: FloatArray
    odometry: FloatArray

    def __post_init__(self) -> None:
        scans = tuple(self.scans)
        laser = tuple(self.laser_poses)
        robot = tuple(self.robot_poses)
        stamps = np.array(
            as_float_array(self.timestamps, "timestamps", ndim=1, finite=False), copy=True
        )
        odometry = np.array(
            as_float_array(self.odometry, "odometry", shape=(None, 4), finite=False), copy=True
        )
        if not len(scans) == len(laser) == len(robot) == stamps.shape[0]:
            raise ValueError(
                "scans, laser_poses, robot_poses and timestamps must have the same length, got "
                f"{len(scans)}, {len(laser)}, {len(robot)} and {stamps.shape[0]}"
            )
        stamps.flags.writeable = False
        odometry.flags.writeable = False
        object.__setattr__(self, "scans", scans)
        object.__setattr__(self, "laser_poses", laser)
        object.__setattr__(self, "robot_poses", robot)
        object.__setattr__(self, "timestamps", stamps)
        object.__setattr__(self, "odometry", odometry)

    def __len__(self) -> int:
        return len(self.scans)


def _open_text(path: Path) -> list[str]:
    with path.open("rb") as fh:
        magic = fh.read(2)
    if magic == b"\x1f\x8b":
        with gzip.open(path, "rt", encoding="ascii", errors="replace") as fh:
            return fh.read().splitlines()
    return path.read_text(encoding="ascii", errors="replace").splitlines()


def read_carmen(
    path: str | os.PathLike[str],
    *,
    range_max: float | None = None,
    range_min: float = 0.0,
) -> CarmenLog:
    """Read the laser scans, poses and odometry of a CARMEN log (plain or gzip'd).

    ``FLASER n r_1 .. r_n x y theta odom_x odom_y odom_theta timestamp host
    logger_timestamp`` lines carry no scanner geometry, so CARMEN's own guesses
    are used: the first beam at -90° and an increment of 1° for 180/181 beams,
    0.5° for 360/361, 0.25° for 400/401, otherwise 180° spread over ``n - 1``
    gaps. ``ROBOTLASER1`` lines carry their start angle, increment, maximum
    range and remissions (as intensities). ``ODOM`` lines give ``odometry``.

    Parameters
    ----------
    path : str or path-like
        Log file, gzip'd or not.
    range_max : float, optional
        Maximum range of FLASER scans, m. Readings equal to or beyond it are "no
        return". By default the largest FLASER reading in the file is used, since
        CARMEN logs store "no return" as the scanner's maximum value.
    range_min : float, default 0.0
        Minimum valid range, m.

    Raises
    ------
    FileNotFoundError
        Missing file.
    ValueError
        A malformed laser line (the message names the line number) or a log
        without laser lines.

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
    log_path = Path(path)
    if not log_path.is_file():
        raise FileNotFoundError(f"CARMEN log {log_path} does not exist")
    rmin = positive_float(range_min, "range_min", allow_zero=True)
    rmax_user = None if range_max is None else positive_float(range_max, "range_max")

    # Parsed records: (ranges, angle_min, increment, range_max or None, intensities,
    # laser pose, robot pose, timestamp).
    records: list[
        tuple[
            FloatArray,
            float,
            float,
            float | None,
            FloatArray | None,
            tuple[float, float, float],
            tuple[float, float, float],
            float,
        ]
    ] = []
    odometry: list[tuple[float, float, float, float]] = []
    for number, line in enumerate(_open_text(log_path), start=1):
        kind, _, rest = line.partition(" ")
        if kind not in ("FLASER", "ROBOTLASER1", "ODOM"):
            continue
        tokens = rest.split()
        try:
            if kind == "ODOM":
                x, y, th = (float(t) for t in tokens[0:3])
                odometry.append((x, y, th, float(tokens[6])))
                continue
            if kind == "FLASER":
                n = int(tokens[0])
                vals = np.array(tokens[1 : n + 8], dtype=np.float64)
                if n <= 0 or vals.shape[0] != n + 7:
                    raise IndexError
                records.append(
                    (
                        vals[:n],
                        -math.pi / 2.0,
                        _guess_increment(n),
                        None,
                        None,
                        (vals[n], vals[n + 1], vals[n + 2]),
                        (vals[n + 3], vals[n + 4], vals[n + 5]),
                        float(vals[n + 6]),
                    )
                )
            else:
                start, _fov, inc, maxr = (float(t) for t in tokens[1:5])
                n = int(tokens[7])
                ranges = np.array(tokens[8 : 8 + n], dtype=np.float64)
                k = 8 + n
                n_rem = int(tokens[k])
                remissions = np.array(tokens[k + 1 : k + 1 + n_rem], dtype=np.float64)
                k += 1 + n_rem
                tail = np.array(tokens[k : k + 12], dtype=np.float64)
                if n <= 0 or ranges.shape[0] != n or tail.shape[0] != 12:
                    raise IndexError
                records.append(
                    (
                        ranges,
                        start,
                        inc,
                        maxr,
                        remissions if n_rem == n else None,
                        (tail[0], tail[1], tail[2]),
                        (tail[3], tail[4], tail[5]),
                        float(tail[11]),
                    )
                )
        except (IndexError, ValueError):
            raise ValueError(f"{log_path}:{number}: malformed {kind} line") from None
    if not records:
        raise ValueError(f"{log_path}: no FLASER or ROBOTLASER1 lines")

    flaser_max = rmax_user
    if flaser_max is None:
        flaser = [r[0] for r in records if r[3] is None]
        if flaser:
            flaser_max = float(max(float(np.nanmax(r)) for r in flaser))
    scans = []
    for scan_ranges, start, inc, own_max, inten, _, _, _ in records:
        rm_opt = own_max if own_max is not None else flaser_max
        if rm_opt is None or rm_opt <= rmin:
            raise ValueError(f"{log_path}: cannot determine a maximum range above range_min")
        scans.append(
            LaserScan(
                scan_ranges,
                angle_min=start,
                angle_increment=inc,
                range_min=rmin,
                range_max=rm_opt,
                intensities=inten,
            )
        )
    return CarmenLog(
        scans=tuple(scans),
        laser_poses=tuple(Pose2D(*r[5]) for r in records),
        robot_poses=tuple(Pose2D(*r[6]) for r in records),
        timestamps=np.array([r[7] for r in records], dtype=np.float64),
        odometry=np.array(odometry, dtype=np.float64).reshape(-1, 4),
    )
