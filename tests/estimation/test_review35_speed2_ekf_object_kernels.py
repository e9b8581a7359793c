"""The general EKF's kernels take the user's arrays as objects and type them in C.

Issue 17 (a step at least 3 times filterpy's speed on any machine): the
public layer now calls each kernel's compiled entry directly, without numba's
dispatcher, and the kernel tests each user array in C
(``navkit._shared.array_objects.float_vector`` / ``float_matrix``), returning
``BAD_TYPE`` where the dispatcher used to raise. These tests pin that the C
test takes exactly what the dispatcher took (a 1-D or 2-D ndarray, exactly, of
native float64, C-contiguous, writeable: numba's ``Array(float64, ndim,
'C')``), with numba's own ``typeof`` as the oracle, for many spellings of an
array, except a misaligned one, which ``typeof`` types so too but whose loads
the type says aligned (review 47: refused, the public layer copies it); that
everything else is refused without an exception; and that the filter's
answers are the same bits whichever way an argument takes.
"""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from numba import typeof
from numba.core import types

from navkit.estimation import ExtendedKalmanFilter
from navkit.estimation import _ekf_kernels as kernels


class _Sub(np.ndarray):  # type: ignore[type-arg]
    pass


def _unaligned(a: Any, writeable: bool = True) -> np.ndarray:
    """``a``'s values in a C-contiguous float64 array at an odd address."""
    values = np.asarray(a, dtype=np.float64)
    buffer = bytearray(8 * values.size + 1)
    out = np.frombuffer(buffer, dtype=np.float64, count=values.size, offset=1)
    out = out.reshape(values.shape)
    out[...] = values
    assert not out.flags.aligned and out.flags.c_contiguous
    out.flags.writeable = writeable
    return out


def _read_only(a: np.ndarray) -> np.ndarray:
    out = a.copy()
    out.flags.writeable = False
    return out


def _spellings(a: np.ndarray) -> list[Any]:
    """The same values in many containers (some not arrays at all)."""
    big = np.zeros((2 * a.shape[0], *a.shape[1:]))
    big[::2] = a
    return [
        a.copy(),
        a.tolist(),
        tuple(a.tolist()),
        a.astype(np.float32),
        a.astype(">f8"),
        a.astype(np.int64),
        a.astype(np.complex128),
        _read_only(a),
        big[::2],
        np.asfortranarray(a),
        a.view(_Sub),
        np.ma.masked_array(a.copy()),
        a.reshape(1, -1),
        a[None],
        a.ravel() if a.ndim == 2 else a.reshape(-1, 1),
        _unaligned(a),
        _unaligned(a, writeable=False),
        np.float64(1.0),
        np.array(1.0),
        1.0,
        None,
        "1.0",
        object(),
        np.zeros((0,) * a.ndim),
    ]


def _dispatcher_took(obj: object, ndim: int) -> bool:
    """Whether numba's dispatcher typed ``obj`` as the kernels' compiled array type."""
    if type(obj) is not np.ndarray:  # the public layer sent subclasses the checked way
        return False
    try:
        return bool(typeof(obj) == types.Array(types.float64, ndim, "C"))
    except Exception:
        return False


@pytest.mark.parametrize("ndim", [1, 2])
def test_the_c_test_takes_exactly_what_the_dispatcher_took(ndim: int) -> None:
    n = 3
    state = kernels.new_state(np.zeros(n), np.eye(n), ())
    eye, x = np.eye(n), np.zeros(n)
    kernels.set_q(state, eye, eye)
    predict = kernels.predict_kernel(n)
    base = x if ndim == 1 else eye
    checked = 0
    for spelling in _spellings(base):
        typed = _dispatcher_took(spelling, ndim)
        took = typed and spelling.flags.aligned
        args = [x, eye, eye]
        args[0 if ndim == 1 else 1] = spelling
        before = state.copy()
        status = predict(state, *args)  # never raises, whatever the object
        if took:
            assert status != kernels.BAD_TYPE, type(spelling)
        else:
            assert status == kernels.BAD_TYPE, (type(spelling), spelling)
            np.testing.assert_array_equal(state, before)  # nothing written
        # The Python equivalent (NUMBA_DISABLE_JIT=1) agrees, but may take a
        # misaligned array: run as Python, the kernels read it through NumPy.
        assert kernels._float_view_python(spelling, ndim)[0] in {typed, took}
        checked += took
    # The copy, an empty array and an array of another shape that numba also types
    # as a C array; not the unaligned copy (numba's typeof does not look at alignment).
    assert checked == 3


def test_the_update_kernel_types_its_four_user_arrays() -> None:
    n, m = 2, 1
    state = kernels.new_state(np.zeros(n), np.eye(n), ())
    rbuf = kernels.new_rbuf(n, m)
    r = np.eye(m)
    kernels.set_r(rbuf, r, r)
    update = kernels.update_kernel(n, m)
    z, hx, h = np.ones(m), np.zeros(m), np.array([[1.0, 0.0]])
    good = [z, hx, h, r]
    for k in range(4):
        for spelling in (good[k].tolist(), good[k].astype(np.float32), _read_only(good[k])):
            args = list(good)
            args[k] = spelling
            before = (state.copy(), rbuf.copy())
            out = update(state, *args, rbuf, np.empty(m))
            assert out == -float(kernels.BAD_TYPE)
            np.testing.assert_array_equal(state, before[0])
            np.testing.assert_array_equal(rbuf, before[1])  # not even the NIS slot
    assert update(state, *good, rbuf, np.empty(m)) == pytest.approx(0.5)


def _model() -> tuple[Callable[[np.ndarray], np.ndarray], np.ndarray, np.ndarray]:
    jac = np.array([[1.0, 0.1, 0.0], [0.0, 1.0, 0.1], [0.0, 0.0, 1.0]])
    return (lambda x: jac @ x), jac, np.diag([0.01, 0.02, 0.03])


def _steps(spell: Callable[[np.ndarray], Any]) -> tuple[bytes, bytes, list[bytes]]:
    f, jac, q = _model()
    h = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    r = np.diag([0.05, 0.01])
    ekf = ExtendedKalmanFilter([0.1, 0.4, -3.0], np.diag([1.0, 2.0, 0.5]), angle_states=(2,))
    residuals = []
    for k in range(6):
        z = np.array([0.2 * k, 3.1 - 0.5 * k])
        ekf.predict(lambda x: spell(f(x)), spell(jac), spell(q))
        result = ekf.update(
            spell(z), lambda x: spell(h @ x), spell(h), spell(r), angle_measurements=(1,)
        )
        assert result.accepted
        residuals.append(result.residual.tobytes() + np.float64(result.nis).tobytes())
    return ekf.x.tobytes(), ekf.P.tobytes(), residuals


@pytest.mark.parametrize(
    "spell",
    [
        lambda a: np.asarray(a).tolist(),
        lambda a: np.asarray(a, dtype=">f8"),
        _read_only,
        lambda a: np.asfortranarray(a),
        _unaligned,
        lambda a: np.ma.masked_array(a),
    ],
)
def test_every_spelling_gives_the_same_bits(spell: Callable[[np.ndarray], Any]) -> None:
    assert _steps(spell) == _steps(lambda a: a)


def test_bad_input_in_any_spelling_raises_as_before() -> None:
    f, jac, q = _model()
    for spell in (lambda a: a, lambda a: np.asarray(a).tolist(), _read_only):
        ekf = ExtendedKalmanFilter(np.zeros(3), np.eye(3))
        bad = jac.copy()
        bad[1, 2] = np.nan
        with pytest.raises(ValueError, match=r"^F must contain only finite values$"):
            ekf.predict(f, spell(bad), spell(q))
        with pytest.raises(ValueError, match=r"^z must"):
            ekf.update(spell(np.array([[1.0]])), lambda x: x[:1], np.eye(1, 3), [[1.0]])
        np.testing.assert_array_equal(ekf.x, np.zeros(3))


_OTHER_NUMPY = """
import numba  # noqa: F401  (numba itself refuses a NumPy 3: loaded before the change)
import numpy as np
np.__version__ = "3.0.0"
from navkit._shared import array_objects
from navkit.estimation import ExtendedKalmanFilter
jac = np.array([[1.0, 0.1], [0.0, 1.0]])
h = np.array([[1.0, 0.0]])
spells = (lambda a: a, lambda a: np.asarray(a).tolist(), np.ma.masked_array)
out = [str(array_objects.LAYOUT_OK)]
for spell in spells:
    ekf = ExtendedKalmanFilter([0.1, 3.0], np.eye(2), angle_states=(1,))
    for k in range(5):
        ekf.predict(lambda x: spell(jac @ x), spell(jac), spell(0.01 * np.eye(2)))
        r = ekf.update(spell(np.array([0.3 * k])), lambda x: spell(x[:1]), spell(h),
                       spell(np.array([[0.1]])))
        out.append(r.residual.tobytes().hex() + np.float64(r.nis).tobytes().hex())
    out.append(ekf.x.tobytes().hex() + ekf.P.tobytes().hex())
    try:
        ekf.predict(lambda x: x, spell(np.array([[1.0, np.nan], [0.0, 1.0]])), np.eye(2))
    except ValueError as error:
        out.append(str(error))
print(chr(10).join(out))
"""


def test_under_another_numpy_major_the_filter_answers_the_same() -> None:
    """Where the C test cannot read NumPy's structs, the kernels are typed by numba's
    dispatcher as before: the same bits and errors (the first version raised FilterError
    at every step there: every array refused, even the converted ones)."""
    jac = np.array([[1.0, 0.1], [0.0, 1.0]])
    h = np.array([[1.0, 0.0]])
    expected = ["False"]
    spells = (lambda a: a, lambda a: np.asarray(a).tolist(), np.ma.masked_array)
    for spell in spells:
        ekf = ExtendedKalmanFilter([0.1, 3.0], np.eye(2), angle_states=(1,))
        for k in range(5):
            ekf.predict(lambda x, s=spell: s(jac @ x), spell(jac), spell(0.01 * np.eye(2)))
            r = ekf.update(spell(np.array([0.3 * k])), lambda x, s=spell: s(x[:1]), spell(h),
                           spell(np.array([[0.1]])))  # fmt: skip
            expected.append(r.residual.tobytes().hex() + np.float64(r.nis).tobytes().hex())
        expected.append(ekf.x.tobytes().hex() + ekf.P.tobytes().hex())
        expected.append("F must contain only finite values")
    # The default cache: there the kernels are compiled for other signatures (arrays,
    # not objects), which a process under NumPy 2 never asks for.
    env = dict(os.environ)
    env.pop("NUMBA_DISABLE_JIT", None)
    done = subprocess.run(
        [sys.executable, "-c", _OTHER_NUMPY], env=env, capture_output=True, text=True,
        check=False,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout.splitlines() == expected
