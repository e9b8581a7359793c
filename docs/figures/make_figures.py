"""Figures of the guides and tutorials, computed by navkit itself (issue 16).

Writes into ``docs/figures/`` (or the folder given):

* ``willow_paths.png`` — A* and Field D* routes across the Willow Garage office
  map (``MapPlanner``, 0.3 m robot radius);
* ``blended_field.png`` — the radial potential and force of
  ``BlendedAttraction`` for several blending widths, with the false minima of
  the narrow ones;
* ``carmen_grid.png`` — the Intel Research Lab CARMEN log ray-cast into a
  log-odds grid with ``integrate_scan`` from the corrected poses, one scan
  highlighted;
* ``ekf_vs_odometry.png`` — ``PlanarFusion`` of wheel odometry and IMU on the
  robot_localization bags: the Jackal run (test2.bag) done naively and done
  right, and the Husky run (test1.bag) against GPS with and without the IMU's
  mounting rotation.

Usage::

    python docs/figures/make_figures.py [OUTPUT_DIR]   # default: this script's folder

Needs matplotlib (``pip install -e ".[plot]"``), rosbags (``.[ros]``) and the
data sets in ``../shared/data`` beside the repository (or ``$NAVKIT_DATA``).
"""

from __future__ import annotations

import math
import os
import sys
from pathlib import Path
from typing import Any

import numpy as np

from navkit.estimation import FusionResult, MeasurementLog, PlanarFusion
from navkit.geometry import quaternion_to_matrix, quaternion_to_yaw, rpy_to_quaternion
from navkit.mapping import OccupancyGrid, integrate_scan
from navkit.mapping.io import BagImu, BagOdometry, read_bag_imu, read_bag_odometry, read_carmen
from navkit.planning import BlendedAttraction, MapPlanner

ROOT = Path(__file__).resolve().parents[2]
DATA = Path(os.environ.get("NAVKIT_DATA", ROOT.parent / "shared" / "data"))
WILLOW = DATA / "ros-map-server-maps/willow_garage_2010/willow-2010-02-18-0.10.yaml"
INTEL = DATA / "carmen-logs/intel-corrected.log.gz"
BAGS = DATA / "robot-localization-odom-imu-bags"

#: Willow route: from the west end of the long diagonal corridor to the
#: north-east corridor, across most of the building (cells (row, col)).
WILLOW_START_CELL = (215, 48)
WILLOW_GOAL_CELL = (443, 528)
#: Where robot_localization's own regression test puts the Jackal at the end.
JACKAL_REFERENCE = (1.0206, 3.4292)


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _map_image(grid: OccupancyGrid) -> np.ndarray:
    """Grey levels of a map: occupied black, free white, unknown grey."""
    img = np.full(grid.shape, 0.75)
    img[grid.free()] = 1.0
    img[grid.occupied()] = 0.0
    return img


def _extent(grid: OccupancyGrid) -> tuple[float, float, float, float]:
    x0, y0 = grid.origin.x, grid.origin.y
    return (x0, x0 + grid.width, y0, y0 + grid.height)


def willow_paths(out_dir: Path) -> Path:
    """A* against Field D* on the Willow Garage map."""
    plt = _pyplot()
    grid = OccupancyGrid.load(WILLOW)
    start_xy, goal_xy = grid.cell_to_world([WILLOW_START_CELL, WILLOW_GOAL_CELL])
    fig, ax = plt.subplots(figsize=(7.2, 7.2))
    ax.imshow(_map_image(grid), origin="lower", extent=_extent(grid), cmap="gray",
              vmin=0.0, vmax=1.0, interpolation="nearest")  # fmt: skip
    for name, colour in (("astar", "tab:red"), ("field_dstar", "tab:blue")):
        route = MapPlanner(grid, robot_radius=0.3, planner=name).plan(start_xy, goal_xy)
        pts = route.points
        label = f"{name}: {route.length:.2f} m, {len(pts)} points, {route.expanded} expanded"
        ax.plot(pts[:, 0], pts[:, 1], color=colour, lw=1.6, label=label)
    ax.plot(*start_xy, "o", color="tab:green", ms=7, label="start")
    ax.plot(*goal_xy, "*", color="tab:green", ms=12, label="goal")
    ax.set_xlim(2.0, 56.0)
    ax.set_ylim(2.0, 60.0)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title("Willow Garage office map, robot radius 0.3 m")
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    out = out_dir / "willow_paths.png"
    fig.savefig(out, dpi=90)
    plt.close(fig)
    return out


def blended_field(out_dir: Path) -> Path:
    """Radial potential and force of BlendedAttraction for several widths."""
    plt = _pyplot()
    d = np.linspace(0.0, 1.5, 3001)[1:]
    points = np.column_stack((d, np.zeros_like(d)))
    fig, (ax_u, ax_f) = plt.subplots(1, 2, figsize=(10.5, 4.2))
    for width in (0.05, 0.1, 0.15, 0.3, 0.5):
        field = BlendedAttraction((0.0, 0.0), threshold_radius=0.5, width=width)
        u = field.potential(points)
        f_radial = field.force(points)[:, 0]  # positive = pushed away from the goal
        (line,) = ax_u.plot(d, u, lw=1.4, label=f"ω = {width} m")
        ax_f.plot(d, f_radial, lw=1.4, color=line.get_color())
        # Local minima of U along the ray: the force turns from outward to inward.
        minima = np.flatnonzero((f_radial[:-1] > 0.0) & (f_radial[1:] <= 0.0))
        ax_u.plot(d[minima], u[minima], "o", color=line.get_color(), ms=6, mfc="none")
        ax_f.plot(d[minima], f_radial[minima], "o", color=line.get_color(), ms=6, mfc="none")
    for ax in (ax_u, ax_f):
        ax.axvline(0.5, color="0.6", ls=":", lw=1)
        ax.set_xlabel("distance to the goal d (m)")
        ax.grid(alpha=0.3)
    ax_f.axhline(0.0, color="k", lw=0.8)
    ax_u.set_ylabel("potential U")
    ax_u.set_title("BlendedAttraction, rad_thr = 0.5 m (circles: local minima)")
    ax_f.set_ylabel("radial force (> 0 pushes away from the goal)")
    ax_f.set_ylim(-1.6, 1.0)
    ax_f.set_title("force along a ray from the goal")
    ax_u.legend(fontsize=8)
    fig.tight_layout()
    out = out_dir / "blended_field.png"
    fig.savefig(out, dpi=90)
    plt.close(fig)
    return out


def carmen_grid(out_dir: Path) -> Path:
    """The Intel lab log ray-cast from its corrected poses."""
    plt = _pyplot()
    log = read_carmen(INTEL)
    grid = OccupancyGrid.empty(width=30.0, height=30.0, resolution=0.05,
                               origin=(-12.0, -24.5, 0.0))  # fmt: skip
    for scan, pose in zip(log.scans, log.laser_poses, strict=True):
        integrate_scan(grid, scan, pose, range_max=20.0)
    fig, ax = plt.subplots(figsize=(7.0, 7.0))
    ax.imshow(1.0 - grid.probability(), origin="lower", extent=_extent(grid), cmap="gray",
              vmin=0.0, vmax=1.0, interpolation="nearest")  # fmt: skip
    xy = np.array([(p.x, p.y) for p in log.laser_poses])
    ax.plot(xy[:, 0], xy[:, 1], color="tab:blue", lw=0.6, alpha=0.7, label="laser poses")
    k = 300
    ends = log.scans[k].to_points(log.laser_poses[k])
    ax.plot(ends[:, 0], ends[:, 1], ".", color="tab:red", ms=2.5, label=f"scan {k}")
    ax.plot(xy[k, 0], xy[k, 1], "o", color="tab:red", ms=5)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"Intel Research Lab: {len(log)} scans, integrate_scan, 5 cm cells")
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    out = out_dir / "carmen_grid.png"
    fig.savefig(out, dpi=80)
    plt.close(fig)
    return out


def _fuse(odom: BagOdometry, imu: BagImu, *, x0_yaw: float, wheel_rate: bool, imu_yaw: bool,
          pitch_projection: bool) -> FusionResult:  # fmt: skip
    """PlanarFusion of a bag's wheel odometry and (base-frame) IMU, as the tutorial does."""
    speed = odom.twists[:, 0]
    if pitch_projection:
        r = quaternion_to_matrix(imu.orientations)
        speed = speed * np.interp(odom.times, imu.times, np.hypot(r[:, 0, 0], r[:, 1, 0]))
    streams: dict[str, Any] = {
        "yaw_rate": (imu.times, imu.angular_velocities[:, 2]),
        "yaw_rate_variance": imu.angular_velocity_covariances[:, 2, 2],
    }
    if wheel_rate:
        streams["odometry"] = (odom.times, speed, odom.twists[:, 2])
        streams["odometry_variance"] = (odom.twist_covariances[:, 0, 0],
                                        odom.twist_covariances[:, 5, 5])  # fmt: skip
    else:
        streams["odometry"] = (odom.times, speed)
        streams["odometry_variance"] = (odom.twist_covariances[:, 0, 0], 0.03)
    if imu_yaw:
        streams["yaw"] = (imu.times, np.asarray(quaternion_to_yaw(imu.orientations)))
        streams["yaw_variance"] = imu.orientation_covariances[:, 2, 2]
    t0 = min(odom.times[0], imu.times[0])
    fusion = PlanarFusion([0.0, 0.0, x0_yaw, 0.0, 0.0, 0.0], t0=t0)
    return fusion.update_batch(MeasurementLog.from_streams(**streams))


def _gps_local(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """test1's GPS fixes as (times, east/north metres about the first fix)."""
    with path.open() as fh:
        header = fh.readline().strip().split(",")
    cols = [header.index(c) for c in ("stamp", "latitude", "longitude")]
    stamp, lat, lon = np.loadtxt(path, delimiter=",", skiprows=1, usecols=cols, ndmin=2).T
    lat, lon = np.radians(lat), np.radians(lon)
    earth = 6378137.0
    en = np.column_stack((earth * math.cos(lat[0]) * (lon - lon[0]), earth * (lat - lat[0])))
    return stamp, en


def _align(times: np.ndarray, xy: np.ndarray, ref_t: np.ndarray, ref: np.ndarray) -> np.ndarray:
    """``xy`` sampled at ``ref_t`` and rigidly aligned to ``ref`` (least squares)."""
    est = np.column_stack([np.interp(ref_t, times, xy[:, i]) for i in (0, 1)])
    mu_e, mu_r = est.mean(axis=0), ref.mean(axis=0)
    u, _, vt = np.linalg.svd((ref - mu_r).T @ (est - mu_e))
    rot = u @ np.diag([1.0, np.sign(np.linalg.det(u @ vt))]) @ vt
    return np.asarray((est - mu_e) @ rot.T + mu_r)


def ekf_vs_odometry(out_dir: Path) -> Path:
    """PlanarFusion against wheel odometry on both robot_localization bags."""
    plt = _pyplot()
    fig, (ax_j, ax_h) = plt.subplots(1, 2, figsize=(11.0, 5.2))

    odom = read_bag_odometry(BAGS / "test2.bag")
    imu = read_bag_imu(BAGS / "test2.bag", topic="/imu/data")
    yaw0 = float(quaternion_to_yaw(imu.orientations[0]))
    naive = _fuse(odom, imu, x0_yaw=0.0, wheel_rate=True, imu_yaw=False, pitch_projection=False)
    good = _fuse(odom, imu, x0_yaw=yaw0, wheel_rate=False, imu_yaw=True, pitch_projection=True)
    ax_j.plot(odom.poses[:, 0], odom.poses[:, 1], color="0.5", lw=1.2,
              label="wheel odometry (Jackal controller)")  # fmt: skip
    runs = ((naive, "tab:red", "naive: wheel v and ω + gyro, yaw 0"),
            (good, "tab:blue", "tutorial: v + IMU yaw + gyro, pitch"))
    for res, colour, label in runs:
        end = res.final_pose
        miss = math.hypot(end.x - JACKAL_REFERENCE[0], end.y - JACKAL_REFERENCE[1])
        ax_j.plot(res.states[:, 0], res.states[:, 1], color=colour, lw=1.4,
                  label=f"{label} ({miss:.2f} m off)")  # fmt: skip
    ax_j.plot(*JACKAL_REFERENCE, "k*", ms=12, label="robot_localization's end (± 0.14 m)")
    ax_j.plot(0.0, 0.0, "ko", ms=4)
    ax_j.set_aspect("equal", adjustable="datalim")
    ax_j.set_title("Jackal, test2.bag (61 s)")

    odom = read_bag_odometry(BAGS / "test1.bag")
    imu = read_bag_imu(BAGS / "test1.bag", topic="/imu/data")
    gps_t, gps = _gps_local(BAGS / "csv_extract" / "test1_gps_fix.csv")
    mount = rpy_to_quaternion(math.pi / 2, 0.0, -math.pi / 2)
    ax_h.plot(gps[:, 0], gps[:, 1], color="k", lw=1.0, ls="--", label="GPS")
    wheel = _align(odom.times, odom.poses[:, :2], gps_t, gps)
    rms = float(np.sqrt(np.mean(np.sum((wheel - gps) ** 2, axis=1))))
    ax_h.plot(wheel[:, 0], wheel[:, 1], color="0.5", lw=1.2,
              label=f"wheel odometry (RMS {rms:.1f} m)")  # fmt: skip
    gyros = ((imu, "tab:red", "gyro as mounted (no rotation)"),
             (imu.to_base(mount), "tab:blue", "gyro in base_link"))
    for base_imu, colour, label in gyros:
        res = _fuse(odom, base_imu, x0_yaw=0.0, wheel_rate=True, imu_yaw=False,
                    pitch_projection=False)  # fmt: skip
        fused = _align(res.times, res.states[:, :2], gps_t, gps)
        rms = float(np.sqrt(np.mean(np.sum((fused - gps) ** 2, axis=1))))
        ax_h.plot(fused[:, 0], fused[:, 1], color=colour, lw=1.2,
                  label=f"{label} (RMS {rms:.1f} m)")  # fmt: skip
    lo = np.minimum(gps.min(axis=0), wheel.min(axis=0)) - 10.0
    hi = np.maximum(gps.max(axis=0), wheel.max(axis=0)) + 10.0
    ax_h.set_xlim(lo[0], hi[0])
    ax_h.set_ylim(lo[1], hi[1])
    ax_h.set_aspect("equal", adjustable="datalim")
    ax_h.set_title("Husky, test1.bag (395 s), aligned to GPS")
    for ax in (ax_j, ax_h):
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    out = out_dir / "ekf_vs_odometry.png"
    fig.savefig(out, dpi=85)
    plt.close(fig)
    return out


def main(out_dir: Path | None = None) -> list[Path]:
    """Write every figure into ``out_dir`` (default: this script's folder)."""
    target = Path(__file__).resolve().parent if out_dir is None else Path(out_dir)
    target.mkdir(parents=True, exist_ok=True)
    return [willow_paths(target), blended_field(target), carmen_grid(target),
            ekf_vs_odometry(target)]  # fmt: skip


if __name__ == "__main__":
    for written in main(Path(sys.argv[1]) if len(sys.argv) > 1 else None):
        print(written, f"{written.stat().st_size / 1024:.0f} KB")
