"""Every array argument of every fuzz spec, given as a foreign array type (review 19).

``foreign_arrays`` turns each spec's valid value of each array, pose, cell and
real-number argument into masked arrays, ``np.matrix``, big-endian dtypes,
memory maps, views with negative, Fortran or zero strides, ``__array__`` and
``__array_interface__`` objects, object arrays, float16 and longdouble,
``array.array``, memoryviews (big-endian too), lists of NumPy scalars, NumPy
scalar types, 0-d arrays, ``Fraction`` and ``Decimal``, and checks that the
call gives the plain value's answer bit for bit or refuses it as its policy
(``foreign_arrays.POLICY``) allows — never another exception, a changed input,
a result that shares the caller's buffer, or a new numba kernel specialisation.

The default run covers the callables whose defects the review fixed; the
``slow`` run a fixed quarter of the rest (every fourth spec by name: a few
minutes, within CI's time), and ``NAVKIT_FOREIGN_ALL=1`` every spec (about 18
minutes on two cores).
"""

from __future__ import annotations

import inspect
import os
import re
import shutil
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path

import foreign_arrays
import fuzz_specs  # noqa: F401 - registers the specs
import numpy as np
import pytest
from fuzz_engine import SPECS, Spec, call, quiet, refresh_memory_limit

pytestmark = pytest.mark.filterwarnings("ignore::PendingDeprecationWarning")

#: Answers that differ from the plain value's by design: (spec, problem pattern, why).
DOCUMENTED = [
    (
        "navkit.mapping.validate_costs",
        r"shares memory with the caller's buffer|\[1\]\[0\]\[3\]: False != True",
        "validate_costs returns its input itself (a view of it: read-only for a read-only "
        "memory map) when it already is C-contiguous float64, as documented",
    ),
]

#: The callables of the defects fixed in review 19 (and a few plain neighbours).
DEFAULT = [
    "navkit.geometry.as_pose",
    "navkit.geometry.rollout",
    "navkit.geometry.wrap_angle",
    "navkit.kinematics.tick_delta",
    "navkit.mapping.validate_costs",
    "navkit.planning.grid.astar",
    "navkit.sim.RangeNoise",
    "navkit.sim.World.clearance",
    "navkit.estimation.MeasurementLog.from_streams",
]


@pytest.fixture
def folder() -> Iterator[Path]:
    path = Path(tempfile.mkdtemp(prefix="navkit-foreign-"))
    try:
        yield path
    finally:
        foreign_arrays.close_maps()
        shutil.rmtree(path, ignore_errors=True)


def _undocumented(name: str, problems: list[str]) -> list[str]:
    return [
        p
        for p in problems
        if not any(name == spec and re.search(pattern, p) for spec, pattern, _ in DOCUMENTED)
    ]


def _check(name: str, folder: Path) -> None:
    refresh_memory_limit()
    with quiet():
        problems = _undocumented(name, foreign_arrays.check_spec(name, folder))
    assert not problems, f"{len(problems)} problem(s):\n  " + "\n  ".join(problems[:40])


@pytest.mark.parametrize("name", DEFAULT)
def test_foreign_array_types(name: str, folder: Path) -> None:
    _check(name, folder)


#: The rest of the catalogue the slow run covers (all with NAVKIT_FOREIGN_ALL=1).
THOROUGH = sorted(set(SPECS) - set(DEFAULT))
if os.environ.get("NAVKIT_FOREIGN_ALL") != "1":
    THOROUGH = THOROUGH[::4]


@pytest.mark.slow
@pytest.mark.parametrize("name", THOROUGH)
def test_foreign_array_types_thoroughly(name: str, folder: Path) -> None:
    _check(name, folder)


def test_the_defaults_are_specs() -> None:
    assert set(DEFAULT) <= set(SPECS)
    assert {spec for spec, _, _ in DOCUMENTED} <= set(SPECS)


# --------------------------------------------------------------------------- the checker itself


def _wrong_layouts(points: object) -> float:
    """Reads a big-endian array's bytes as native ones: the silent wrong answer."""
    arr = points if isinstance(points, np.ndarray) else np.asarray(points)
    if arr.dtype.byteorder == ">":
        arr = arr.view(arr.dtype.newbyteorder("="))
    return float(np.asarray(arr, dtype=float).sum())


def _keeps_masked_data(values: object) -> float:
    return float(np.asarray(values, dtype=float).sum())


def _writes(values: object) -> float:
    arr = values if isinstance(values, np.ndarray) else np.asarray(values)
    if arr.flags.writeable and arr.size:
        arr.flat[0] = 0.0
    return 1.0


@pytest.mark.parametrize(
    ("fn", "label", "problem"),
    [
        (_wrong_layouts, "big-endian", "a different answer"),
        (_keeps_masked_data, "masked, first entry masked", "accepted"),
        (_writes, "np.memmap mode 'r+'", "modified the caller's input"),
    ],
    ids=["big-endian misread", "masked data used", "memmap written"],
)
def test_the_checker_sees_broken_promises(
    fn: Callable[[object], float], label: str, problem: str, folder: Path
) -> None:
    spec = Spec("selftest", lambda c: call(fn, np.array([1.0, 2.0, 3.0])))
    variant = next(v for v in foreign_arrays.ARRAY_VARIANTS if v.label == label)
    name = next(iter(inspect.signature(fn).parameters))
    with quiet():
        found = foreign_arrays.check_variant(
            spec, (name,), np.array([1.0, 2.0, 3.0]), variant, folder
        )
    assert any(problem in p for p in found), found
