"""animate_trace's GIF frames keep every colour their RGB canvas shows.

Frames were quantised with ``convert("P", palette=ADAPTIVE)`` (median cut):
ten times slower than fast octree (a third of a ``navkit run --animate``),
and weighing colours by their pixels it moved the small areas of a plot (a
robot's body over a path, a marker) by up to 42 levels of 255 to a
neighbour's colour. Each colour of at least 20 pixels must now survive within
24 levels at its own pixels.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import navkit.plot._animate as animate_module
from navkit.mapping import OccupancyGrid
from navkit.plot import animate_trace
from navkit.sim import Metrics, Scene, Trace

pytest.importorskip("matplotlib")
Image = pytest.importorskip("PIL.Image")

_TOLERANCE = 24


def _turning_trace(rows: int = 9) -> Trace:
    t = np.linspace(0.0, 3.0, rows)
    a = t * (math.pi / 6.0)
    poses = np.column_stack((1.0 + 2.0 * np.sin(a), 1.0 + 2.0 * (1.0 - np.cos(a)), a))
    nan = math.nan
    metrics = Metrics(False, "timeout", 3.0, nan, nan, nan, nan, nan, nan, 1.0, 0, 0.0)
    return Trace(t, poses, poses, np.zeros((rows, 3)), (), (), metrics)


def _colourful_scene() -> Scene:
    """A noisy fine map (hundreds of greys), ten coloured plans, seven markers, a run."""
    rng = np.random.default_rng(0)
    cells = np.full((400, 600), -1, dtype=np.int8)
    cells[50:350, 50:550] = 0
    cells[150:200, 200:400] = 100
    noise = rng.random(cells.shape) < 0.3
    cells[noise] = rng.choice(np.array([0, 100, -1], dtype=np.int8), int(noise.sum()))
    grid = OccupancyGrid(cells.astype(np.float32), resolution=0.01)  # log-odds -1, 0, 100
    paths = tuple((f"plan {k}", np.array([[0.5, 0.4 + 0.35 * k], [5.5, 0.4 + 0.35 * k]]))
                  for k in range(10))  # fmt: skip
    points = tuple((f"mark {k}", np.array([[0.6 + 0.5 * k, 3.5]])) for k in range(7))
    return Scene("colours", grid=grid, paths=paths, traces=(("run", _turning_trace()),),
                 points=points)  # fmt: skip


def test_every_colour_of_a_frame_survives_in_the_gif(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    canvases: list[np.ndarray] = []
    quantise = animate_module._frame

    def recording(canvas: Any) -> Any:
        canvases.append(np.array(np.asarray(canvas.buffer_rgba())[..., :3], dtype=np.int16))
        return quantise(canvas)

    monkeypatch.setattr(animate_module, "_frame", recording)
    gif = animate_trace(_colourful_scene(), tmp_path / "run.gif", max_frames=3, dpi=80)
    assert len(canvases) == 3
    with Image.open(gif) as image:
        assert image.n_frames == 3
        for k, rgb in enumerate(canvases):
            image.seek(k)
            shown = np.asarray(image.convert("RGB"), dtype=np.int16)
            colours, counts, errors = _median_errors(rgb, shown)
            assert len(colours) > 256  # more than a GIF palette holds: quantised for real
            for colour, error in zip(colours[counts >= 20], errors[counts >= 20], strict=True):
                assert error <= _TOLERANCE, (k, tuple(int(v) for v in colour), float(error))


def _median_errors(rgb: np.ndarray, shown: np.ndarray) -> tuple[np.ndarray, ...]:
    """Each colour of ``rgb`` (rows of 3), its pixel count and the median over its
    pixels of the largest channel error of ``shown`` there (``np.median``'s value)."""
    pixels = rgb.reshape(-1, 3)
    colours, inverse, counts = np.unique(pixels, axis=0, return_inverse=True, return_counts=True)
    inverse = inverse.reshape(-1)
    error = np.abs(shown.reshape(-1, 3) - pixels).max(axis=1)  # colour == rgb at its pixels
    by_colour = error[np.lexsort((error, inverse))]  # grouped by colour, sorted within
    start = np.concatenate(([0], np.cumsum(counts)[:-1]))
    middle = (by_colour[start + (counts - 1) // 2] + by_colour[start + counts // 2]) / 2.0
    return colours, counts, middle
