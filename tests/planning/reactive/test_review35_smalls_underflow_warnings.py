"""Underflow reports under a caller's ``np.seterr(under=...)`` (session 39, SMALLS).

Decided: ``sample_field`` (no per-step call: one ``np.errstate`` is 1 % of its
smallest grid) evaluates its field with underflow ignored, so it is silent under
``under="warn"``, ``"call"`` and the rest, as under ``"raise"``, and evaluates a
user's field once (before, under ``"raise"``, twice: the try, then the redo). The
per-step calls (the fields' ``potential`` and ``force``, the controller, the
velocity limit) still let NumPy report their underflows to 0, which
``docs/getting-started.md`` now lists; the last tests hold those words to the code.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterator

import numpy as np
import pytest
from numpy.typing import NDArray

from navkit.control import PotentialFieldController, limit_velocity_change
from navkit.geometry import Pose2D
from navkit.planning import (
    BlendedAttraction,
    ConicAttraction,
    ParaboloidAttraction,
    PotentialField,
    sample_field,
)

F64 = NDArray[np.float64]
TINY = 1e-200  # a goal this far from a cell centre: its squared offset underflows

WINDOW = {"xlim": (-0.5, 0.5), "ylim": (-0.5, 0.5), "resolution": 1.0}  # one centre, (0, 0)


@pytest.fixture
def warn_as_error() -> Iterator[None]:
    with np.errstate(under="warn"), warnings.catch_warnings():
        warnings.simplefilter("error")
        yield


@pytest.mark.parametrize(
    "field",
    [ParaboloidAttraction((TINY, 0.0)), BlendedAttraction((0.0, TINY)),
     ConicAttraction((TINY, TINY)) + ParaboloidAttraction((0.0, TINY))],
    ids=["paraboloid", "blended", "composite"],
)  # fmt: skip
def test_sample_field_is_silent_under_every_underflow_mode(field: PotentialField) -> None:
    want = sample_field(field, **WINDOW)  # NumPy's default: underflow ignored
    reports: list[str] = []
    for mode in ("warn", "raise", "call", "print"):
        handler = np.errstate(under=mode, call=lambda kind, flag: reports.append(kind))
        with handler, warnings.catch_warnings():
            warnings.simplefilter("error")
            got = sample_field(field, **WINDOW)
        assert np.array_equal(got.potential, want.potential)
        assert np.array_equal(got.force, want.force)
    assert reports == []


class _Counted(PotentialField):
    """A user's field whose squares underflow near the origin, counting its calls."""

    __slots__ = ("calls",)

    def __init__(self) -> None:
        self.calls = 0

    def _potential(self, pts: F64) -> F64:
        self.calls += 1
        out: F64 = (pts[:, 0] - TINY) ** 2
        return out

    def _force(self, pts: F64) -> F64:
        self.calls += 1
        return np.stack((2.0 * (TINY - pts[:, 0]), np.zeros(len(pts))), axis=1)


def test_sample_field_evaluates_a_users_field_once_under_raise() -> None:
    field = _Counted()
    with np.errstate(under="raise"):
        sampled = sample_field(field, **WINDOW)
    assert field.calls == 2  # one potential, one force: no second try
    assert sampled.potential.tolist() == [[0.0]]


def test_other_errors_still_follow_the_callers_seterr() -> None:
    class Dividing(_Counted):
        __slots__ = ()

        def _potential(self, pts: F64) -> F64:
            out: F64 = 1.0 / (pts[:, 0] - pts[:, 0])
            return out

    with np.errstate(divide="raise"), pytest.raises(FloatingPointError, match="divide"):
        sample_field(Dividing(), **WINDOW)


# ---------------------------------------------- what the docs say still reports
def test_the_documented_per_step_reports(warn_as_error: None) -> None:
    near = [[1.4e-154, 0.0]]
    with pytest.raises(RuntimeWarning, match="underflow"):
        ParaboloidAttraction((0.0, 0.0)).potential(near)
    with pytest.raises(RuntimeWarning, match="underflow"):
        BlendedAttraction((0.0, 0.0)).force(near)
    with pytest.raises(RuntimeWarning, match="underflow"):
        PotentialFieldController().desired_velocity(Pose2D(1.4e-154, 0.0, 0.0), (0.0, 0.0))
    with pytest.raises(RuntimeWarning, match="underflow"):
        limit_velocity_change([0.0, 0.0], [1e10, 1e-300], max_accel=0.5, max_decel=2.0, dt=0.1)
    with pytest.raises(RuntimeWarning, match="underflow"):
        limit_velocity_change([0.0, 0.0], [1.0, 1e-306], max_accel=1e-3, max_decel=1e-3, dt=0.05)
    # ... and only from there: 1.5e-154 m squares to a normal float.
    ParaboloidAttraction((0.0, 0.0)).potential([[1.5e-154, 0.0]])
    limit_velocity_change([0.0, 0.0], [1.0, 1e-306], max_accel=0.5, max_decel=2.0, dt=0.1)


def test_the_reports_change_no_result() -> None:
    near = np.array([[1.4e-154, 0.0]])
    field = BlendedAttraction((0.0, 0.0))
    want = field.force(near), field.potential(near)
    with np.errstate(under="warn"), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        got = field.force(near), field.potential(near)
    assert all(np.array_equal(a, b) for a, b in zip(got, want, strict=True))
