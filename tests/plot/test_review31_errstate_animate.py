"""An animation's frames do not depend on the caller's ``np.seterr`` (review 31).

Each frame turns the robot's outline by its heading: a heading below about
1e-290 rad times an outline coordinate of rounding noise (the 1e-17 of a
circle's cos(π/2)) underflows, ``FloatingPointError`` in ``animate_trace``
after a caller's ``np.seterr(all="raise")`` or ``under="raise"``.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from navkit.plot import animate_trace
from navkit.sim import Metrics, Trace

pytest.importorskip("matplotlib")


def _animate(path: Path) -> bytes:
    times = np.array([0.0, 0.5, 1.0])
    poses = np.array([[1e-300, 1e-300, 1e-300], [0.5, 0.1, 0.2], [1.0, 0.3, 0.4]])
    metrics = Metrics(False, "timeout", 1.0, *[math.nan] * 6, 0.5, 0, 1.0)
    trace = Trace(times, poses, poses.copy(), np.zeros_like(poses), (), (), metrics)
    animate_trace(trace, path, fps=5, max_frames=2, footprint=0.1, dpi=12.0)
    return path.read_bytes()


@pytest.mark.parametrize("mode", ["all", "under"])
def test_the_same_animation_whatever_numpys_error_state(mode: str, tmp_path: Path) -> None:
    expected = _animate(tmp_path / "default.gif")
    with np.errstate(**{mode: "raise"}):  # type: ignore[arg-type]
        got = _animate(tmp_path / "raise.gif")  # FloatingPointError before the fix
    assert got == expected
