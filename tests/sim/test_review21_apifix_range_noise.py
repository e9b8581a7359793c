"""sim.RangeNoise is keyword-only, as every sensor configuration (review 21, API consistency).

Its sigma and bias are both tuples of small floats: swapped by position they
passed validation. By position they keep working for a release, with a
DeprecationWarning at the caller's line; navkit itself never passes them so.
Also: the seed's type error says ``got float``, as every other message does.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import warnings

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from navkit.sim import Circle, Compass, Imu, Lidar, RangeNoise, Robot, WheelEncoders, World
from navkit.sim._noise import PAPER_LIMITS, PAPER_SIGMA


def test_every_sensor_configuration_is_keyword_only() -> None:
    for cls in (RangeNoise, Compass, Imu, Lidar, WheelEncoders, Robot):
        kinds = {p.kind for p in inspect.signature(cls).parameters.values()}
        assert kinds == {inspect.Parameter.KEYWORD_ONLY}, cls.__name__


@st.composite
def bands(draw: st.DrawFn) -> tuple[tuple[float, ...], tuple[float, ...], tuple[float, ...]]:
    n = draw(st.integers(1, 4))
    edges = draw(st.lists(st.floats(0.01, 1e6), min_size=n - 1, max_size=n - 1, unique=True))
    sigma = draw(st.lists(st.floats(0.0, 1.0), min_size=n, max_size=n))
    bias = draw(st.lists(st.floats(-0.5, 0.5), min_size=n, max_size=n))
    return (*sorted(edges), math.inf), tuple(sigma), tuple(bias)


@settings(max_examples=60, deadline=None)
@given(bands(), st.integers(1, 3))
def test_positional_fields_warn_and_mean_what_they_meant(
    band: tuple[tuple[float, ...], ...], count: int
) -> None:
    assume(count > 1 or len(band[0]) == len(PAPER_SIGMA))  # limits alone: the default sigma's
    names = ("limits", "sigma", "bias")
    expected = RangeNoise(**dict(zip(names[:count], band[:count], strict=True)))
    with pytest.warns(DeprecationWarning, match=r"^RangeNoise\(limits") as caught:
        by_position = RangeNoise(*band[:count])
    assert len(caught) == 1
    assert caught[0].filename == __file__  # the caller's line, not navkit's
    assert ", ".join(n + "=" for n in names[:count]) in str(caught[0].message)
    assert by_position == expected
    assert dataclasses.astuple(by_position) == dataclasses.astuple(expected)


def test_positional_and_keyword_fields_mix_as_before() -> None:
    with pytest.warns(DeprecationWarning, match=r"RangeNoise\(limits\) by position"):
        noise = RangeNoise((1.0, math.inf), sigma=(0.01, 0.02))  # type: ignore[call-arg]
    assert noise == RangeNoise(limits=(1.0, math.inf), sigma=(0.01, 0.02))
    assert noise.bias == (0.0, 0.0)


def test_keywords_and_defaults_do_not_warn() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert RangeNoise().limits == PAPER_LIMITS
        assert RangeNoise().sigma == PAPER_SIGMA
        noise = RangeNoise(sigma=(0.01, 0.02), bias=(0.0, 0.01), limits=(1.0, math.inf))
        assert dataclasses.replace(noise, bias=(0.0, 0.02)).bias == (0.0, 0.02)


def test_bad_positional_calls_are_type_errors_before_warning() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(TypeError, match="at most 3 positional arguments"):
            RangeNoise((math.inf,), (0.1,), (0.0,), (0.0,))  # type: ignore[call-arg]
        with pytest.raises(TypeError, match="multiple values for argument 'limits'"):
            RangeNoise((math.inf,), limits=(math.inf,))  # type: ignore[misc]


def test_validation_is_unchanged_by_position() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        with pytest.raises(ValueError, match=r"^sigma\[0\] must lie in \[0, 1\]"):
            RangeNoise((math.inf,), (2.0,))  # type: ignore[call-arg]


@pytest.mark.parametrize("noise", [None, RangeNoise(limits=(math.inf,), sigma=(0.01,))])
def test_navkit_never_warns_from_inside(noise: RangeNoise | None) -> None:
    # Lidar builds a zero-noise band when noise is None: by keyword.
    world = World(Circle((0.0, 0.0), 3.0, solid=False))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        scan = Lidar(n_beams=8, noise=noise).scan(world, (0.0, 0.0, 0.0), seed=1)
    assert np.all(np.isfinite(scan.ranges))
    if noise is None:
        assert np.allclose(scan.ranges, 3.0)


@pytest.mark.parametrize(("seed", "kind"), [(1.5, "float"), ("1", "str"), (True, "bool")])
def test_a_seed_of_another_type_names_the_type(seed: object, kind: str) -> None:
    world = World(Circle((0.0, 0.0), 3.0, solid=False))
    with pytest.raises(TypeError, match=rf"^seed must be .*, got {kind}$"):
        Lidar(dropout=0.1).scan(world, (0.0, 0.0, 0.0), seed=seed)  # type: ignore[arg-type]
