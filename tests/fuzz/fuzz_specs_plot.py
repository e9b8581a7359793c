"""Fuzz specs of ``navkit.plot`` (registered on import by ``fuzz_specs.py``).

Kept cheap: tiny maps and runs, pictures of a few dozen pixels (``dpi`` 10-20)
and GIFs of two frames; files go to the case's own folder (``c.tmp``).
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np
from fuzz_engine import (
    Anything,
    Array,
    Call,
    Choice,
    Hostile,
    Kind,
    Obj,
    Real,
    Text,
    call,
    h,
    spec,
)
from shapely.geometry import box

from navkit.mapping import LaserScan, OccupancyGrid
from navkit.planning import ConicAttraction, PotentialField, SampledField
from navkit.plot import (
    animate_trace,
    plot_field,
    plot_grid,
    plot_path,
    plot_scan,
    plot_scene,
    plot_trace,
    save_figure,
)
from navkit.sim import Circle, Metrics, MovingObstacle, Scene, Trace, World

A = np.array
P = "navkit.plot."
AX = Anything(optional=True)  # a matplotlib Axes (None: a new figure)
LABEL = Text(optional=True)
COLOR = Text(optional=True)


class PicturePath(Kind):
    """A path of a picture to write (``.png`` or ``.gif``), in the case's folder."""

    def __init__(self, suffix: str, **kw: Any) -> None:
        super().__init__(allowed_errors=(FileNotFoundError,), **kw)
        self.suffix = suffix
        self.name = f"a {suffix} path to write"

    def catalogue(self, valid: Any = None) -> list[Hostile]:
        sfx = self.suffix
        return [
            Hostile("the same as a str", lambda v, _c: str(v), equivalent=True),
            Hostile(
                "an existing file (replaced)",
                lambda _v, c: _junk(c.tmp / f"old{sfx}"),
                equivalent=True,
            ),
            Hostile("upper-case suffix", lambda _v, c: c.tmp / f"UP{sfx.upper()}", equivalent=True),
            Hostile("another suffix", lambda _v, c: c.tmp / "picture.jpg"),
            Hostile("no suffix", lambda _v, c: c.tmp / "picture"),
            Hostile("the folder itself", lambda _v, c: c.tmp),
            Hostile("a folder with the suffix", lambda _v, c: _folder(c.tmp / f"dir{sfx}")),
            Hostile("a missing folder", lambda _v, c: c.tmp / "no" / "such" / f"p{sfx}"),
            Hostile("a name with a NUL", lambda _v, c: str(c.tmp / f"a\x00b{sfx}")),
            h("''", ""),
            h("3.0", 3.0),
            h("None", None),
            h("bytes", f"p{sfx}".encode()),
            h("{}", {}),
            h("object()", object()),
            *super().catalogue(valid),
        ]

    def must_reject(self, value: Any, tags: set[str]) -> str | None:
        if isinstance(value, bytes) or not isinstance(value, (str, os.PathLike)):
            return f"a {type(value).__name__} for a path"
        text = os.fspath(value)
        if not text or "\x00" in text:
            return "an empty path or one with a NUL"
        p = Path(text)
        if p.suffix.lower() != self.suffix:
            return f"a path not ending in {self.suffix}"
        if p.is_dir():
            return "a folder"
        if not p.parent.is_dir():
            return "a path in a missing folder"
        return None


def _junk(path: Path) -> Path:
    path.write_bytes(b"not a picture")
    return path


def _folder(path: Path) -> Path:
    path.mkdir(exist_ok=True)
    return path


def grid() -> Call:
    occupied = np.zeros((6, 8), dtype=bool)
    occupied[4:, 5:] = True
    return call(OccupancyGrid.from_occupancy, occupied, resolution=0.25)


def laser_scan() -> Call:
    return call(LaserScan, A([0.8, 1.5, math.inf]), angle_min=-0.5, angle_increment=0.5,
                range_min=0.1, range_max=4.0)  # fmt: skip


def metrics() -> Call:
    return call(Metrics, False, "timeout", 1.0, math.nan, math.nan, math.nan, math.nan,
                math.nan, math.nan, 0.5, 0, 1.0)  # fmt: skip


TIMES = [0.0, 0.5, 1.0]
POSES = [[0.0, 0.0, 0.0], [0.5, 0.1, 0.2], [1.0, 0.3, 0.4]]
ESTIMATES = [[np.nan, np.nan, np.nan], [0.5, 0.15, 0.2], [1.0, 0.35, 0.4]]


def trace() -> Call:
    return call(Trace, A(TIMES), A(POSES), A(ESTIMATES), np.zeros((3, 3)), (), (), metrics())


def _scene() -> Scene:
    # Built by a helper (Scene holds nested tuples a lazy call cannot reach into).
    world = World([box(-1.0, -1.0, 2.0, 1.0).exterior, Circle(A([1.5, 0.5]), 0.2)],
                  moving=[MovingObstacle.constant_velocity(0.1, start_xy=(0.0, 0.5),
                                                           velocity_xy=(0.1, 0.0))])  # fmt: skip
    done = Metrics(False, "timeout", 1.0, *[math.nan] * 6, 0.5, 0, 1.0)
    run = Trace(A(TIMES), A(POSES), A(ESTIMATES), np.zeros((3, 3)), (), (), done)
    occupied = np.zeros((6, 8), dtype=bool)
    occupied[4:, 5:] = True
    return Scene(
        "fuzz",
        grid=OccupancyGrid.from_occupancy(occupied, resolution=0.25),
        world=world,
        paths=(("plan", A([[0.0, 0.0], [1.0, 0.3]])),),
        traces=(("run", run),),
        points=(("goal", A([1.0, 0.3])),),
    )


def scene() -> Call:
    return call(_scene)


FIELD = Obj((PotentialField, SampledField))

spec(P + "plot_grid", lambda c: call(plot_grid, grid(), alpha=0.5), kinds={"ax": AX})
spec(
    P + "plot_path",
    lambda c: call(plot_path, A([[0.0, 0.0], [1.0, 0.5]]), label="plan", color="red"),
    kinds={"path": Array(), "ax": AX, "label": LABEL, "color": COLOR},
)
spec(
    P + "plot_trace",
    lambda c: call(plot_trace, trace(), label="run", color="C1", estimate=True),
    kinds={"trace": Obj(Trace), "ax": AX, "label": LABEL, "color": COLOR},
)
spec(
    P + "plot_scan",
    lambda c: call(plot_scan, laser_scan(), A([1.0, 0.5, 0.3]), rays=True, label="scan"),
    kinds={"ax": AX, "label": LABEL, "color": COLOR},
)
spec(
    P + "plot_field",
    lambda c: call(
        plot_field,
        call(ConicAttraction, A([0.0, 0.0])),
        kind="contour",
        xlim=A([-1.0, 1.0]),
        ylim=A([-1.0, 1.0]),
        resolution=0.25,
        clip=2.0,
    ),
    kinds={"field": FIELD, "ax": AX, "kind": Choice("surface", "contour", "quiver")},
)
spec(P + "plot_scene", lambda c: call(plot_scene, scene()), kinds={"scene": Obj(Scene), "ax": AX})
spec(
    P + "save_figure",
    lambda c: call(save_figure, call(plot_grid, grid()), c.tmp / "map.png", dpi=12.0),
    kinds={"fig_or_ax": Anything(), "path": PicturePath(".png")},
)
spec(
    P + "animate_trace",
    lambda c: call(
        animate_trace,
        trace(),
        c.tmp / "run.gif",
        fps=5,
        max_frames=2,
        footprint=0.1,
        lidar_mount=A([0.1, 0.0, 0.0]),
        dpi=12.0,
    ),
    kinds={
        "source": Obj((Scene, Trace)),
        "path": PicturePath(".gif"),
        "fps": Real(integer=True),
        "max_frames": Real(integer=True),
        "footprint": Real(),
    },
)
