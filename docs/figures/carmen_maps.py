"""Maps of the CARMEN logs built by navkit's ScanMapper from a noisy motion prior (issue 15).

Runs the mapper of ``benchmarks/carmen_navkit.py`` (the same settings and
prior: the true relative motion plus 5 cm per axis and 2° of noise, seed 0)
on the intel, aces and csail logs and draws each finished map with the
estimated trajectory (red) over the corrected one (blue, rigidly aligned onto
the estimate). Writes ``carmen_maps.png``.

Usage::

    python docs/figures/carmen_maps.py [OUTPUT_DIR]   # default: this script's folder

Needs matplotlib (``pip install -e ".[plot]"``) and ``../shared/data/carmen-logs``
beside the repository (or ``$NAVKIT_DATA``).
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

import carmen_eval as ce
import carmen_navkit as cn


def main(out_dir: Path | None = None) -> Path:
    """Write ``carmen_maps.png`` into ``out_dir`` (default: this script's folder)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    target = Path(__file__).resolve().parent if out_dir is None else Path(out_dir)
    target.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(1, 3, figsize=(15, 5.6))
    for ax, name in zip(axes, ce.LOGS, strict=True):
        data = ce.load_log(name)
        mapper = cn.make_mapper()
        for scan, odom in zip(data.scans, ce.chain(ce.motion_prior(data.poses)), strict=True):
            mapper.update(scan, odometry=odom)
        grid = mapper.map
        known = np.argwhere(grid.logodds != 0)
        (r0, c0), (r1, c1) = known.min(axis=0), known.max(axis=0) + 1
        o, res = grid.origin, grid.resolution
        extent = (o.x + c0 * res, o.x + c1 * res, o.y + r0 * res, o.y + r1 * res)
        ax.imshow(
            1.0 - grid.probability()[r0:r1, c0:c1],
            origin="lower",
            cmap="gray",
            extent=extent,
            interpolation="nearest",
        )
        est = np.asarray(mapper.trajectory)
        rot, t = ce.align_rigid(data.poses[:, :2], est[:, :2])
        truth = data.poses[:, :2] @ rot.T + t
        ax.plot(truth[:, 0], truth[:, 1], "-", color="tab:blue", lw=0.6, label="corrected log")
        ax.plot(est[:, 0], est[:, 1], "-", color="tab:red", lw=0.6, label="navkit")
        ate = float(np.sqrt(np.mean(ce.absolute_trajectory_error(est, data.poses) ** 2)))
        ax.set_title(f"{name}: {len(data)} scans, ATE {ate:.2f} m")
        ax.set_xlabel("x (m)")
        ax.set_aspect("equal")
    axes[0].set_ylabel("y (m)")
    axes[0].legend(fontsize=8, loc="lower left")
    fig.suptitle("ScanMapper on the CARMEN logs (5 cm finest cells, prior noise 5 cm / 2°)")
    fig.tight_layout()
    out = target / "carmen_maps.png"
    handle, tmp = tempfile.mkstemp(suffix=".png", dir=target)
    os.close(handle)
    try:
        fig.savefig(tmp, dpi=80)
        os.chmod(tmp, 0o644)
        os.replace(tmp, out)
    finally:
        plt.close(fig)
        if os.path.exists(tmp):
            os.unlink(tmp)
    return out


if __name__ == "__main__":
    print(main(Path(sys.argv[1]) if len(sys.argv) > 1 else None))
