"""A real-time 2-D mapper: scan-to-map matching and log-odds updates on a map pyramid."""

from __future__ import annotations

import copy
import math
from typing import Any, cast

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.counts import counted
from navkit._shared.deprecation import renamed_keyword
from navkit._shared.frozen import restore_slots
from navkit._shared.locks import one_caller
from navkit._shared.types import FloatArray
from navkit._shared.validation import finite_float, scan_reading_hint
from navkit.geometry import Pose2D, as_pose
from navkit.mapping._grid import OccupancyGrid, grid_origin
from navkit.mapping._limits import (
    COORDINATE_LIMIT,
    MAX_CELLS,
    RESOLUTION_MAX,
    bounded_float,
    check_cell_count,
)
from navkit.mapping._logodds import logit
from navkit.mapping._raycast import _clamp_pair, _sensor_model
from navkit.mapping._raycast_kernels import integrate_beams
from navkit.mapping._scan import LaserScan
from navkit.mapping._scan_matcher import ScanMatcher, ScanMatchResult, scan_points

__all__ = ["ScanMapper"]

_IDENTITY = Pose2D(0.0, 0.0, 0.0)
# Hector's update_factor_occupied / update_factor_free (probabilities) as log-odds.
_HIT = logit(0.9)
_MISS = logit(0.4)
# Growth margin around what a scan reaches, m, and the initial half-size.
_MARGIN = 10.0
# The log-odds a grown level is first built with (see _ensure_covers).
_ONE_CELL = np.zeros((1, 1), dtype=np.float32)
# Whether the ray casting kernel has been called in this process (see _write).
_KERNEL_CALLED = [False]


class ScanMapper:
    """Build a map from laser scans in order: match each to the map, then write it in.

    Hector mapping's loop (Kohlbrecher et al., SSRR 2011) on a pyramid of
    log-odds :class:`OccupancyGrid` levels (the finest at ``resolution``,
    each next one at twice the cell size, as many as the matcher's
    ``levels``). For every scan, :meth:`update`:

    1. guesses the sensor pose: the previous pose moved by the odometry
       increment since the previous scan when ``odometry`` is given, otherwise
       by the previous scan-to-scan motion (constant velocity; no motion for the
       second scan). That guess needs closely spaced scans: on logs that keep a
       scan only every metre or so, with sharp turns between them (the CARMEN
       logs), the match starts too far off and mapping without odometry fails;
    2. matches the scan to the map from that guess (:meth:`ScanMatcher.match`;
       when the match cannot be made, e.g. a featureless corridor, the guess is
       kept, or with the default matcher's pull towards the guess the pose
       that pull fixes: see :class:`ScanMatchResult`);
    3. writes the scan into **every** level (ray casting as
       :func:`navkit.mapping.integrate_scan`, log-odds ``hit`` added to end
       cells and ``miss`` to crossed cells, each cell updated once per scan,
       clamped to ``clamp``) when the pose has moved more than
       ``min_distance`` or turned more than ``min_angle`` since the last
       write (the first scan with a return to write is always written).
       Returns with no echo (``>= scan.range_max``) and from ``range_max`` on are
       not written, as in Hector.

    The map starts about ±10 m around the first pose (less where that would
    exceed :attr:`OccupancyGrid.MAX_CELLS` cells, below about 1.2 mm cells) and
    grows (by whole coarse cells, keeping every level aligned) when a scan
    would reach beyond it, up to :attr:`OccupancyGrid.MAX_CELLS` cells. An axis
    that grows at least doubles, on the side or sides the scan leaves by
    (near the cell limit by a half, a quarter or an eighth, then by what the
    scan needs plus 10 m), so a route that keeps leaving the map copies it a
    logarithmic number of times: along a 1 km corridor at 5 cm, 6 growths
    instead of 96 (0.2 s of copying instead of 0.5 s; 5 km: 8 instead of
    477, 1.3 s instead of 6.8 s), at the price of up to twice the cells the
    route needs along that axis (1 km: 51 MiB of levels instead of 41).
    Growing changes no cell: each keeps its value and world position.

    Memory: the levels take 4 bytes a cell of the finest level and a third
    more for the coarser ones, and the trajectory 24 bytes a scan (float64
    ``x, y, theta``) for as long as the mapper lives, in an array that grows
    by half when full (up to a third of it spare): 100,000 scans, under three
    hours of a 10 Hz LiDAR, hold 2.8 MB (29 bytes a scan measured with
    :mod:`tracemalloc`, 48 at the peak of a growth; a list of poses took 137),
    three days at 40 Hz (10.4 million scans) 250 to 375 MB.
    :attr:`trajectory` copies the filled rows on every read (0.1 ms for
    100,000 scans, against 70 ms to gather the former list of poses);
    :attr:`pose` reads only the latest.

    Long runs of a robot standing still (one scan over and over, zero
    odometry) write nothing after the first scan and do not drift, but with
    the default matcher the pose need not settle: a match goes coarse to
    fine from its guess (the last pose), and may end where the finest
    level's cost plus the pull towards the guess is higher than at the guess
    itself (359 of 600 such matches, by 0.7 % at the median), so the poses
    cycle within a few millimetres (in a 6 m room of 180 beams at 5 cm
    cells: 13 poses 2.4 mm apart from the constant-velocity guess, 5 poses
    5.4 mm apart with odometry, the same band after 5,000 scans as after
    600). With ``ScanMatcher()`` (no pull) the pose stays put, to the bit with
    odometry.

    The odometry only guesses each pose; the match decides it, pulled
    towards the guess by the matcher's weights. So with the default pull
    (1/m, 1/rad) the mapper drifts as an incremental matcher does, whatever
    the odometry's quality: given the Radish aces log's corrected poses as
    odometry its poses lie 0.75 m from them on the mean and 2.47 m at worst
    (0.8 % of the distance and 0.06°/m over 10 m of travel), and as far
    given odometry off by 5 cm and 2° a step. Its keyframes, 1 m and 12°
    apart, each disagree with the corrected poses by 3 cm and 0.3° on the
    mean (the corrected poses are not the scans' ground truth to that
    precision), and nothing closes the loop. Good odometry wants a stronger
    pull: ``ScanMatcher(translation_weight=30, rotation_weight=30,
    search_distance=0.1, search_angle=0.1)`` keeps that run within 0.05 m
    mean and 0.18 m of the corrected poses, but follows odometry off by 5 cm
    and 2° a step as far as it drifts. A scanner looking forward (180°) is
    also matched about 0.1 cell forward of its pose, Hector's model's bias
    (unknown cells behind the walls, free in front); in the mapper it mostly
    cancels. Measurements and causes: the mapping guide's "How closely the
    mapper keeps to good odometry".

    A mapper keeps its map and trajectory between calls, so it is not
    thread-safe: one thread at a time may call :meth:`update`; different
    mappers may run in different threads at once, also with one shared
    :class:`ScanMatcher` (which keeps only its options). An update called
    while another is under way (another thread's, or a signal handler's
    interrupting one in the same thread) raises ``RuntimeError`` and changes
    nothing; the update under way goes on as alone (before, the two matched
    from one guess and recorded each other's poses: wrong poses and a map
    written at them, without an error). Copies and pickles of a mapper in
    use are not in use. While one thread updates, others may read
    :attr:`map`: each level is written holding its grid's lock, which
    :meth:`OccupancyGrid.copy` holds too, so the copy holds a whole number
    of scans (the ray casting releases the GIL: without the lock a copy
    could hold part of a scan).

    The name says what it does — mapping from scans by scan matching — rather
    than naming one implementation; the defaults are Hector's.

    Parameters
    ----------
    resolution : float, default 0.05
        Cell size of the finest level, m, in [1e-3, 1e6].
    hit, miss : float, default logit(0.9), logit(0.4)
        Log-odds increments of end cells and crossed cells, as
        :func:`~navkit.mapping.integrate_scan`'s (the defaults are Hector's
        ``update_factor_occupied`` 0.9 and ``update_factor_free`` 0.4 as
        log-odds, about 2.197 and -0.405): ``hit`` in [0, 1e6], ``miss`` in
        [-1e6, 0].
    clamp : (float, float), default (-50.0, 50.0)
        Bounds of the stored log-odds (Hector stops raising a cell at 50).
        They bound how long the map remembers: a cell hit by any number of
        scans is free again after at most 127 written scans that cross it
        (``ceil((50 - logit(0.196)) / 0.405)`` with the default ``miss`` and
        the grid's free threshold), and a free cell occupied again after 24
        hits. Scans are written only after ``min_distance`` or ``min_angle``
        of motion, so a standing robot changes nothing; a narrower ``clamp``
        (OctoMap's ``(logit(0.12), logit(0.97))``: 13 misses) forgets faster.
    min_distance : float, default 0.4
        Translation, m, since the last write that triggers a write (>= 0).
    min_angle : float, default 0.9
        Rotation, rad, since the last write that triggers a write, in [0, π].
    range_max : float, optional
        Returns at least this long (m) are neither matched nor written; default
        the matcher's ``range_max`` (all valid returns).
    pose : Pose2D or array_like [x, y, theta], default (0, 0, 0)
        World pose given to the first scan (the start pose, as the odometries
        and :class:`~navkit.estimation.PlanarFusion` take it), x and y within
        ±1e9 m (the range of grid origins: the map extends no further below
        -1e9 m).
    matcher : ScanMatcher, optional
        The matcher and its options. Default ``ScanMatcher(translation_weight=1.0,
        rotation_weight=1.0, search_distance=0.1, search_angle=0.1)``: three
        levels; a pull towards the guess (the odometry or constant-velocity
        prediction) that keeps weakly constrained directions — a corridor's
        axis, a scan mostly into unexplored space — near the prediction (on
        the CARMEN logs it lowers the pair error by a fifth against Hector's
        pure objective, weights 0); and a correlative pre-search of ±1 coarse
        cell and ±0.1 rad around the guess, which puts Gauss–Newton in the
        right basin when the guess is a few degrees off (odometry noise of
        about 5 cm and 2° per step; give a wider window for worse odometry).
        At most 14 levels: the smallest map, 2 × 2 cells of the coarsest
        level, must fit in :attr:`OccupancyGrid.MAX_CELLS` cells of the finest.

    Other Parameters
    ----------------
    max_range : float, optional
        Deprecated name of `range_max`.
    occupied : float, optional
        Deprecated: the probability ``p`` in (0.5, 1) of ``hit=logit(p)``.
    free : float, optional
        Deprecated: the probability ``p`` in (0, 0.5) of ``miss=logit(p)``.
    min_rotation : float, optional
        Deprecated name of `min_angle`.
    start : Pose2D or array_like [x, y, theta], optional
        Deprecated name of `pose`.

    Raises
    ------
    TypeError
        An option of the wrong type (a ``matcher`` that is not a
        :class:`ScanMatcher` included); a new name given with its deprecated one.
    ValueError
        An option outside its range, NaN or inf; a ``clamp`` that is not a
        ``(low, high)`` pair with ``low < high``; a matcher with more levels
        than :attr:`OccupancyGrid.MAX_CELLS` allows.

    Examples
    --------
    >>> import math
    >>> mapper = ScanMapper(resolution=0.1)
    >>> ranges = [2.0 / max(abs(math.cos(a)), abs(math.sin(a)))
    ...           for a in np.linspace(-math.pi, math.pi, 90, endpoint=False)]
    >>> scan = LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / 90,
    ...                  range_min=0.1, range_max=10.0)
    >>> mapper.update(scan).reason         # the first scan has nothing to match
    'degenerate'
    >>> result = mapper.update(scan, odometry=(0.05, -0.04, 0.03))
    >>> result.converged, bool(np.abs(mapper.pose.as_array()).max() < 0.05)  # half a cell
    (True, True)
    >>> mapper.map.resolution, len(mapper)
    (0.1, 2)
    """

    __slots__ = (
        "__weakref__",  # weakref.ref(obj) for callbacks and caches (review 36)
        "_callers",
        "_clamp",
        "_free",
        "_last_odometry",
        "_last_write",
        "_levels",
        "_matcher",
        "_max_range",
        "_min_distance",
        "_min_rotation",
        "_occupied",
        "_path",
        "_path_len",
        "_pose",
        "_resolution",
        "_start",
    )

    def __init__(
        self,
        *,
        resolution: float = 0.05,
        hit: float = _HIT,
        miss: float = _MISS,
        clamp: tuple[float, float] = (-50.0, 50.0),
        min_distance: float = 0.4,
        min_angle: float = 0.9,
        range_max: float | None = None,
        pose: Pose2D | ArrayLike = _IDENTITY,
        matcher: ScanMatcher | None = None,
        max_range: float | None = None,
        occupied: float | None = None,
        free: float | None = None,
        min_rotation: float | None = None,
        start: Pose2D | ArrayLike | None = None,
    ) -> None:
        # The updates under way (one at most: see one_caller; not copied or pickled).
        self._callers: list[tuple[int, str, object]] = []
        named = "range_max" if max_range is None else "max_range"  # as the caller wrote it
        range_max = renamed_keyword("max_range", max_range, "range_max", range_max, None)
        # The mapper's own lower bound (its pyramid's cells), stated in the one message:
        # a grid's 1e-6 would be named for 1e-7 and then refused for 1e-6.
        self._resolution = bounded_float(resolution, "resolution", 1e-3, RESOLUTION_MAX, "m")
        # integrate_scan's sensor model (log-odds hit/miss); the old probabilities
        # are checked as before and converted, so they give the same increments.
        # The slots keep their old names, so that pickled mappers still load.
        old_hit = None if occupied is None else logit(_probability(occupied, "occupied", 0.5, 1.0))
        old_miss = None if free is None else logit(_probability(free, "free", 0.0, 0.5))
        # The warnings give the log-odds to write: hit=0.7 for occupied=0.7 is silently
        # another sensor model, and miss=0.4 for free=0.4 an error.
        hit = renamed_keyword("occupied", old_hit, "hit", hit, _HIT, use=_log_odds("hit", old_hit))
        miss = renamed_keyword(
            "free", old_miss, "miss", miss, _MISS, use=_log_odds("miss", old_miss)
        )
        self._occupied, self._free = _sensor_model(hit, miss)
        self._clamp = _clamp_pair(clamp)
        self._min_distance = bounded_float(min_distance, "min_distance", 0.0, math.inf, "m")
        angle_name = "min_angle" if min_rotation is None else "min_rotation"
        min_angle = renamed_keyword("min_rotation", min_rotation, "min_angle", min_angle, 0.9)
        self._min_rotation = bounded_float(min_angle, angle_name, 0.0, math.pi, "rad")
        if matcher is None:
            matcher = ScanMatcher(
                translation_weight=1.0, rotation_weight=1.0, search_distance=0.1, search_angle=0.1
            )
        elif not isinstance(matcher, ScanMatcher):
            raise TypeError(f"matcher must be a ScanMatcher, got {type(matcher).__name__}")
        self._matcher = matcher
        self._max_range = (
            matcher.range_max
            if range_max is None
            else bounded_float(range_max, named, 0.0, 1e9, "m", low_open=True)
        )
        if self._resolution * 2 ** (matcher.levels - 1) > RESOLUTION_MAX:
            raise ValueError("resolution * 2**(levels - 1) must be <= 1e6 m")
        # The smallest map the mapper builds is 2 x 2 cells of the coarsest level:
        # (2 * 2**(levels - 1))**2 cells of the finest, within MAX_CELLS up to 14 levels.
        side = 2 * 2 ** (matcher.levels - 1)
        check_cell_count(
            float(side * side),
            f"a map of matcher.levels={matcher.levels} (2 x 2 cells on its coarsest level)",
        )
        # Within ±1e9 m, as every grid origin: the map is built around it.
        pose_name = "pose" if start is None else "start"  # as the caller wrote it
        pose = renamed_keyword("start", start, "pose", pose, _IDENTITY)
        self._start = grid_origin(pose, pose_name)
        self._levels: list[OccupancyGrid] = []
        # The trajectory: rows [x, y, theta] of the first _path_len scans, in an
        # array with spare rows (24 bytes a scan; a list of Pose2D took 140).
        self._path: FloatArray = np.empty((0, 3), dtype=np.float64)
        self._path_len = 0
        # The last row as the matcher's Pose2D: reading pose after every update
        # builds none (a Pose2D takes 2.5 us to check and wrap its fields).
        self._pose = self._start
        self._last_odometry: Pose2D | None = None
        self._last_write: Pose2D | None = None

    def __len__(self) -> int:
        """Number of scans processed."""
        return self._path_len

    def __bool__(self) -> bool:
        """Always True: a mapper is an object, not a collection of scans.

        Without it Python takes ``len(mapper)``, so a fresh mapper was false:
        ``if self.mapper:`` (an optional mapper) never fed it its first scan.
        """
        return True

    def __repr__(self) -> str:
        # The scans taken are no argument: <...> as the library's other reprs show state.
        scans = counted(len(self), "scan")
        return f"{type(self).__name__}(<{scans}>, resolution={self._resolution})"

    def __copy__(self) -> ScanMapper:
        # update() writes into the map levels and appends to the trajectory in
        # place: a shallow copy sharing them would write its scans into this
        # mapper (and leave its odometry and last write stale), so copy.copy
        # copies them too, as OccupancyGrid's does.
        return copy.deepcopy(self)

    def __getstate__(self) -> tuple[dict[str, Any] | None, dict[str, Any]]:
        # Python's default state (a subclass's __dict__ and slots included), with
        # the filled rows of the trajectory only: copies and pickles leave the
        # spare rows out.
        # A slotted object's default state is the pair (__dict__ or None, slots).
        instance, slots = cast(
            "tuple[dict[str, Any] | None, dict[str, Any]]", object.__getstate__(self)
        )
        slots["_path"] = self._path[: self._path_len]
        # Not in use, whatever the original is doing (pickles as before the guard).
        slots.pop("_callers", None)
        return instance, slots

    def __setstate__(self, state: Any) -> None:
        instance, slots = state if isinstance(state, tuple) else (None, state)
        slots = dict(slots)
        # Pickles made before the trajectory became an array hold a list of Pose2D.
        poses = slots.pop("_poses", None)
        if poses is not None:
            rows = [(p.x, p.y, p.theta) for p in poses]
            slots["_path"] = np.array(rows, dtype=np.float64).reshape(len(rows), 3)
            slots["_path_len"] = len(rows)
            slots["_pose"] = poses[-1] if poses else slots["_start"]
        # The state's array holds no spare row: the next update appends to a new
        # one, never writing into what pickle or deepcopy handed over.
        slots["_callers"] = []
        restore_slots(self, (instance, slots))

    # ------------------------------------------------------------------ views
    @property
    def trajectory(self) -> FloatArray:
        """World poses ``[x, y, theta]`` of the sensor at every scan, (n, 3), a read-only copy."""
        out = self._path[: self._path_len].copy()
        out.flags.writeable = False
        return out

    @property
    def pose(self) -> Pose2D:
        """The sensor's latest world pose (the start ``pose`` before the first scan).

        The last row of :attr:`trajectory`, without copying the whole
        trajectory: read it after every :meth:`update`, as the ``pose`` of the
        odometry classes and of :class:`~navkit.estimation.PlanarFusion`.

        Examples
        --------
        >>> ScanMapper(pose=(1.0, 2.0, 0.5)).pose
        Pose2D(x=1.0, y=2.0, theta=0.5)
        """
        return self._pose

    @property
    def map(self) -> OccupancyGrid:
        """A copy of the finest map level (before any scan: an empty 1 m square at the start pose).

        Save it with ``mapper.map.save(path)`` (:func:`navkit.mapping.io.write_map`).
        """
        if not self._levels:
            half = 0.5
            return OccupancyGrid.empty(
                width=2 * half,
                height=2 * half,
                resolution=min(self._resolution, half),
                origin=(
                    max(self._start.x - half, -COORDINATE_LIMIT),
                    max(self._start.y - half, -COORDINATE_LIMIT),
                    0.0,
                ),
            )
        return self._levels[0].copy()

    # ----------------------------------------------------------------- update
    @one_caller
    def update(
        self, scan: LaserScan, odometry: Pose2D | ArrayLike | None = None
    ) -> ScanMatchResult:
        """Match ``scan`` to the map, record its pose and write it in when moved far enough.

        Parameters
        ----------
        scan : LaserScan
            The next scan, in time order. Scans may differ in beam count,
            angles and range limits (each is read with its own). Only valid
            returns (:meth:`LaserScan.valid_mask`) are matched and written:
            REP 117 readings (NaN, ``±inf``), readings below ``range_min``
            and "no echo" at or beyond ``range_max`` are skipped, clearing no
            free space, as in Hector; a scan with none keeps the guess.
        odometry : Pose2D or array_like [x, y, theta], optional
            Odometry pose of the **sensor** at this scan, in any fixed frame
            (compose a mounting offset yourself: ``robot_odometry @ mount``
            with ``mount`` a ``Pose2D``; ``robot_odometry`` may be a pose or
            an ``[x, y, theta]`` array row, such as a ``BagOdometry.poses`` row).
            Only increments between consecutive scans are used. Without it, or
            when the previous scan came without it, the previous scan-to-scan
            motion is repeated.

        Returns
        -------
        ScanMatchResult
            The match (for the first scan: the start ``pose``, reason
            ``"degenerate"`` as an empty map constrains nothing).

        Raises
        ------
        TypeError
            ``scan`` is not a LaserScan, ``odometry`` not real numbers.
        ValueError
            ``odometry`` not finite, or the pose predicted for this scan
            (from the odometry increment, or the previous motion repeated)
            beyond ±1.8e308 m, the float range; the mapper is unchanged.
        RuntimeError
            Another update of this mapper is under way (another thread's, or a
            signal handler's in the same thread): one call at a time, see the
            class notes; the mapper is unchanged.
        KeyboardInterrupt
            Or any other exception from outside the mapper raised part-way (a
            signal handler's): the mapper has then not taken the scan, or has
            recorded its pose (:attr:`trajectory`, :attr:`pose`, with its
            odometry) and written it into every map level or none; never into
            some levels only. The next update continues from that state.

        Examples
        --------
        >>> mapper = ScanMapper()
        >>> scan = LaserScan([1.0, 1.0, 1.0], angle_min=-1.0, angle_increment=1.0,
        ...                  range_min=0.1, range_max=5.0)
        >>> mapper.update(scan).pose
        Pose2D(x=0.0, y=0.0, theta=0.0)
        """
        if not isinstance(scan, LaserScan):
            raise TypeError(
                f"scan must be a LaserScan, got {type(scan).__name__}" + scan_reading_hint(scan)
            )
        odom = None if odometry is None else as_pose(odometry, "odometry")
        points = scan_points(scan, self._max_range)
        try:
            guess = self._guess(odom)
        except ValueError as err:  # Pose2D names its own arguments (other, frame) in it
            source = (
                "odometry: the increment since the previous scan's odometry, or the pose it "
                "predicts,"
                if odom is not None and self._last_odometry is not None
                else "the pose predicted by repeating the previous scan-to-scan motion"
            )
            raise ValueError(f"{source} lies beyond ±1.8e308 m (the float range)") from err
        if not self._levels:
            self._create_levels(guess)
        self._ensure_covers(guess, points)
        result = self._matcher._match(tuple(self._levels), points, guess)
        pose = result.pose
        self._reserve_row()
        # The pose and the odometry are recorded together, by plain stores: Python
        # delivers a KeyboardInterrupt only at calls, so an interrupted update has
        # recorded both or neither. A scan without odometry breaks the chain: the
        # next odometry increment would span two scans, on top of this scan's
        # constant-velocity guess.
        n = self._path_len
        self._path[n] = (pose.x, pose.y, pose.theta)
        self._path_len = n + 1
        self._pose = pose
        self._last_odometry = odom
        # A scan with nothing to write (no valid return within range_max) does not
        # count as written: the next scan would then wait for min_distance.
        if points.shape[0] and self._should_write(pose):
            self._write(scan, pose)
        return result

    def _reserve_row(self) -> None:
        """Make room in the trajectory array for one more row."""
        n = self._path_len
        if n == self._path.shape[0]:
            # Half as many rows again: amortised O(1) appends, at most a third
            # of the rows spare (a doubling would leave up to half).
            grown = np.empty((max(16, n + n // 2), 3), dtype=np.float64)
            grown[:n] = self._path[:n]
            self._path = grown

    def _guess(self, odom: Pose2D | None) -> Pose2D:
        n = self._path_len
        if not n:
            return self._start
        last = self._pose
        if odom is not None and self._last_odometry is not None:
            return last.compose(odom.relative_to(self._last_odometry))
        if n >= 2:
            # The row holds the matcher's pose bit for bit, theta already wrapped.
            x, y, theta = self._path[n - 2].tolist()
            return last.compose(last.relative_to(Pose2D(x, y, theta)))
        return last

    def _should_write(self, pose: Pose2D) -> bool:
        last = self._last_write
        if last is None:
            return True
        moved = math.hypot(pose.x - last.x, pose.y - last.y)
        turned = abs(math.remainder(pose.theta - last.theta, 2 * math.pi))
        return moved > self._min_distance or turned > self._min_rotation

    def _write(self, scan: LaserScan, pose: Pose2D) -> None:
        ranges = np.array(scan.ranges, dtype=np.float64, copy=True)
        with np.errstate(invalid="ignore"):
            drop = ~scan.valid_mask()
            if self._max_range is not None:
                drop |= ranges >= self._max_range
        ranges[drop] = np.nan  # no echo: neither a hit nor free space (Hector)
        ranges.flags.writeable = False  # as integrate_scan's: one kernel specialisation
        lo, hi = self._clamp
        # The ray casting's scratch buffer, sized for the finest (largest) level.
        scratch = np.empty(self._levels[0]._logodds.size, dtype=np.uint8)
        # The scan goes into every level: an exception part-way (a KeyboardInterrupt,
        # which Python delivers as a level's kernel call returns, most likely after the
        # finest level's) is raised once all are written, never leaving the coarse
        # levels, which steer the matching on the finer ones, without a scan the finer
        # ones hold. So the try holds the kernel call alone (Python delivers it at a
        # call's return, or on entering a Python function, such as a property: a level
        # whose arguments were being read would be skipped), its arguments read before.
        # Each level is written holding its grid's writer lock, which OccupancyGrid.copy
        # holds too: `map` read by another thread meanwhile (the kernel releases the
        # GIL) is the finest level after a whole number of scans, not half of one.
        px, py, pth = pose.x, pose.y, pose.theta
        a0, da = scan.angle_min, scan.angle_increment
        rmin, rmax = scan.range_min, scan.range_max
        hit, miss = self._occupied, self._free
        frames = [
            (grid._logodds, grid.origin, grid.resolution, grid._writer_lock())
            for grid in self._levels
        ]
        if not _KERNEL_CALLED[0]:
            # A kernel's first call in a process runs Python before the kernel does
            # (numba loads or compiles it, for a second or more): an interrupt there
            # raised before the first level was written, and the coarser levels were
            # written after it. So that first call is made here, before any level, with
            # the levels' argument types (a one-cell grid, no beams): an interrupt in it
            # leaves every level unwritten.
            integrate_beams(
                np.zeros((1, 1), dtype=np.float32), 0.0, 0.0, 0.0, 1.0, px, py, pth,
                ranges[:0], a0, da, rmin, rmax, hit, miss, lo, hi, False, scratch,
            )  # fmt: skip
            _KERNEL_CALLED[0] = True
        pending: BaseException | None = None
        for logodds, o, res, lock in frames:
            ox, oy, oth = o.x, o.y, o.theta
            started = False
            # Waiting for the lock (another thread copying the map) may be interrupted:
            # then the kernel has not run, and the level is tried again.
            while not started:
                try:
                    with lock:
                        started = True
                        integrate_beams(
                            logodds, ox, oy, oth, res, px, py, pth, ranges, a0, da, rmin,
                            rmax, hit, miss, lo, hi, False, scratch,
                        )  # fmt: skip
                except BaseException as exc:  # a try costs nothing in Python 3.11+
                    if pending is None:
                        pending = exc
        self._last_write = pose
        if pending is not None:
            raise pending

    # ----------------------------------------------------------------- growth
    def _coarsest(self) -> float:
        return self._resolution * float(2 ** (self._matcher.levels - 1))

    def _create_levels(self, centre: Pose2D) -> None:
        step = self._coarsest()
        # ±_MARGIN around the start, in whole coarse cells; fewer at the finest
        # resolutions, so that the finest level (2 n 2**(levels - 1) cells a side)
        # keeps within MAX_CELLS (the constructor checked that n = 1 does).
        scale = 2 ** (self._matcher.levels - 1)
        n_max = math.isqrt(MAX_CELLS) // (2 * scale)
        n = max(1, min(math.ceil(_MARGIN / step), n_max))
        # A grid's origin lies within ±1e9 m: near -1e9 the map starts there.
        x0 = max(centre.x - n * step, -COORDINATE_LIMIT)
        y0 = max(centre.y - n * step, -COORDINATE_LIMIT)
        self._levels = [
            OccupancyGrid(
                np.zeros((2 * n * 2**k, 2 * n * 2**k), dtype=np.float32),
                resolution=step / 2**k,
                origin=(x0, y0, 0.0),
            )
            for k in range(self._matcher.levels - 1, -1, -1)
        ]

    def _ensure_covers(self, pose: Pose2D, points: FloatArray) -> None:
        """Grow every level so that the sensor and its returns (with a margin) are inside."""
        if points.shape[0]:
            world = pose.transform_points(points)
            lo = np.minimum(world.min(axis=0), (pose.x, pose.y))
            hi = np.maximum(world.max(axis=0), (pose.x, pose.y))
        else:
            lo = hi = np.array([pose.x, pose.y])
        finest = self._levels[0]
        o = finest.origin
        width = finest.shape[1] * finest.resolution
        height = finest.shape[0] * finest.resolution
        margin = 1.0
        if (
            lo[0] - margin >= o.x
            and lo[1] - margin >= o.y
            and hi[0] + margin <= o.x + width
            and hi[1] + margin <= o.y + height
        ):
            return
        step = self._coarsest()
        rows, cols = finest.shape
        scale = 2 ** (self._matcher.levels - 1)
        # Coarse cells added on each side (the need plus the margin), as floats
        # first: a pose far away must not reach an integer conversion (its
        # counts overflow to inf, quietly: the size check below refuses them).
        with np.errstate(over="ignore"):
            left_f = (o.x - (lo[0] - _MARGIN)) / step if lo[0] - margin < o.x else 0.0
            down_f = (o.y - (lo[1] - _MARGIN)) / step if lo[1] - margin < o.y else 0.0
            right_need = hi[0] + margin - (o.x + width)
            up_need = hi[1] + margin - (o.y + height)
            right_f = (right_need + _MARGIN) / step if right_need > 0 else 0.0
            up_f = (up_need + _MARGIN) / step if up_need > 0 else 0.0
            need = (rows + (down_f + up_f + 2) * scale) * (cols + (left_f + right_f + 2) * scale)
        if not need <= MAX_CELLS:
            return  # keep the map; returns beyond it are clipped by the ray casting
        # Geometric growth: an axis that grows at least doubles (the extra on the side
        # or sides that need it), so a route that keeps leaving the map, a long
        # corridor, copies it O(log) times instead of every _MARGIN metres (quadratic
        # in the distance travelled). Only the extent changes: cells keep their world
        # positions and contents. Near MAX_CELLS the axis grows by a half, a quarter
        # or an eighth, and at the limit by the need alone.
        for share in (1.0, 0.5, 0.25, 0.125):
            wide = _at_least(left_f, right_f, share * cols / scale)
            tall = _at_least(down_f, up_f, share * rows / scale)
            cells = (rows + (tall[0] + tall[1] + 2) * scale) * (
                cols + (wide[0] + wide[1] + 2) * scale
            )
            if cells <= MAX_CELLS:
                (left_f, right_f), (down_f, up_f) = wide, tall
                break
        left, down, right, up = (math.ceil(v) for v in (left_f, down_f, right_f, up_f))
        # A grid's origin lies within ±1e9 m: the map grows no further left or down.
        left = min(left, math.floor((o.x + COORDINATE_LIMIT) / step))
        down = min(down, math.floor((o.y + COORDINATE_LIMIT) / step))
        if not (left or down or right or up):
            return
        x0 = max(o.x - left * step, -COORDINATE_LIMIT)
        y0 = max(o.y - down * step, -COORDINATE_LIMIT)
        grown = []
        for k, grid in enumerate(self._levels):
            f = scale // 2**k
            r, c = grid.shape
            arr = np.zeros((r + (down + up) * f, c + (left + right) * f), dtype=np.float32)
            arr[down * f : down * f + r, left * f : left * f + c] = grid._logodds
            # The grid takes arr itself: its values are the checked ones of a level and
            # zeros, and the constructor's scan and copy of them would double the time
            # of a growth and add a level's size to its peak (a tiny grid is built to
            # check the resolution and origin, then given arr).
            level = OccupancyGrid(_ONE_CELL, resolution=grid.resolution, origin=(x0, y0, 0.0))
            level._logodds = arr
            grown.append(level)
        self._levels = grown


def _at_least(low: float, high: float, extent: float) -> tuple[float, float]:
    """Coarse cells to add below and above on one axis: the need, at least ``extent``.

    ``low`` and ``high`` are the cells a scan needs on each side (0 for a side
    that needs none). An axis that needs nothing stays as it is; the extra goes
    to the side that needs cells, or half to each when both do.
    """
    extra = extent - (low + high)
    if not (low or high) or not extra > 0.0:
        return low, high
    if not low:
        return low, high + extra
    if not high:
        return low + extra, high
    return low + extra / 2.0, high + extra / 2.0


def _probability(value: float, name: str, low: float, high: float) -> float:
    """A probability strictly between ``low`` and ``high`` (the deprecated options)."""
    p = finite_float(value, name)
    # Both ends open: bounded_float's message ("<= high") named an end refused here.
    if not p > low:
        raise ValueError(f"{name} must be > {low:g} (and < {high:g}), got {p}")
    if not p < high:
        raise ValueError(f"{name} must be < {high:g} (and > {low:g}), got {p}")
    return p


def _log_odds(name: str, value: float | None) -> str | None:
    """What to write for a deprecated probability: ``name=`` its log-odds (None: not used)."""
    if value is None:
        return None
    return f"{name}={float(value)!r}, the log-odds log(p / (1 - p)) of that probability"
