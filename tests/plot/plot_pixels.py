"""Helpers of the plot tests: render an Axes to a PNG and find world points in it."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image

from navkit.plot import save_figure


def render(ax: Any, folder: Path, name: str = "figure.png") -> tuple[np.ndarray, Callable]:
    """Save ``ax``'s figure as a PNG and read it back.

    Returns the image (rows from the top, RGB floats in [0, 1]) and a function
    giving the ``(row, col)`` pixel of world points ``(x, y)``.
    """
    fig = ax.figure
    png = save_figure(ax, folder / name, dpi=fig.dpi)
    image = np.asarray(Image.open(png).convert("RGB"), dtype=np.float64) / 255.0

    def pixel(points_xy: Any) -> np.ndarray:
        display = ax.transData.transform(np.atleast_2d(np.asarray(points_xy, dtype=float)))
        col = np.floor(display[:, 0]).astype(int)
        row = image.shape[0] - 1 - np.floor(display[:, 1]).astype(int)
        return np.column_stack((row, col))

    return image, pixel


def grey_at(image: np.ndarray, pixel: np.ndarray, radius: int = 1) -> float:
    """Mean grey level of the small square of pixels around ``pixel`` (row, col)."""
    r, c = (int(v) for v in np.ravel(pixel)[:2])
    patch = image[r - radius : r + radius + 1, c - radius : c + radius + 1]
    return float(patch.mean())
