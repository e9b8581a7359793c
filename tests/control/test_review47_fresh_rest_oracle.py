"""Review 47 (FRESH): the resting distance ``PotentialFieldController`` names, checked
against an independent computation.

The controller refuses a ``goal_tolerance`` not beyond the distance at which its
``BlendedAttraction`` brings the robot to rest, found by a bracket search over
the field's own ``_force`` on a 512-point grid. Here the same distance comes
from the paper's gradient written out again in 40-digit arithmetic (mpmath),
its first sign change found on a grid 400 times finer and bisected: over blends
drawn from the whole parameter ranges (gains 1e-12 to 1e12, lengths 1e-6 to
1e6 m), where the radial force changes sign several times (narrow widths: a
ring of minima beyond ``threshold_radius``), and for elliptic blends, whose
robot slides off the stiffer axis's rest to the other's. The check never
raises anything but the documented ``ValueError`` or warns.
"""

from __future__ import annotations

import itertools
import math
import warnings
from typing import Any

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from navkit.control import PotentialFieldController
from navkit.control._potential_field_controller import _resting_distance
from navkit.planning import BlendedAttraction

_NAMES = ("k_att", "c", "a", "b", "threshold_radius", "width", "m", "u_trans")
_FINE = np.geomspace(1e-12, 2e9, 200_000)


def _mp(params: dict[str, float]) -> dict[str, mpmath.mpf]:
    return {k: mpmath.mpf(v) for k, v in params.items()}


def _gradient(p: dict[str, mpmath.mpf], x: mpmath.mpf, y: mpmath.mpf) -> tuple[Any, Any]:
    """∇U of the blend at ``(x, y)`` (goal at the origin), as the paper writes it."""
    d = mpmath.sqrt(x * x + y * y)
    z = 2 * (d - p["threshold_radius"]) / p["width"]
    sig, one_minus = 1 / (1 + mpmath.exp(-z)), 1 / (1 + mpmath.exp(z))
    kc = p["k_att"] * p["c"]
    u_par = kc * (x * x / p["a"] ** 2 + y * y / p["b"] ** 2)
    u_cone = p["m"] * p["u_trans"] * (d - p["threshold_radius"])
    radial = sig * p["m"] * p["u_trans"] + (2 / p["width"]) * sig * one_minus * (u_cone - u_par)
    gx = one_minus * 2 * kc * x / p["a"] ** 2 + radial * x / d
    gy = one_minus * 2 * kc * y / p["b"] ** 2 + radial * y / d
    return gx, gy


def _inward(params: dict[str, float], axis: int, d: np.ndarray) -> np.ndarray:
    """Whether the force at ``d`` m along ``axis`` points at the goal (float64, for the scan)."""
    from scipy.special import expit

    k, c, r, w = params["k_att"], params["c"], params["threshold_radius"], params["width"]
    mu = params["m"] * params["u_trans"]
    semi = params["a"] if axis == 0 else params["b"]
    z = 2.0 * (d - r) / w
    sig, one_minus = expit(z), expit(-z)
    with np.errstate(all="ignore"):
        radial = sig * mu + (2.0 / w) * sig * one_minus * (mu * (d - r) - k * c * d**2 / semi**2)
        grad: np.ndarray = one_minus * 2.0 * k * c * d / semi**2 + radial
    return grad >= 0.0


def _axis_rest(params: dict[str, float], axis: int) -> float:
    """The last distance along ``axis`` before the force first points inward (0: at once)."""
    inward = np.flatnonzero(_inward(params, axis, _FINE))
    if inward.size == 0:
        return math.inf
    k = int(inward[0])
    if k == 0:
        return 0.0
    p = _mp(params)
    lo, hi = mpmath.mpf(float(_FINE[k - 1])), mpmath.mpf(float(_FINE[k]))
    for _ in range(80):
        mid = (lo + hi) / 2
        point = (mid, mpmath.mpf(0)) if axis == 0 else (mpmath.mpf(0), mid)
        if _gradient(p, *point)[axis] >= 0:
            hi = mid
        else:
            lo = mid
    return float(lo)


def _held(params: dict[str, float], rest: float, axis: int) -> bool:
    """Whether a robot nudged off ``axis`` at ``rest`` is pushed back onto it."""
    if not 0.0 < rest < math.inf:
        return True
    p = _mp(params)
    off = mpmath.mpf(rest) * mpmath.mpf("1e-3")
    point = (mpmath.mpf(rest), off) if axis == 0 else (off, mpmath.mpf(rest))
    return bool(_gradient(p, *point)[1 - axis] >= 0)


def _oracle(params: dict[str, float]) -> float:
    rests = [_axis_rest(params, 0), _axis_rest(params, 1)]
    held = [r for axis, r in enumerate(rests) if _held(params, r, axis)]
    return min(held or rests)


def _field(params: dict[str, float]) -> BlendedAttraction:
    return BlendedAttraction(np.zeros(2), **params)


def _log_uniform(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(math.log10(lo), math.log10(hi)).map(lambda e: 10.0**e)


@pytest.mark.parametrize(
    "params",
    [
        {},  # the default blend: 3.75 mm
        {"width": 0.3},  # 4.6 cm (BlendedAttraction's Notes)
        {"k_att": 2.0, "m": 1.5},  # the soccer players' at 1.5 m/s
        {"a": 0.5, "b": 2.0},  # elliptic: the y axis's rest holds, 17.4 mm
        {"a": 2.0, "b": 0.5},  # the same turned a quarter
        {"width": 0.1},  # a ring of minima at 0.55 m: not the nearest rest
    ],
)
def test_the_named_rest_is_the_papers_computed_independently(params: dict[str, float]) -> None:
    full = {name: getattr(BlendedAttraction(np.zeros(2)), name) for name in _NAMES} | params
    assert _resting_distance(_field(full)) == pytest.approx(_oracle(full), rel=1e-9, abs=1e-15)


@settings(max_examples=40, deadline=None)
@given(
    k_att=_log_uniform(1e-3, 1e3),
    a=_log_uniform(0.1, 10.0),
    b=_log_uniform(0.1, 10.0),
    threshold_radius=_log_uniform(1e-3, 10.0),
    width=_log_uniform(1e-4, 10.0),
    m=_log_uniform(1e-3, 1e3),
)
def test_over_drawn_blends_the_named_rest_is_the_independent_one(
    k_att: float, a: float, b: float, threshold_radius: float, width: float, m: float
) -> None:
    params = {
        "k_att": k_att, "c": 1.0, "a": a, "b": b, "threshold_radius": threshold_radius,
        "width": width, "m": m, "u_trans": 1.0,
    }  # fmt: skip
    rest = _resting_distance(_field(params))
    assert rest == pytest.approx(_oracle(params), rel=1e-9, abs=1e-15)


_EXTREMES = {
    "k_att": (1e-12, 1.0, 1e12),
    "c": (1.0,),
    "a": (1e-6, 1.0, 1e6),
    "b": (1e-6, 1e6),
    "threshold_radius": (0.0, 1e-6, 0.5, 1e6),
    "width": (1e-6, 1e-3, 1.0, 1e6),
    "m": (1e-12, 1e12),
    "u_trans": (1.0, 1e12),
}


def _extreme_cases(step: int) -> list[dict[str, float]]:
    combos = itertools.product(*_EXTREMES.values())
    return [
        dict(zip(_EXTREMES, combo, strict=True))
        for combo in itertools.islice(combos, 0, None, step)
    ]


@pytest.mark.parametrize(
    "step", [pytest.param(23, id="sample"), pytest.param(1, marks=pytest.mark.slow, id="all")]
)
def test_extreme_blends_raise_only_the_documented_error(step: int) -> None:
    # np.errstate(all="raise") and warnings as errors: the search's overflow and
    # underflow far out and near the goal stay inside it.
    for params in _extreme_cases(step):
        field = _field(params)
        with np.errstate(all="raise"), warnings.catch_warnings():
            warnings.simplefilter("error")
            rest = _resting_distance(field)
            try:
                PotentialFieldController(field, goal_tolerance=1e-6)
            except ValueError as exc:
                assert "goal_tolerance must exceed" in str(exc)
                assert rest >= 1e-6
            else:
                assert rest < 1e-6
        assert math.isfinite(rest)
        assert rest == pytest.approx(_oracle(params), rel=1e-9, abs=1e-15)


# ------------------------------------------------- found by this review, not fixed here
# The controller's module was another helper's this session: these mark what a user
# meets (strict: they fail, as XPASS, once fixed; drop the mark then).


@pytest.mark.parametrize("width", np.linspace(0.12, 0.5, 40).tolist())
def test_the_distance_the_error_names_is_itself_accepted(width: float) -> None:
    # The message named the rest rounded to the nanometre: with width 0.12 the rest
    # is 0.000892502496 m, named 0.000892502, below it (so for 22 of 40 widths in
    # [0.12, 0.5]): the tolerance the message named was refused, with the same
    # message ("must exceed X m ...; got X"). Now rounded up where rounding fell below.
    field = BlendedAttraction(np.zeros(2), width=width)
    with pytest.raises(ValueError, match="goal_tolerance must exceed") as info:
        PotentialFieldController(field, goal_tolerance=1e-6)
    named = float(str(info.value).split("must exceed ")[1].split(" m")[0])
    PotentialFieldController(field, goal_tolerance=math.nextafter(named, math.inf))
    # Rounded up by a nanometre at most (or named exactly, and then refused: "exceed").
    assert 0.0 <= named - _resting_distance(field) <= 1e-9


class _NoBlend(BlendedAttraction):
    """A blend whose σ is 0 everywhere: the paraboloid alone, pulling up to the goal."""

    __slots__ = ()

    def _terms(self, pts: Any) -> Any:
        diff, d, sig, one_minus, u_par, u_cone = BlendedAttraction._terms(self, pts)
        return diff, d, np.zeros_like(sig), np.ones_like(one_minus), u_par, u_cone


def test_a_subclass_changing_the_blends_terms_is_judged_by_its_own_force() -> None:
    field = _NoBlend(np.zeros(2))
    # Its force points at the goal 1 mm off (the paraboloid's -2 x), yet the default
    # blend's 3.75 mm is named and a 1 mm tolerance refused.
    assert field.force([[1e-3, 0.0]])[0, 0] < 0.0
    PotentialFieldController(field, goal_tolerance=1e-3)
