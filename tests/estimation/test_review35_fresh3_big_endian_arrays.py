"""The general EKF reads a big-endian array's values, whatever came before (session 39).

numba's dispatcher keys the arrays it types in C partly by a fingerprint that
leaves out the byte order: once any dispatcher in the process has typed an
unaligned float64 array, a big-endian (``>f8``) array of the same ndim and
layout is typed as native float64 and its bytes are read swapped. The EKF
called its kernels through the dispatcher until this session, so a model
whose F, f(x), z, h(x), H or R came big-endian (data read from a file of a
big-endian machine) after any unaligned array silently ran on values like
1e-319 or 6e213. Its kernels now type the user's arrays in C themselves,
where the byte order is looked at (``navkit._shared.array_objects``), and the
fallback used where NumPy's structs are not known (another NumPy major: the
dispatcher behind Python's tests) refuses non-native arrays too, so that the
checked way converts them. Each test fails on the code before its fix.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from typing import Any

import numpy as np
import pytest

from navkit._shared.jit import jit_disabled
from navkit.estimation import ExtendedKalmanFilter

_SCRIPT = textwrap.dedent(
    """
    import numpy as np
    from navkit.estimation import ExtendedKalmanFilter

    F = np.array([[1.0, 0.1], [0.0, 1.0]])
    H = np.array([[1.0, 0.0]])


    def unaligned(a):
        values = np.asarray(a, dtype=np.float64)
        buffer = bytearray(8 * values.size + 1)
        out = np.frombuffer(buffer, np.float64, count=values.size, offset=1)
        out = out.reshape(values.shape)
        out[...] = values
        return out


    def steps(spell, slot):
        ekf = ExtendedKalmanFilter([0.1, 0.4], np.diag([1.0, 2.0]))
        out = []
        for k in range(3):
            pick = {s: (spell if s == slot else (lambda a: a)) for s in
                    ("fx", "F", "Q", "z", "hx", "H", "R")}
            ekf.predict(lambda x: pick["fx"](F @ x), pick["F"](F),
                        pick["Q"](np.diag([0.01, 0.02])))
            result = ekf.update(pick["z"](np.array([0.3 * k + 0.1])),
                                lambda x: pick["hx"](H @ x), pick["H"](H),
                                pick["R"](np.array([[0.05]])))
            out.append(result.residual.tobytes().hex() + float(result.nis).hex())
            out.append(ekf.x.tobytes().hex() + ekf.P.tobytes().hex())
        return out


    # Unaligned arrays of each ndim first: they fill numba's fingerprint cache.
    for slot in ("fx", "F"):
        steps(unaligned, slot)
    wrong = []
    for slot in ("fx", "F", "Q", "z", "hx", "H", "R"):
        try:
            if steps(lambda a: np.asarray(a, dtype=">f8"), slot) != steps(lambda a: a, slot):
                wrong.append(slot)
        except Exception as error:  # before: a numba TypingError for a big-endian Q
            wrong.append(slot + ":" + type(error).__name__)
    print(" ".join(wrong) or "none")
    """
)


def _run(prefix: str = "") -> str:
    env = dict(os.environ)
    env.pop("NUMBA_DISABLE_JIT", None)
    done = subprocess.run(
        [sys.executable, "-c", prefix + _SCRIPT], env=env, capture_output=True, text=True,
        check=False,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout.strip()


@pytest.mark.skipif(jit_disabled(), reason="NUMBA_DISABLE_JIT=1: no dispatcher")
def test_numba_dispatch_misreads_big_endian_after_unaligned() -> None:
    """The numba behaviour this file guards against (if a numba release fixes it,
    this test says so; the EKF's tests below stay)."""
    import numba

    @numba.njit(cache=False)
    def first(a: Any) -> Any:
        return a[0]

    buffer = bytearray(17)
    unaligned = np.frombuffer(buffer, np.float64, count=2, offset=1)
    unaligned[:] = [1.5, 2.0]
    first(unaligned)
    try:
        got = first(np.array([1.5, 2.0], dtype=">f8"))
    except Exception:  # a numba that refuses non-native arrays as it should
        return
    assert got != 1.5  # read with its bytes swapped


def test_big_endian_arrays_after_unaligned_ones_give_the_native_bits() -> None:
    """In a fresh process (numba's cache of fingerprints is per process): every
    argument the user gives or a model returns, big-endian, after unaligned arrays."""
    assert _run() == "none"


def test_the_dispatcher_fallback_refuses_big_endian_arrays() -> None:
    """The same under another NumPy major (the C test stands aside: the kernels are
    typed by numba's dispatcher behind Python's tests, which now look at the byte
    order)."""
    prefix = "import numba\nimport numpy as np\nnp.__version__ = '3.0.0'\n"
    prefix += "from navkit._shared import array_objects\nassert not array_objects.LAYOUT_OK\n"
    assert _run(prefix) == "none"


def test_in_this_process_too() -> None:
    """The public steps with big-endian arrays, after an unaligned one, in-process."""
    jac = np.array([[1.0, 0.1], [0.0, 1.0]])
    buffer = bytearray(8 * 4 + 1)
    unaligned = np.frombuffer(buffer, np.float64, count=4, offset=1).reshape(2, 2)
    unaligned[...] = jac
    results = []
    for spell in (lambda a: a, lambda a: np.asarray(a, dtype=">f8")):
        ekf = ExtendedKalmanFilter([0.1, 0.4], np.eye(2))
        ekf.predict(lambda x: jac @ x, unaligned, 0.01 * np.eye(2))
        ekf.predict(lambda x, s=spell: s(jac @ x), spell(jac), spell(0.01 * np.eye(2)))
        ekf.update(spell(np.array([0.5])), lambda x, s=spell: s(x[:1]), spell(np.eye(1, 2)),
                   spell(np.array([[0.1]])))  # fmt: skip
        results.append(ekf.x.tobytes() + ekf.P.tobytes())
    assert results[0] == results[1]
