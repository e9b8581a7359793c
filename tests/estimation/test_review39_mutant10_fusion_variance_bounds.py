"""PlanarFusion's measurement variances: [1e-100, 1e100] exactly, for either component.

Review 39 (mutation testing, MUTANT10). The fusion kernel's online step checks the
variances itself before it changes anything (``_fusion_kernels._planar_step``:
``1e-100 <= var <= 1e100``); the public layer takes its general, validating path
only when that check fails. The upper bound of the first component's check and
both bounds of the second's, each doubled, passed every test: a variance just
above 1e100 was then fused without a word, and an ``omega_variance`` of exactly
1e-100, which the docstrings admit, failed inside the general path with an
``AssertionError``. Oracle: the documented closed interval, read at its two end
points and at the floats just outside them (``math.nextafter``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from navkit.estimation import PlanarFusion

LOW, HIGH = 1e-100, 1e100
OUTSIDE = [math.nextafter(LOW, 0.0), math.nextafter(HIGH, math.inf), 1.5e100]


def _single(f: PlanarFusion, kind: str, var: float) -> Any:
    calls = {
        "speed": lambda: f.update_speed(0.1, 1.0, variance=var),
        "yaw": lambda: f.update_yaw(0.1, 0.3, variance=var),
        "yaw_rate": lambda: f.update_yaw_rate(0.1, 0.5, variance=var),
        "acceleration": lambda: f.update_acceleration(0.1, 0.2, variance=var),
    }
    return calls[kind]()


def _state(f: PlanarFusion) -> tuple[Any, ...]:
    return (f.t, f.x.tobytes(), np.asarray(f.P).tobytes())


@pytest.mark.parametrize("kind", ["speed", "yaw", "yaw_rate", "acceleration"])
@pytest.mark.parametrize("var", OUTSIDE)
def test_a_single_variance_outside_the_range_is_refused_and_changes_nothing(
    kind: str, var: float
) -> None:
    f = PlanarFusion(t0=0.0)
    before = _state(f)
    with pytest.raises(ValueError, match=r"^variance must be in \[1e-100, 1e\+100\]"):
        _single(f, kind, var)
    assert _state(f) == before


@pytest.mark.parametrize("which", ["v_variance", "omega_variance"])
@pytest.mark.parametrize("var", OUTSIDE)
def test_an_odometry_variance_outside_the_range_is_refused_and_changes_nothing(
    which: str, var: float
) -> None:
    f = PlanarFusion(t0=0.0)
    before = _state(f)
    kw = {"v_variance": 0.01, "omega_variance": 0.01, which: var}
    with pytest.raises(ValueError, match=rf"^{which} must be in \[1e-100, 1e\+100\]"):
        f.update_odometry(0.1, 1.0, 0.5, **kw)
    assert _state(f) == before


@pytest.mark.parametrize("which", ["v_variance", "omega_variance"])
@pytest.mark.parametrize("var", [LOW, HIGH])
def test_an_odometry_variance_at_either_end_is_fused(which: str, var: float) -> None:
    f = PlanarFusion(t0=0.0)
    kw = {"v_variance": 0.01, "omega_variance": 0.01, which: var}
    res = f.update_odometry(0.1, 1.0, 0.5, **kw)
    assert res.accepted and f.t == 0.1
    # The measured component is pulled to the measurement as far as its variance says:
    # all the way at 1e-100, not at all (to 1e-100 of the prior's variance) at 1e100.
    i, z = (3, 1.0) if which == "v_variance" else (4, 0.5)
    if var == LOW:
        assert f.x[i] == pytest.approx(z, rel=1e-12)
    else:
        assert abs(f.x[i]) < 1e-90


@pytest.mark.parametrize("kind", ["speed", "yaw", "yaw_rate", "acceleration"])
@pytest.mark.parametrize("var", [LOW, HIGH])
def test_a_single_variance_at_either_end_is_fused(kind: str, var: float) -> None:
    f = PlanarFusion(t0=0.0)
    assert _single(f, kind, var).accepted
    assert f.t == 0.1
