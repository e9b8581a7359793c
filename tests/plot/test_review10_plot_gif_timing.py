"""animate_trace plays at the documented fps: each frame lasts the nearest whole 1/100 s.

GIF delays are hundredths of a second and Pillow truncates milliseconds to
them: fps=35 asked for 29 ms and got 2/100 s (50 frames per second, the GIF
1.4 times too fast); fps=15 played at 16.7 instead of 14.3.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from navkit.plot import animate_trace
from navkit.sim import Metrics, Trace

pytest.importorskip("matplotlib")
Image = pytest.importorskip("PIL.Image")


def _turning_trace(rows: int) -> Trace:
    """A robot driving a quarter circle: every frame differs (nothing merged)."""
    t = np.linspace(0.0, 3.0, rows)
    a = t * (math.pi / 6.0)
    poses = np.column_stack((np.sin(a), 1.0 - np.cos(a), a))
    nan = math.nan
    metrics = Metrics(False, "timeout", 3.0, nan, nan, nan, nan, nan, nan, 1.0, 0, 0.0)
    return Trace(t, poses, poses, np.zeros((rows, 3)), (), (), metrics)


def _nearest_hundredths_ms(fps: int) -> int:
    """The GIF delay (ms, whole hundredths, at least 2) nearest to 1 / fps."""
    return 10 * min(range(2, 101), key=lambda c: abs(10 * c - 1000.0 / fps))


@pytest.mark.parametrize("fps", [6, 15, 28, 35, 10, 30, 50])
def test_each_frame_lasts_the_nearest_gif_delay(fps: int, tmp_path: Path) -> None:
    frames = 4
    gif = animate_trace(_turning_trace(9), tmp_path / "run.gif", fps=fps, max_frames=frames,
                        dpi=15)  # fmt: skip
    with Image.open(gif) as image:
        delays = []
        for k in range(image.n_frames):
            image.seek(k)
            delays.append(image.info["duration"])
    want = _nearest_hundredths_ms(fps)
    # Identical frames may be merged by Pillow, their delays added: the total holds.
    assert sum(delays) == frames * want
    assert all(d % want == 0 for d in delays)
    assert abs(want - 1000.0 / fps) <= 5.0
