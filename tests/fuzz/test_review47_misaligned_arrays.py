"""Arrays in misaligned buffers reach navkit's kernels as aligned copies (review 47).

numba types a misaligned NumPy array (a float64 view of bytes at an odd
offset, a float64 field of a packed structured array) as an *aligned* one
(``numba.typeof`` does not look at the alignment flag), and LLVM then
assumes its loads aligned: undefined behaviour, harmless on x86-64 and
AArch64 only because they execute such loads as unaligned ones. Review 46
fixed the grid planners' converter; this property covers every fuzz spec:
each array argument (of a spec's call tree: a constructor's too) given as a
misaligned copy must give the aligned value's answer bit for bit, leave the
input as it was, and no numba dispatcher may receive a misaligned array
during the call (:func:`watching_kernels` sees every Python call of a
dispatcher, whatever module it was imported into).

The default run covers the specs whose paths the review fixed and one or
two of each other layer; the ``slow`` run every spec (about 2 minutes on one
core). The compiled entries that skip numba's dispatcher (the general EKF's,
typing the user's arrays in C) are checked by their own tests below.
"""

from __future__ import annotations

import contextlib
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import foreign_arrays
import fuzz_specs  # noqa: F401 - registers the specs
import numpy as np
import pytest
from fuzz_engine import SKIP, SPECS, Array, Ctx, PoseLike, quiet, refresh_memory_limit, slots

from misaligned_arrays import misaligned
from navkit._shared.costs import validate_costs
from navkit._shared.validation import aligned, as_float_array, as_points, kernel_input
from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation._ekf_kernels import (
    _FAIL_TYPE,
    BAD_TYPE,
    OK,
    new_rbuf,
    predict_kernel,
    update_kernel,
)

pytestmark = pytest.mark.filterwarnings("ignore::PendingDeprecationWarning")


def packed_field(a: np.ndarray) -> np.ndarray:
    """A copy of ``a`` as the field of a packed structured array (strides not multiples of 8)."""
    record = np.zeros(a.shape, dtype=np.dtype([("pad", "u1"), ("value", a.dtype)]))
    record["value"] = a
    out = record["value"]
    assert out.size == 0 or not out.flags.aligned
    return out


def _variant(label: str, make: Any) -> foreign_arrays.Variant:
    def fn(a: np.ndarray, _folder: Path) -> Any:
        if a.dtype.itemsize == 1 or a.size == 0:
            return SKIP  # always aligned
        return make(a)

    return foreign_arrays._array_variant(label, fn)


VARIANTS = [
    _variant("misaligned, writeable", misaligned),
    _variant("misaligned, read-only", lambda a: misaligned(a, writeable=False)),
    _variant("packed structured field", packed_field),
]


def _misaligned_in(value: Any, depth: int = 0) -> Iterator[str]:
    if isinstance(value, np.ndarray):
        if value.size and not value.flags.aligned:
            yield f"{value.dtype}{list(value.shape)} strides {value.strides}"
    elif isinstance(value, (tuple, list)) and depth < 3:
        for item in value:
            yield from _misaligned_in(item, depth + 1)


@contextlib.contextmanager
def watching_kernels() -> Iterator[list[str]]:
    """Every misaligned array passed to a numba dispatcher from Python, while in the block.

    ``Dispatcher.__call__`` is numba's C ``tp_call``; a Python ``__call__`` set
    on numba's ``Dispatcher`` class takes its place for every dispatcher
    (CPython updates the slot of the class and its subclasses) and is removed
    after the block. Kernels calling kernels inside compiled code do not go
    through it: only what the public layers hand over.
    """
    from numba import _dispatcher
    from numba.core.dispatcher import Dispatcher

    assert "__call__" not in vars(Dispatcher)
    c_call = _dispatcher.Dispatcher.__call__
    seen: list[str] = []

    def call(self: Any, *args: Any, **kwargs: Any) -> Any:
        for i, arg in enumerate((*args, *kwargs.values())):
            for what in _misaligned_in(arg):
                name = f"{self.py_func.__module__}.{self.py_func.__qualname__}"
                seen.append(f"{name} argument {i}: {what}")
        return c_call(self, *args, **kwargs)

    Dispatcher.__call__ = call  # type: ignore[method-assign]
    try:
        yield seen
    finally:
        del Dispatcher.__call__


def check_spec(name: str, folder: Path) -> list[str]:
    spec = SPECS[name]
    tree = spec.make(Ctx(folder))
    problems: list[str] = []
    for slot, kind, value, _nested in slots(tree):
        if not isinstance(kind, (Array, PoseLike)):
            continue
        for variant in VARIANTS:
            with watching_kernels() as seen:
                problems += foreign_arrays.check_variant(spec, slot.path, value, variant, folder)
            where = f"{name}: {'.'.join(slot.path)} = {variant.label}"
            problems += [f"{where}: a kernel received a misaligned array: {s}" for s in seen]
    return problems


@pytest.fixture
def folder() -> Iterator[Path]:
    path = Path(tempfile.mkdtemp(prefix="navkit-misaligned-"))
    try:
        yield path
    finally:
        foreign_arrays.close_maps()
        shutil.rmtree(path, ignore_errors=True)


def _check(name: str, folder: Path) -> None:
    refresh_memory_limit()
    with quiet():
        problems = check_spec(name, folder)
    assert not problems, f"{len(problems)} problem(s):\n  " + "\n  ".join(problems[:40])


#: The paths fixed in review 47 (the first four), review 46's, and neighbours of each layer.
DEFAULT = [
    "navkit.geometry.rollout",
    "navkit.mapping.validate_costs",
    "navkit.sim.Simulation.run",
    "navkit.sim.World.raycast",
    "navkit.planning.grid.astar",
    "navkit.mapping.OccupancyGrid.world_to_cell",
    "navkit.kinematics.DiffDrive.forward_batch",
    "navkit.estimation.ExtendedKalmanFilter.predict",
    "navkit.planning.reactive.repulsive_force_from_scan",
]


def test_the_defaults_are_specs() -> None:
    assert set(DEFAULT) <= set(SPECS)


@pytest.mark.parametrize("name", DEFAULT)
def test_misaligned_arrays(name: str, folder: Path) -> None:
    _check(name, folder)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(set(SPECS) - set(DEFAULT)))
def test_misaligned_arrays_thoroughly(name: str, folder: Path) -> None:
    _check(name, folder)


# --------------------------------------------------------------------------- the checker itself


def test_the_watch_sees_a_misaligned_array_handed_to_a_dispatcher() -> None:
    numba = pytest.importorskip("numba")

    @numba.njit(cache=False)
    def first(values: np.ndarray) -> float:
        return float(values[0])

    odd = misaligned(np.array([1.5, 2.5]))
    with watching_kernels() as seen:
        assert first(np.array([1.5, 2.5])) == 1.5
        assert seen == []
        assert first(odd) == 1.5
    assert len(seen) == 1 and "argument 0: float64[2]" in seen[0]
    assert first(odd) == 1.5  # numba's own call again, after the block


# --------------------------------------------------------------------------- the shared rule


@pytest.mark.parametrize("make", [misaligned, packed_field], ids=["offset", "packed"])
@pytest.mark.parametrize("writeable", [True, False])
def test_the_shared_converters_copy_misaligned_buffers_only(make: Any, writeable: bool) -> None:
    values = np.array([[1.0, 2.5], [3.0, np.inf]])
    odd = make(values)
    odd.flags.writeable = writeable
    before = odd.copy()
    for got in (
        aligned(odd),
        kernel_input(odd),
        as_float_array(odd, "values", finite=False),
        as_points(odd, "points", finite=False),
        validate_costs(odd),
    ):
        assert got.flags.aligned and got.flags.c_contiguous
        assert not np.shares_memory(got, odd)
        np.testing.assert_array_equal(got, values)
    np.testing.assert_array_equal(odd, before)  # the input is not modified
    plain = values.copy()
    assert aligned(plain) is plain
    assert kernel_input(plain) is plain
    assert as_float_array(plain, "values", finite=False) is plain
    assert validate_costs(plain) is plain


def test_a_misaligned_integer_array_converts_as_its_values() -> None:
    cells = np.array([[1, 2], [3, 4]], dtype=np.int64)
    got = as_float_array(misaligned(cells), "cells")
    assert got.flags.aligned
    np.testing.assert_array_equal(got, cells)
    assert aligned(misaligned(cells)).dtype == np.int64


# --------------------------------------------------------------------------- the EKF's entries


def _ekf_steps(wrap: Any) -> tuple[np.ndarray, np.ndarray, float]:
    ekf = ExtendedKalmanFilter(np.array([1.0, 2.0]), np.array([[0.5, 0.1], [0.1, 0.4]]))
    jac = np.array([[1.0, 0.1], [0.0, 1.0]])
    ekf.predict(lambda x: wrap(jac @ x), lambda x: wrap(jac), wrap(0.01 * np.eye(2)))
    result = ekf.update(
        wrap(np.array([1.3])),
        lambda x: wrap(np.array([x[0] + 0.1 * x[1]])),
        lambda x: wrap(np.array([[1.0, 0.1]])),
        wrap(np.array([[0.04]])),
    )
    return ekf.x.copy(), ekf.P.copy(), result.nis


def test_ekf_steps_on_misaligned_arrays_are_those_on_aligned_ones() -> None:
    want = _ekf_steps(lambda a: a)
    for make in (misaligned, packed_field):
        got = _ekf_steps(make)
        np.testing.assert_array_equal(got[0], want[0])
        np.testing.assert_array_equal(got[1], want[1])
        assert got[2] == want[2]


def test_the_ekf_entries_refuse_misaligned_arrays() -> None:
    """The entries type the user's arrays in C (``float_vector``, ``float_matrix``):
    a misaligned one is refused (BAD_TYPE) and the public layer copies it."""
    ekf = ExtendedKalmanFilter(np.zeros(2), np.eye(2))
    state = ekf._state
    fx, jac, q = np.zeros(2), np.eye(2), 0.01 * np.eye(2)
    predict = predict_kernel(2)
    assert predict(state.copy(), fx, jac, q) == OK
    for i in range(3):
        args = [fx, jac, q]
        args[i] = misaligned(args[i])
        assert predict(state.copy(), *args) == BAD_TYPE, f"argument {i + 1}"
    update = update_kernel(2, 1)
    z, hx, h_jac, r = np.array([0.1]), np.array([0.0]), np.array([[1.0, 0.0]]), np.array([[0.04]])
    assert update(state.copy(), z, hx, h_jac, r, new_rbuf(2, 1), np.empty(1)) >= 0.0
    for i in range(4):
        args = [z, hx, h_jac, r]
        args[i] = misaligned(args[i])
        out = update(state.copy(), *args, new_rbuf(2, 1), np.empty(1))
        assert out == _FAIL_TYPE, f"argument {i + 1}"
