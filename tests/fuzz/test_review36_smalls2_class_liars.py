"""Objects that lie about their class: ``__class__`` says ``np.ndarray`` (review 36).

``isinstance`` believes an object's ``__class__``: a
``unittest.mock.Mock(spec=np.ndarray)`` in a user's test, or a wrapper whose
``__class__`` property returns ``np.ndarray`` (a lazy or proxied array), passed
navkit's ``isinstance(x, np.ndarray)`` checks and then failed with an
``AttributeError`` (``'Liar' object has no attribute 'dtype'``) or an unnamed
``TypeError`` (``'in <string>' requires string as left operand, not Mock``):
821 such failures over the fuzz catalogue's array and number arguments. navkit
now asks the object's type (``issubclass(type(x), np.ndarray)``,
``navkit._shared.validation.is_ndarray``): a wrapper NumPy reads through
``__array__`` is read as any array-like (the plain array's answer), and a mock,
which NumPy cannot read, is refused with a ``TypeError``/``ValueError`` naming
the argument.
"""

from __future__ import annotations

import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any
from unittest import mock

import foreign_arrays
import fuzz_specs  # noqa: F401 - registers the specs
import numpy as np
import pytest
from fuzz_engine import SPECS, Ctx, quiet, refresh_memory_limit, slots

from class_liars import Liar
from navkit.geometry import Pose2D, as_pose
from navkit.mapping.io import MovingAIMap
from navkit.sim import sweep
from navkit.sim.scenarios import Demo

pytestmark = pytest.mark.filterwarnings("ignore::PendingDeprecationWarning")


def _mock() -> Any:
    return mock.Mock(spec=np.ndarray)


def test_the_liars_pass_isinstance() -> None:
    assert isinstance(Liar([1.0]), np.ndarray)
    assert isinstance(_mock(), np.ndarray)


# --------------------------------------------------------------------------- the fuzz catalogue


def _liar_variant(a: np.ndarray, _f: Path) -> Any:
    return Liar(a)


def _mock_variant(a: Any, _f: Path) -> Any:
    return foreign_arrays.PAIR, (_mock(), a)


ARRAY_LIARS = [
    foreign_arrays._array_variant("liar wrapper", _liar_variant, may_refuse=True),
    foreign_arrays._array_variant("Mock(spec=np.ndarray)", _mock_variant, expect="reject"),
]
SCALAR_LIARS = [
    foreign_arrays._scalar_variant("0-d liar wrapper", lambda x: Liar(x), may_refuse=True),
    foreign_arrays._scalar_variant(
        "0-d Mock(spec=np.ndarray)",
        lambda x: (foreign_arrays.PAIR, (_mock(), x)),
        expect="reject",
    ),
]


@pytest.fixture
def folder(monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """A scratch folder; the checker's own input snapshots told about the liars."""
    plain_state = foreign_arrays._input_state
    plain_buffer = foreign_arrays._buffer_of

    def state(value: Any) -> Any:
        if type(value) is Liar:
            return ("liar", np.array(value._data))
        if issubclass(type(value), mock.Mock):
            return ("mock",)
        return plain_state(value)

    def buffer(value: Any) -> Any:
        if type(value) is Liar:
            return value._data
        return None if issubclass(type(value), mock.Mock) else plain_buffer(value)

    monkeypatch.setattr(foreign_arrays, "_input_state", state)
    monkeypatch.setattr(foreign_arrays, "_buffer_of", buffer)
    path = Path(tempfile.mkdtemp(prefix="navkit-liars-"))
    try:
        yield path
    finally:
        shutil.rmtree(path, ignore_errors=True)


def _problems(name: str, folder: Path) -> list[str]:
    """What went wrong with liars for each array and number argument of spec ``name``."""
    spec = SPECS[name]
    refresh_memory_limit()
    with quiet():
        if foreign_arrays._invoke(spec, None, None, folder).error is not None:
            return []
        found: list[str] = []
        for slot, kind, value, _nested in slots(spec.make(Ctx(folder))):
            kinds = foreign_arrays.variants_for(kind)
            if kinds is foreign_arrays.ARRAY_VARIANTS:
                variants = ARRAY_LIARS
            elif kinds is foreign_arrays.SCALAR_VARIANTS:
                variants = SCALAR_LIARS
            else:
                continue
            for variant in variants:
                found += foreign_arrays.check_variant(spec, slot.path, value, variant, folder)
                made = variant.make(value, folder)
                if made is foreign_arrays.SKIP or variant.expect != "reject":
                    continue
                err = foreign_arrays._invoke(spec, slot.path, made[0], folder).error
                named = foreign_arrays.names_the_argument(err, name, slot.path) or (
                    name in CALLED and str(err).startswith(CALLED[name])
                )
                if err is not None and not named:
                    found.append(f"{name}: {'.'.join(slot.path)} = {variant.label}: {err!r}")
    return found


#: Functions that name their argument by their ``name=`` keyword's default.
CALLED = {"navkit.geometry.as_pose": "pose ", "navkit.geometry.as_twist": "twist "}

#: One spec through each place that trusted isinstance (validation's converters,
#: OccupancyGrid's log-odds checks, Trace's copies, a footprint's radius, the
#: Pose2D field checks, MovingAI's integer arrays, the velocity limits).
DEFAULT = [
    "navkit.geometry.Pose2D",
    "navkit.geometry.Pose2D.transform_points",
    "navkit.mapping.OccupancyGrid",
    "navkit.mapping.OccupancyGrid.world_to_cell",
    "navkit.sim.Trace",
    "navkit.sim.World.collides",
    "navkit.mapping.io.MovingAIScenarios",
    "navkit.control.limit_velocity_change",
    "navkit.kinematics.tick_delta",
]

@pytest.mark.parametrize("name", DEFAULT)
def test_liars_are_read_as_arrays_or_refused_by_name(name: str, folder: Path) -> None:
    problems = _problems(name, folder)
    assert not problems, f"{len(problems)} problem(s):\n  " + "\n  ".join(problems[:20])


@pytest.mark.slow
def test_every_spec_reads_or_refuses_liars(folder: Path) -> None:
    problems = [p for name in sorted(SPECS) for p in _problems(name, folder)]
    assert not problems, f"{len(problems)} problem(s):\n  " + "\n  ".join(problems[:40])


# --------------------------------------------------------------------------- single places


def test_a_pose_compared_with_a_liar_is_unequal() -> None:
    # _elementwise read other.dtype for anything isinstance called an ndarray.
    assert (Pose2D(1.0, 2.0) == Liar([1.0, 2.0, 0.0])) is False
    assert (Pose2D(1.0, 2.0) != Liar([1.0, 2.0, 0.0])) is True


def test_as_pose_reads_a_liar() -> None:
    assert as_pose(Liar([1.0, 2.0, 0.5])) == Pose2D(1.0, 2.0, 0.5)
    with pytest.raises(TypeError, match="pose must be numeric array-like"):
        as_pose(_mock())


def test_movingai_terrain_from_a_liar_is_refused_by_name() -> None:
    # MovingAIMap read terrain.dtype of anything isinstance called an ndarray; an
    # object NumPy reads only through __array__ is no sequence of rows.
    rows = np.array([list("..@"), list("T..")])
    for liar in (Liar(rows), _mock()):
        with pytest.raises(TypeError, match=r"^terrain must be a sequence, got"):
            MovingAIMap(liar)


def test_a_generator_seed_from_a_liar_is_refused_by_name() -> None:
    from navkit.sim._lidar import as_generator

    for liar in (Liar(np.int64(7)), _mock()):
        with pytest.raises(TypeError, match=r"^seed must be a numpy Generator"):
            as_generator(liar, "seed")


def test_sweep_seeds_given_as_liars_are_named() -> None:
    scenario = Demo()
    with pytest.raises(TypeError, match="seeds"):
        sweep(scenario, trials=1, seeds=_mock())
    with pytest.raises(TypeError, match="seeds"):
        sweep(scenario, trials=1, seeds=Liar(np.int64(3)))
