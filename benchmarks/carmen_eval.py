"""Scan-matching evaluation on the CARMEN logs (intel, aces, csail) with a motion prior (issue 15).

The logs in ``../shared/data/carmen-logs`` keep only keyframes (0.67-1.05 m and
10-22° between consecutive scans), and their poses are SLAM-corrected: they are
the ground truth here. Every method gets the same *motion prior*, standing in
for odometry: the true relative motion between consecutive scans plus Gaussian
noise (default 5 cm on x and on y of the motion, in the frame of the first
scan, and 2° on the heading; a fixed seed).

API (import this file as a module: ``sys.path`` holds ``benchmarks/`` when a
script in it runs, e.g. ``python benchmarks/carmen_navkit.py``)::

    import carmen_eval as ce

    log = ce.load_log("intel", max_scans=None, data_dir=None)   # CarmenData
    prior = ce.motion_prior(log.poses, sigma_xy=0.05, sigma_theta=math.radians(2), seed=0)
    result = ce.evaluate(my_method, log, prior, method="mine")  # Result (metrics, poses)
    print(ce.format_table([result]))
    ce.main(methods={"mine": my_method})       # the CLI, with extra methods beside the baselines

A *method* is any callable ``method(scans, prior) -> poses``:

* ``scans``: tuple of ``navkit.mapping.LaserScan`` (in the laser frame; CARMEN's
  FLASER geometry, "no return" readings invalid);
* ``prior``: array (n - 1, 3) of relative motions ``[dx, dy, dθ]`` from scan i to
  scan i + 1, expressed in the frame of scan i (``pose_i⁻¹ ∘ pose_{i+1}``);
* returns an array (n, 3) of poses ``[x, y, θ]`` of every scan in any fixed frame
  (the first is usually ``(0, 0, 0)``): the metrics are invariant to the frame.

Baselines: :func:`dead_reckoning` (the prior alone), :func:`kiss_icp_method`
(KISS-ICP 1.x, each scan as 3-D points with z = 0, voxel 0.1 m, the prior as its
initial guess) and :func:`icp_method` (plain point-to-point scan-to-scan ICP with
a SciPy k-d tree, the prior as the initial guess).

Metrics (:func:`compute_metrics`), against the corrected poses:

* relative pose error (RPE) between consecutive scans, and between scan i and the
  first scan j after ~1 m and ~5 m of true travel: ``E = (T_i⁻¹ T_j)_true⁻¹
  (T_i⁻¹ T_j)_est``, translation ‖E_xy‖ in m and rotation |E_θ| in degrees,
  mean and RMS (:class:`ErrorStats`);
* absolute trajectory error (ATE) after the best rigid 2-D alignment of the
  estimated positions onto the true ones (Kabsch/Umeyama without scale), RMS
  and mean, m;
* gross failures: consecutive pairs with an error above 0.5 m or 10°;
* wall-clock and CPU time per scan of the method call.

Run ``python benchmarks/carmen_eval.py`` for the baseline table on all three logs
(``--basin`` adds the noise basin: 10/20/50 cm with 5/10/20°; ``--help``).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.spatial import cKDTree

from navkit.mapping import LaserScan
from navkit.mapping.io import read_carmen

FloatArray = NDArray[np.float64]
Method = Callable[[Sequence[LaserScan], FloatArray], ArrayLike]

LOGS = ("intel", "aces", "csail")
#: Default prior noise: 5 cm per axis and 2° (the issue's setting).
SIGMA_XY = 0.05
SIGMA_THETA = math.radians(2.0)
#: Prior noise levels of the basin study: (sigma_xy m, sigma_theta rad).
BASIN_LEVELS = ((0.10, math.radians(5.0)), (0.20, math.radians(10.0)), (0.50, math.radians(20.0)))
#: A consecutive pair whose error exceeds either bound is a gross failure.
GROSS_TRANSLATION = 0.5
GROSS_ROTATION = math.radians(10.0)
#: Travel distances of the longer RPEs, m.
RPE_DISTANCES = (1.0, 5.0)

#: The issue's KISS-ICP figures (voxel 0.1 m, the prior as the guess), for the table's notes.
ISSUE_KISS_ICP = {
    "intel": {"pair_m": 0.045, "pair_deg": 1.04, "ate_m": 1.85},
    "aces": {"pair_m": 0.054, "pair_deg": 0.99, "ate_m": 2.86},
    "csail": {"pair_m": 0.038, "pair_deg": 0.63, "ate_m": 0.99},
}


# ---------------------------------------------------------------- SE(2) on arrays
def _wrap(a: ArrayLike) -> FloatArray:
    out = np.asarray(a, dtype=np.float64)
    w = np.mod(out + math.pi, 2.0 * math.pi) - math.pi
    return np.where(w == -math.pi, math.pi, w)


def relative_motions(poses: ArrayLike) -> FloatArray:
    """Relative motions ``pose_i⁻¹ ∘ pose_{i+1}`` (n - 1, 3) of poses (n, 3)."""
    p = np.asarray(poses, dtype=np.float64)
    return between(p[:-1], p[1:])


def between(a: ArrayLike, b: ArrayLike) -> FloatArray:
    """``a⁻¹ ∘ b`` for poses (..., 3): b expressed in the frame of a."""
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    dx, dy = b[..., 0] - a[..., 0], b[..., 1] - a[..., 1]
    c, s = np.cos(a[..., 2]), np.sin(a[..., 2])
    return np.stack((c * dx + s * dy, -s * dx + c * dy, _wrap(b[..., 2] - a[..., 2])), axis=-1)


def compose(a: ArrayLike, b: ArrayLike) -> FloatArray:
    """``a ∘ b`` for poses (..., 3)."""
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    c, s = np.cos(a[..., 2]), np.sin(a[..., 2])
    return np.stack(
        (
            a[..., 0] + c * b[..., 0] - s * b[..., 1],
            a[..., 1] + s * b[..., 0] + c * b[..., 1],
            _wrap(a[..., 2] + b[..., 2]),
        ),
        axis=-1,
    )


def chain(motions: ArrayLike, start: ArrayLike = (0.0, 0.0, 0.0)) -> FloatArray:
    """Poses (n + 1, 3) reached from ``start`` by the relative ``motions`` (n, 3)."""
    m = np.asarray(motions, dtype=np.float64).reshape(-1, 3)
    out = np.empty((m.shape[0] + 1, 3))
    out[0] = np.asarray(start, dtype=np.float64)
    for i, step in enumerate(m):
        out[i + 1] = compose(out[i], step)
    return out


def _matrix(pose: ArrayLike) -> FloatArray:
    x, y, th = (float(v) for v in np.asarray(pose, dtype=np.float64))
    c, s = math.cos(th), math.sin(th)
    return np.array([[c, -s, 0.0, x], [s, c, 0.0, y], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])


def _pose(matrix: FloatArray) -> FloatArray:
    return np.array([matrix[0, 3], matrix[1, 3], math.atan2(matrix[1, 0], matrix[0, 0])])


# ---------------------------------------------------------------- data
@dataclass(frozen=True)
class CarmenData:
    """One CARMEN log: its scans and their corrected (true) laser poses (n, 3)."""

    name: str
    scans: tuple[LaserScan, ...]
    poses: FloatArray

    def __len__(self) -> int:
        return len(self.scans)


def data_folder(data_dir: str | Path | None = None) -> Path:
    """The ``carmen-logs`` folder (``data_dir``, ``$NAVKIT_DATA`` or ``shared/data`` nearby)."""
    try:
        from navkit.sim.scenarios import find_data

        return Path(find_data("carmen-logs", data_dir=data_dir))
    except ImportError:  # pragma: no cover - an older navkit
        base = Path(data_dir) if data_dir else Path(__file__).resolve().parents[2] / "shared/data"
        return base / "carmen-logs"


def load_log(
    name: str, *, max_scans: int | None = None, data_dir: str | Path | None = None
) -> CarmenData:
    """Read ``<name>-corrected.log.gz`` (intel, aces or csail), optionally its first scans only."""
    log = read_carmen(data_folder(data_dir) / f"{name}-corrected.log.gz")
    n = len(log) if max_scans is None else min(int(max_scans), len(log))
    poses = np.array([[p.x, p.y, p.theta] for p in log.laser_poses[:n]], dtype=np.float64)
    return CarmenData(name, tuple(log.scans[:n]), poses)


def motion_prior(
    poses: ArrayLike,
    *,
    sigma_xy: float = SIGMA_XY,
    sigma_theta: float = SIGMA_THETA,
    seed: int = 0,
) -> FloatArray:
    """True relative motions between consecutive poses plus Gaussian noise, shape (n - 1, 3).

    Noise: N(0, sigma_xy²) on dx and on dy (frame of the first scan of the pair),
    N(0, sigma_theta²) on dθ, from ``np.random.default_rng(seed)`` — the same
    prior for every method at a given seed and noise level.
    """
    motions = relative_motions(poses)
    rng = np.random.default_rng(seed)
    noise = rng.standard_normal(motions.shape) * np.array([sigma_xy, sigma_xy, sigma_theta])
    out = motions + noise
    out[:, 2] = _wrap(out[:, 2])
    return out


# ---------------------------------------------------------------- metrics
@dataclass(frozen=True)
class ErrorStats:
    """Translation (m) and rotation (degrees) errors: mean and RMS over ``n`` pairs."""

    mean_m: float
    rms_m: float
    mean_deg: float
    rms_deg: float
    n: int

    @classmethod
    def of(cls, translation: ArrayLike, rotation_rad: ArrayLike) -> ErrorStats:
        t = np.asarray(translation, dtype=np.float64)
        r = np.degrees(np.abs(np.asarray(rotation_rad, dtype=np.float64)))
        if t.size == 0:
            return cls(math.nan, math.nan, math.nan, math.nan, 0)
        return cls(
            float(t.mean()),
            float(np.sqrt(np.mean(t**2))),
            float(r.mean()),
            float(np.sqrt(np.mean(r**2))),
            int(t.size),
        )


@dataclass(frozen=True)
class Metrics:
    """Every figure of one run (see the module docstring)."""

    pair: ErrorStats
    over_1m: ErrorStats
    over_5m: ErrorStats
    ate_rms_m: float
    ate_mean_m: float
    gross_failures: int
    pairs: int
    seconds_per_scan: float
    cpu_seconds_per_scan: float = math.nan


def pair_indices(poses: ArrayLike, distance: float | None) -> tuple[NDArray[np.int64], ...]:
    """Index pairs (i, j) for the RPE: consecutive scans (``distance=None``), or for each i
    the first j whose true path length from i reaches ``distance`` m."""
    p = np.asarray(poses, dtype=np.float64)
    n = p.shape[0]
    if distance is None:
        i = np.arange(n - 1)
        return i, i + 1
    steps = np.hypot(*np.diff(p[:, :2], axis=0).T)
    travelled = np.concatenate(([0.0], np.cumsum(steps)))
    j = np.searchsorted(travelled, travelled + distance, side="left")
    keep = j < n
    return np.arange(n)[keep], j[keep]


def relative_pose_errors(
    estimated: ArrayLike, truth: ArrayLike, *, distance: float | None = None
) -> tuple[FloatArray, FloatArray]:
    """Translation (m) and signed rotation (rad) errors of the pairs of :func:`pair_indices`."""
    est = np.asarray(estimated, dtype=np.float64)
    ref = np.asarray(truth, dtype=np.float64)
    if est.shape != ref.shape or est.ndim != 2 or est.shape[1] != 3:
        raise ValueError(f"estimated and truth must both be (n, 3), got {est.shape}, {ref.shape}")
    i, j = pair_indices(ref, distance)
    err = between(between(ref[i], ref[j]), between(est[i], est[j]))
    return np.hypot(err[:, 0], err[:, 1]), err[:, 2]


def align_rigid(source_xy: ArrayLike, target_xy: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Rotation R (2, 2) and translation t (2,) minimising Σ‖R s + t − d‖² (Kabsch, no scale)."""
    s = np.asarray(source_xy, dtype=np.float64)
    d = np.asarray(target_xy, dtype=np.float64)
    mu_s, mu_d = s.mean(axis=0), d.mean(axis=0)
    u, _, vt = np.linalg.svd((d - mu_d).T @ (s - mu_s))
    rot = u @ np.diag([1.0, np.sign(np.linalg.det(u @ vt))]) @ vt
    return rot, mu_d - rot @ mu_s


def absolute_trajectory_error(estimated: ArrayLike, truth: ArrayLike) -> FloatArray:
    """Position errors (n,) after the rigid 2-D alignment of the estimate onto the truth."""
    est = np.asarray(estimated, dtype=np.float64)[:, :2]
    ref = np.asarray(truth, dtype=np.float64)[:, :2]
    rot, t = align_rigid(est, ref)
    return np.asarray(np.hypot(*((est @ rot.T + t) - ref).T), dtype=np.float64)


def compute_metrics(
    estimated: ArrayLike, truth: ArrayLike, seconds: float = 0.0, cpu_seconds: float = math.nan
) -> Metrics:
    """All metrics of an estimated trajectory (n, 3) against the truth (n, 3).

    ``seconds`` / ``cpu_seconds``: wall-clock and process CPU time of the whole run.
    """
    est = np.asarray(estimated, dtype=np.float64)
    ref = np.asarray(truth, dtype=np.float64)
    if est.shape != ref.shape:
        raise ValueError(f"the method returned poses of shape {est.shape}, expected {ref.shape}")
    if not np.all(np.isfinite(est)):
        raise ValueError("the method returned non-finite poses")
    t_pair, r_pair = relative_pose_errors(est, ref)
    stats = [ErrorStats.of(*relative_pose_errors(est, ref, distance=d)) for d in RPE_DISTANCES]
    ate = absolute_trajectory_error(est, ref)
    gross = (t_pair > GROSS_TRANSLATION) | (np.abs(r_pair) > GROSS_ROTATION)
    return Metrics(
        pair=ErrorStats.of(t_pair, r_pair),
        over_1m=stats[0],
        over_5m=stats[1],
        ate_rms_m=float(np.sqrt(np.mean(ate**2))),
        ate_mean_m=float(ate.mean()),
        gross_failures=int(gross.sum()),
        pairs=int(t_pair.size),
        seconds_per_scan=seconds / max(1, ref.shape[0]),
        cpu_seconds_per_scan=cpu_seconds / max(1, ref.shape[0]),
    )


@dataclass(frozen=True)
class Result:
    """One method on one log at one prior noise level."""

    log: str
    method: str
    sigma_xy: float
    sigma_theta: float
    metrics: Metrics
    poses: FloatArray = field(repr=False)


def evaluate(
    method: Method,
    data: CarmenData,
    prior: ArrayLike,
    *,
    name: str = "method",
    sigma_xy: float = SIGMA_XY,
    sigma_theta: float = SIGMA_THETA,
) -> Result:
    """Run ``method(data.scans, prior)``, time it and score its poses against ``data.poses``.

    Times are wall clock and process CPU time (less disturbed by other processes
    on a shared machine; it sums the threads of a multi-threaded method).
    """
    prior_arr = np.array(prior, dtype=np.float64)
    prior_arr.flags.writeable = False
    start, cpu_start = time.perf_counter(), time.process_time()
    poses = np.asarray(method(data.scans, prior_arr), dtype=np.float64)
    seconds = time.perf_counter() - start
    cpu_seconds = time.process_time() - cpu_start
    return Result(
        data.name,
        name,
        sigma_xy,
        sigma_theta,
        compute_metrics(poses, data.poses, seconds, cpu_seconds),
        poses,
    )


# ---------------------------------------------------------------- baselines
def dead_reckoning(scans: Sequence[LaserScan], prior: FloatArray) -> FloatArray:
    """The prior alone: its motions chained from the origin."""
    del scans
    return chain(prior)


def icp_align(
    source_xy: FloatArray,
    target_xy: FloatArray,
    guess: ArrayLike,
    *,
    tree: Any = None,
    max_distance: float = 0.5,
    iterations: int = 50,
    tolerance: float = 1e-6,
) -> FloatArray:
    """Plain point-to-point ICP: pose ``[x, y, θ]`` of the source frame in the target frame.

    Nearest neighbours in a SciPy ``cKDTree`` of the target, pairs farther than
    ``max_distance`` m dropped, closed-form rigid update (Kabsch), from ``guess``
    until the update is below ``tolerance`` or ``iterations`` are done.
    """
    tree = cKDTree(target_xy) if tree is None else tree
    x, y, th = (float(v) for v in np.asarray(guess, dtype=np.float64))
    rot = np.array([[math.cos(th), -math.sin(th)], [math.sin(th), math.cos(th)]])
    t = np.array([x, y])
    for _ in range(iterations):
        moved = source_xy @ rot.T + t
        dist, idx = tree.query(moved, distance_upper_bound=max_distance)
        ok = np.isfinite(dist)
        if ok.sum() < 3:
            break
        d_rot, d_t = align_rigid(moved[ok], target_xy[idx[ok]])
        rot = d_rot @ rot
        t = d_rot @ t + d_t
        if np.hypot(*d_t) < tolerance and abs(math.atan2(d_rot[1, 0], d_rot[0, 0])) < tolerance:
            break
    return np.array([t[0], t[1], math.atan2(rot[1, 0], rot[0, 0])])


def icp_method(
    scans: Sequence[LaserScan], prior: FloatArray, *, max_distance: float = 0.5
) -> FloatArray:
    """Scan-to-scan point-to-point ICP (SciPy k-d tree), each pair started from the prior."""
    motions = np.empty((len(scans) - 1, 3))
    previous = scans[0].to_points()
    for i in range(1, len(scans)):
        current = scans[i].to_points()
        motions[i - 1] = icp_align(current, previous, prior[i - 1], max_distance=max_distance)
        previous = current
    return chain(motions)


def kiss_icp_method(
    scans: Sequence[LaserScan], prior: FloatArray, *, voxel_size: float = 0.1
) -> FloatArray:
    """KISS-ICP (pip ``kiss-icp`` 1.x): each scan as 3-D points with z = 0, the prior as guess.

    KISS-ICP predicts each frame at ``last_pose @ last_delta`` (its constant
    velocity model, ``KissICP.register_frame``); setting ``last_delta`` to the
    prior's motion before registering a frame makes the prior its initial
    guess, and its adaptive threshold then measures the deviation from the
    prior. Deskewing is off (a scan has no per-point times); ``max_range`` is
    the scans' maximum range; one thread (``max_num_threads=1``: the issue's
    per-scan time is for one core).
    """
    try:
        from kiss_icp.config import load_config
        from kiss_icp.kiss_icp import KissICP
    except ImportError as exc:  # pragma: no cover - bench extra missing
        raise ImportError("KISS-ICP needs kiss-icp: install navkit[bench]") from exc
    config = load_config(None)
    config.data.deskew = False
    config.data.max_range = float(max(s.range_max for s in scans))
    config.data.min_range = 0.0
    config.mapping.voxel_size = float(voxel_size)
    config.registration.max_num_threads = 1
    odometry = KissICP(config)
    poses = np.empty((len(scans), 3))
    for i, scan in enumerate(scans):
        xy = scan.to_points()
        points = np.column_stack((xy, np.zeros(len(xy))))
        if i > 0:
            odometry.last_delta = _matrix(prior[i - 1])
        odometry.register_frame(points, np.zeros(len(xy)))
        poses[i] = _pose(odometry.last_pose)
    return poses


BASELINES: dict[str, Method] = {
    "prior": dead_reckoning,
    "kiss-icp": kiss_icp_method,
    "icp": icp_method,
}


# ---------------------------------------------------------------- tables
def run(
    methods: dict[str, Method],
    logs: Sequence[str] = LOGS,
    *,
    levels: Sequence[tuple[float, float]] = ((SIGMA_XY, SIGMA_THETA),),
    seed: int = 0,
    max_scans: int | None = None,
    data_dir: str | Path | None = None,
    progress: Callable[[str], None] | None = None,
) -> list[Result]:
    """Every method on every log at every prior noise level (one prior per log and level)."""
    results = []
    for log_name in logs:
        data = load_log(log_name, max_scans=max_scans, data_dir=data_dir)
        for sigma_xy, sigma_theta in levels:
            prior = motion_prior(data.poses, sigma_xy=sigma_xy, sigma_theta=sigma_theta, seed=seed)
            for name, method in methods.items():
                if progress is not None:
                    progress(f"{log_name} {name} σ={sigma_xy:g} m/{math.degrees(sigma_theta):g}°")
                results.append(
                    evaluate(
                        method, data, prior, name=name, sigma_xy=sigma_xy, sigma_theta=sigma_theta
                    )
                )
    return results


def format_table(results: Sequence[Result], *, noise: bool = False) -> str:
    """A Markdown table of results (``noise=True`` adds the prior's noise level columns)."""
    head = ["log", "method"]
    if noise:
        head += ["σ_xy m", "σ_θ °"]
    head += [
        "pair m mean/RMS",
        "pair ° mean/RMS",
        "1 m: m / °",
        "5 m: m / °",
        "ATE m RMS/mean",
        "gross",
        "ms/scan wall/CPU",
    ]
    rows = []
    for r in results:
        m = r.metrics
        row = [r.log, r.method]
        if noise:
            row += [f"{r.sigma_xy:.2f}", f"{math.degrees(r.sigma_theta):.0f}"]
        row += [
            f"{m.pair.mean_m:.3f} / {m.pair.rms_m:.3f}",
            f"{m.pair.mean_deg:.2f} / {m.pair.rms_deg:.2f}",
            f"{m.over_1m.mean_m:.3f} / {m.over_1m.mean_deg:.2f}",
            f"{m.over_5m.mean_m:.3f} / {m.over_5m.mean_deg:.2f}",
            f"{m.ate_rms_m:.2f} / {m.ate_mean_m:.2f}",
            f"{m.gross_failures}/{m.pairs}",
            f"{1000 * m.seconds_per_scan:.2f} / {1000 * m.cpu_seconds_per_scan:.2f}",
        ]
        rows.append(row)
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)


def issue_note() -> str:
    """The issue's KISS-ICP figures, to print under the table."""
    parts = [
        f"{k}: pair {v['pair_m']:.3f} m / {v['pair_deg']:.2f}°, ATE {v['ate_m']:.2f} m"
        for k, v in ISSUE_KISS_ICP.items()
    ]
    return "Issue 15's KISS-ICP (voxel 0.1 m, prior as guess): " + "; ".join(parts)


def make_parser() -> argparse.ArgumentParser:
    """The harness's options (``carmen_navkit.py`` adds its own to them)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--logs", nargs="+", default=list(LOGS), choices=LOGS)
    parser.add_argument(
        "--methods",
        nargs="+",
        default=None,
        help="methods to run (default: all; baselines: prior kiss-icp icp)",
    )
    parser.add_argument("--max-scans", type=int, default=None, help="first N scans of each log")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--data-dir", default=None, help="folder holding carmen-logs/")
    parser.add_argument(
        "--basin", action="store_true", help="also the basin: 10/20/50 cm with 5/10/20°"
    )
    return parser


def main(
    argv: Sequence[str] | None = None,
    *,
    methods: dict[str, Method] | None = None,
    parser: argparse.ArgumentParser | None = None,
) -> int:
    """The command line: baselines (and ``methods``) on the logs; ``--basin`` adds noise levels.

    ``parser`` (default :func:`make_parser`) may carry a caller's extra options,
    which this function ignores.
    """
    parser = make_parser() if parser is None else parser
    args = parser.parse_args(argv)
    available = {**BASELINES, **(methods or {})}
    chosen = args.methods or list(available)
    unknown = [m for m in chosen if m not in available]
    if unknown:
        parser.error(f"unknown methods {unknown}; available: {sorted(available)}")
    selected = {name: available[name] for name in chosen}

    def progress(text: str) -> None:
        print(f"  running {text}", file=sys.stderr, flush=True)

    common = {"seed": args.seed, "max_scans": args.max_scans, "data_dir": args.data_dir}
    results = run(selected, args.logs, progress=progress, **common)
    sigma = f"{SIGMA_XY * 100:.0f} cm per axis, {math.degrees(SIGMA_THETA):.0f}°"
    print(f"Prior noise {sigma}, seed {args.seed}\n")
    print(format_table(results))
    print("\n" + issue_note())
    if args.basin:
        basin = run(selected, args.logs, levels=BASIN_LEVELS, progress=progress, **common)
        print("\nBasin (gross failure = pair error > 0.5 m or > 10°):\n")
        print(format_table(basin, noise=True))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
