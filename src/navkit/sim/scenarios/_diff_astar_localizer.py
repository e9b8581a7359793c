"""Map-based localisation for the diff-astar scenario: wheel odometry + LiDAR scan matching.

The delivery robot of the paper localised on its known map (ROS AMCL on a
LiDAR, wheel odometry between scans). navkit has no map localiser yet, so the
scenario brings a small one with the same structure: wheel odometry runs in an
``odom`` frame; at each LiDAR scan a Gauss-Newton scan-to-map match on a
likelihood field (the distance from each map point to the nearest obstacle)
refines the odometry-predicted pose, and the correction ``map <- odom`` is
updated so that the pose continues smoothly from there. The prediction enters
the match as a Gaussian prior, so directions a scan cannot see (along a
featureless corridor) stay where odometry puts them.
"""

from __future__ import annotations

import math

import numpy as np

from navkit._shared.types import FloatArray
from navkit.geometry import Pose2D, Twist2D, integrate
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid, distance_transform
from navkit.sim import EncoderReading, Lidar, Reading, ScanReading
from navkit.sim.scenarios._diff_astar_kernels import match_scan

__all__ = ["LikelihoodField", "ScanLocalizer"]


class LikelihoodField:
    """Signed distance (m) from the points of a map to the nearest obstacle surface.

    Positive in free space, negative inside obstacles (so a scan point that
    noise puts behind a wall pulls back as one in front of it pushes), sampled
    at the cell centres of ``grid``, interpolated bilinearly (exact wherever
    the distance is linear between centres, e.g. along a straight wall) and
    capped at ``±clip``. The field covers the grid's cells to their outer
    edges: between the edge cells' centres and the map's edge the edge cells'
    interpolation is extended (before review 50 points there were left out of
    a match, and a map one cell wide matched nothing); points beyond the edge
    are left out.

    Parameters
    ----------
    grid : OccupancyGrid
        The frame of the samples (origin, resolution, rotation).
    distances : ndarray (rows, cols)
        Signed distance to the nearest obstacle surface at each cell centre, m.
    clip : float, optional
        Cap of the distances, m: a point farther from every obstacle (a beam
        hitting something off the map) is left out of a match.

    Examples
    --------
    >>> grid = OccupancyGrid.empty(width=2.0, height=1.0, resolution=0.1)
    >>> field = LikelihoodField(grid, np.full(grid.shape, 2.0))
    >>> float(field.values.max())  # capped
    0.5
    """

    __slots__ = ("clip", "grid", "values")

    def __init__(self, grid: OccupancyGrid, distances: FloatArray, *, clip: float = 0.5) -> None:
        if distances.shape != grid.shape:
            raise ValueError(f"distances must have the grid's shape {grid.shape}")
        self.grid = grid
        self.clip = float(clip)
        self.values = np.ascontiguousarray(
            np.clip(distances, -self.clip, self.clip), dtype=np.float64
        )
        self.values.flags.writeable = False

    @classmethod
    def from_grid(cls, grid: OccupancyGrid, *, clip: float = 0.5) -> LikelihoodField:
        """The field of a map whose obstacles are its cells that are not free.

        Outside, a value is the distance from a cell centre to the nearest
        blocked cell's centre less half a cell (the distance to that cell's
        near face, which is what a beam hits in a ``World(grid=grid)``);
        inside, minus the distance to the nearest free cell's centre less half
        a cell.

        Parameters
        ----------
        grid : OccupancyGrid
            The map (occupied and unknown cells block, as in a World).
        clip : float, optional
            Cap of the distances, m.

        Returns
        -------
        LikelihoodField
            The field on the grid's cells.

        Examples
        --------
        >>> occupied = np.zeros((1, 5), dtype=bool)
        >>> occupied[0, 0] = True
        >>> grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
        >>> LikelihoodField.from_grid(grid).values.round(3).tolist()
        [[-0.05, 0.05, 0.15, 0.25, 0.35]]
        """
        blocked = ~grid.free()
        if not blocked.any():
            return cls(grid, np.full(grid.shape, float(clip)), clip=clip)
        half = 0.5 * grid.resolution
        # navkit's banded transform: SciPy's distances times the resolution bit for
        # bit, without SciPy's whole-grid work arrays (review 46).
        dist = distance_transform(blocked, resolution=grid.resolution)
        np.subtract(dist, half, out=dist)
        free = ~blocked
        if free.any():
            inside = distance_transform(free, resolution=grid.resolution)
            dist[blocked] = half - inside[blocked]
            # Gone before the field's clipped copy is made: 18 bytes a cell at the
            # peak, not 26 (SciPy's two transforms peaked at 50).
            del inside
        del free, blocked
        return cls(grid, dist, clip=clip)

    @classmethod
    def from_boxes(
        cls, grid: OccupancyGrid, boxes: FloatArray, *, clip: float = 0.5
    ) -> LikelihoodField:
        """The exact signed field of axis-aligned boxes at the cell centres of ``grid``.

        Outside every box a value is the distance to the nearest box; inside,
        minus the distance to the nearest face of the box holding the centre
        (the deepest one where boxes overlap).

        Parameters
        ----------
        grid : OccupancyGrid
            Where to sample (its cell centres).
        boxes : ndarray (n, 4)
            Obstacles ``(xmin, ymin, xmax, ymax)``, m.
        clip : float, optional
            Cap of the distances, m.

        Returns
        -------
        LikelihoodField
            The field on the grid's cells.

        Examples
        --------
        >>> grid = OccupancyGrid.empty(width=2.0, height=1.0, resolution=0.1)
        >>> field = LikelihoodField.from_boxes(grid, np.array([[1.5, 0.0, 2.0, 1.0]]))
        >>> field.values[5, [10, 16]].round(3).tolist()  # x = 1.05 and 1.65 m
        [0.45, -0.15]
        """
        rows, cols = grid.shape
        rr, cc = np.meshgrid(np.arange(rows), np.arange(cols), indexing="ij")
        centres = grid.cell_to_world(np.column_stack((rr.ravel(), cc.ravel())))
        px, py = centres[:, 0], centres[:, 1]
        outside = np.full(px.shape, np.inf)
        depth = np.zeros(px.shape)
        for x0, y0, x1, y1 in np.asarray(boxes, dtype=np.float64).reshape(-1, 4):
            dx = np.maximum(np.maximum(x0 - px, px - x1), 0.0)
            dy = np.maximum(np.maximum(y0 - py, py - y1), 0.0)
            np.minimum(outside, np.hypot(dx, dy), out=outside)
            inner = np.minimum(np.minimum(px - x0, x1 - px), np.minimum(py - y0, y1 - py))
            np.maximum(depth, inner, out=depth)
        dist = np.where(depth > 0.0, -depth, outside)
        return cls(grid, dist.reshape(rows, cols), clip=clip)


class ScanLocalizer:
    """Wheel odometry corrected by scan-to-map matching: a simulation estimator.

    Follows :class:`navkit.sim.Estimator`: ``observe(t, reading)`` takes the
    simulation's encoder and scan readings; :attr:`pose` is the map pose. A
    scan is matched once the encoders have caught up with its time stamp
    (odometry and scan then describe the same instant). Each beam's range
    variance is ``floor^2 + (sigma × range + absolute)^2``, its band's standard
    deviation from the LiDAR's :class:`~navkit.sim.RangeNoise` (the absolute
    term since review 49) widened by ``floor``.

    Parameters
    ----------
    field : LikelihoodField
        The map's distance field.
    drive : DiffDrive
        The nominal drive (the odometry's wheel radii and track).
    lidar : Lidar
        The scanner: its ``mount`` (pose in the robot frame) places the beams'
        end points on the robot (``scan.to_points(lidar.mount)``), so the match
        solves for the robot's pose wherever the scanner sits; its noise sets
        the beam weights.
    ticks_per_rev : float
        Encoder resolution.
    bits : int or None
        Encoder counter width.
    start : Pose2D
        The initial map pose.
    floor : float, optional
        Smallest standard deviation of a beam's fit to the map, m.
    prior_sigma_xy, prior_sigma_theta : float, optional
        Standard deviations of the odometry prediction in a match, m and rad.
    beam_step : int, optional
        Every ``beam_step``-th valid beam is matched.
    iterations : int, optional
        Most Gauss-Newton steps per scan.

    Examples
    --------
    >>> grid = OccupancyGrid.from_occupancy(np.zeros((10, 10), dtype=bool), resolution=0.1)
    >>> drive = DiffDrive(track=0.3, wheel_radius=0.05)
    >>> loc = ScanLocalizer(LikelihoodField.from_grid(grid), drive,
    ...                     Lidar(), ticks_per_rev=1024, bits=16,
    ...                     start=Pose2D(0.5, 0.5, 0.0))
    >>> loc.observe(0.0, EncoderReading(0.0, np.array([0, 0])))
    >>> loc.observe(0.1, EncoderReading(0.1, np.array([1024, 1024])))  # one wheel turn
    >>> round(loc.pose.x, 4)
    0.8142
    """

    __slots__ = (
        "_bands",
        "_correction",
        "_field",
        "_floor2",
        "_forward",
        "_frame",
        "_iterations",
        "_last_ticks",
        "_mount",
        "_odom",
        "_out",
        "_pending",
        "_prior_th",
        "_prior_xy",
        "_rad_per_tick",
        "_span",
        "_step",
        "matches",
    )

    def __init__(
        self,
        field: LikelihoodField,
        drive: DiffDrive,
        lidar: Lidar,
        *,
        ticks_per_rev: float,
        bits: int | None,
        start: Pose2D,
        floor: float = 0.01,
        prior_sigma_xy: float = 0.05,
        prior_sigma_theta: float = 0.05,
        beam_step: int = 2,
        iterations: int = 8,
    ) -> None:
        self._field = field
        origin = field.grid.origin
        self._frame = (
            origin.x, origin.y, math.cos(origin.theta), math.sin(origin.theta),
            field.grid.resolution,
        )  # fmt: skip
        # (ds, dtheta) per radian of each wheel: rows of the forward kinematics.
        fwd = drive.forward_batch(np.eye(2))
        self._forward = (float(fwd[0, 0]), float(fwd[1, 0]), float(fwd[0, 2]), float(fwd[1, 2]))
        self._rad_per_tick = 2.0 * math.pi / float(ticks_per_rev)
        self._span = None if bits is None or bits >= 64 else 1 << bits
        self._last_ticks: tuple[int, int] | None = None
        self._odom = start
        self._correction = Pose2D(0.0, 0.0, 0.0)  # map <- odom
        self._pending: ScanReading | None = None
        mount = lidar.mount
        # None for a scanner at the centre facing forward: its sensor-frame points
        # are the robot's as they are (the scenario's; not recomputed, bit for bit).
        self._mount = None if mount.x == 0.0 and mount.y == 0.0 and mount.theta == 0.0 else mount
        noise = lidar.noise
        if noise is None:
            self._bands: tuple[FloatArray, FloatArray, FloatArray] | None = None
        else:
            self._bands = (np.array(noise.limits), np.array(noise.sigma), np.array(noise.absolute))
        self._floor2 = floor**2
        self._prior_xy = 1.0 / prior_sigma_xy**2
        self._prior_th = 1.0 / prior_sigma_theta**2
        self._step = int(beam_step)
        self._iterations = int(iterations)
        self._out = np.zeros(3)
        #: Number of scans matched so far.
        self.matches = 0

    @property
    def pose(self) -> Pose2D:
        """The current map pose: the correction applied to the odometry."""
        return self._correction.compose(self._odom)

    def observe(self, t: float, reading: Reading) -> None:
        """Take one delivered reading (encoders and scans; others are ignored).

        Parameters
        ----------
        t : float
            Delivery time, s.
        reading : Reading
            The reading.
        """
        if isinstance(reading, EncoderReading):
            self._odometry(int(reading.ticks[0]), int(reading.ticks[1]))
            pending = self._pending
            if pending is not None and pending.stamp <= reading.stamp + 1e-9:
                self._pending = None
                self._match(pending)
        elif isinstance(reading, ScanReading):
            self._pending = reading

    def _odometry(self, left: int, right: int) -> None:
        last = self._last_ticks
        self._last_ticks = (left, right)
        if last is None:
            return
        dl = left - last[0]
        dr = right - last[1]
        span = self._span
        if span is not None:
            half = span >> 1
            dl = (dl + half) % span - half
            dr = (dr + half) % span - half
        al = dl * self._rad_per_tick
        ar = dr * self._rad_per_tick
        sl, sr, tl, tr = self._forward
        self._odom = integrate(self._odom, Twist2D(sl * al + sr * ar, 0.0, tl * al + tr * ar), 1.0)

    def _match(self, reading: ScanReading) -> None:
        scan = reading.scan
        valid = scan.valid_mask()
        ranges = scan.ranges[valid][:: self._step]
        if ranges.shape[0] < 3:
            return
        pts = scan.to_points(self._mount)[:: self._step]
        if self._bands is None:
            variance = np.full(ranges.shape[0], self._floor2)
        else:
            limits, sigma, absolute = self._bands
            band = np.minimum(np.searchsorted(limits, ranges, side="right"), sigma.size - 1)
            # The band's standard deviation, RangeNoise's: relative plus absolute (review
            # 49; + 0.0 keeps a relative-only model's weights to the bit).
            variance = self._floor2 + (sigma[band] * ranges + absolute[band]) ** 2
        prior = self.pose
        ox, oy, co, so, res = self._frame
        match_scan(
            np.ascontiguousarray(pts[:, 0]), np.ascontiguousarray(pts[:, 1]), variance,
            self._field.values, ox, oy, co, so, res, self._field.clip,
            prior.x, prior.y, prior.theta, self._prior_xy, self._prior_th,
            self._iterations, self._out,
        )  # fmt: skip
        matched = Pose2D(float(self._out[0]), float(self._out[1]), float(self._out[2]))
        self._correction = matched.compose(self._odom.inverse())
        self.matches += 1
