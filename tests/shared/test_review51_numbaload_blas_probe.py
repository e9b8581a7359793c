"""Loading numba does not import SciPy's linear algebra for numba's BLAS probe (review 51).

numba's ``numba.np.arraymath`` probes for a BLAS at its import (importing
``scipy.linalg.cython_blas``, so all of ``scipy.linalg`` and, through SciPy's
array-API shim, ``numpy.f2py``): 0.15-0.16 s of the 0.6 s navkit's first kernel
call spent loading numba (issue 17). navkit defers the probe until numba reads
its answer (``jit._blas_probe_deferred``). Each check runs in a fresh process,
where numba's implementations are not imported yet.
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from subprocess_probe import jit_outcome, probe_outcome


def test_loading_numba_imports_neither_scipy_linalg_nor_f2py() -> None:
    out = jit_outcome(
        """
import json, sys
import numpy as np
from navkit._shared.jit import load_numba
from navkit.planning import astar
load_numba()
import numba.np.arraymath as arraymath
import numba.np.linalg as linalg
loaded = ["scipy.linalg" in sys.modules, "numpy.f2py" in sys.modules]
path = astar(np.ones((6, 6)), (0, 0), (5, 5))
print(json.dumps({
    "after_load": loaded,
    "after_astar": "scipy.linalg" in sys.modules,
    "restored": arraymath.ensure_blas is linalg.ensure_blas,
    "restored_module": linalg.ensure_blas.__module__,
    "probe": type(arraymath._HAVE_BLAS).__name__,
    "cells": len(path.cells),
}))
""",
        disable_jit=False,
    )
    assert out == {
        "after_load": [False, False],
        "after_astar": False,
        "restored": True,
        "restored_module": "numba.np.linalg",
        "probe": "_BlasProbe",
        "cells": 6,
    }


_USER_KERNEL = """
import json, sys
import numpy as np
from navkit._shared.jit import load_numba
load_numba()
import numba
import numba.np.arraymath as arraymath

@numba.njit
def both(a, b):
    return np.correlate(a, b), np.convolve(a, b)

a, b = np.array([0.5, 1.0, -2.0, 3.0, 4.25]), np.array([1.0, -2.0, 0.25])
ints = (np.arange(5), np.array([1, 2]))
got = [both(a, b), both(*ints)]
want = [(np.correlate(a, b), np.convolve(a, b)), (np.correlate(*ints), np.convolve(*ints))]
print(json.dumps({
    "same": all(np.array_equal(g, w) for gs, ws in zip(got, want) for g, w in zip(gs, ws)),
    "answer": bool(arraymath._HAVE_BLAS),
    "numbas": arraymath._check_blas(),
    "scipy_linalg": "scipy.linalg" in sys.modules,
}))
"""


def test_users_kernels_get_numbas_blas_answer_when_numba_asks() -> None:
    # np.correlate and np.convolve of floats are where numba reads the answer
    # (then calling np.dot through SciPy's BLAS): the same results as NumPy's.
    out = jit_outcome(_USER_KERNEL, disable_jit=False)
    assert out == {"same": True, "answer": True, "numbas": True, "scipy_linalg": True}


def test_users_kernels_as_python_with_the_jit_disabled() -> None:
    out = jit_outcome(_USER_KERNEL, disable_jit=True)
    assert out["same"] is True
    assert out["answer"] is out["numbas"] is True


#: A stand-in for numba's arraymath, made inside the deferral (``{answer}``: where
#: the module keeps the probe's answer).
_DEFERRAL = """
import json, sys, types
from navkit._shared import jit
import numba.np.linalg as linalg
numbas = linalg.ensure_blas
SOURCE = '''
from numba.np.linalg import ensure_blas
def _check_blas():
    try:
        ensure_blas()
    except ImportError:
        return False
    return True
{answer} = _check_blas()
'''
def fake_arraymath():
    module = types.ModuleType("numba.np.arraymath")
    sys.modules[module.__name__] = module
    exec(compile(SOURCE, "<arraymath>", "exec"), vars(module))
    return module
"""


def test_the_one_probe_at_arraymaths_import_waits_for_its_first_read() -> None:
    out = probe_outcome(
        _DEFERRAL.replace("{answer}", "_HAVE_BLAS")
        + """
with jit._blas_probe_deferred():
    module = fake_arraymath()
    inside = "scipy.linalg" in sys.modules
after = ["scipy.linalg" in sys.modules, type(module._HAVE_BLAS).__name__]
restored = [linalg.ensure_blas is numbas, module.ensure_blas is numbas]
answer = bool(module._HAVE_BLAS)
print(json.dumps([inside, after, restored, answer, "scipy.linalg" in sys.modules]))
"""
    )
    assert out == [False, [False, "_BlasProbe"], [True, True], True, True]


def test_any_other_call_during_the_deferral_probes_as_numba_does() -> None:
    out = probe_outcome(
        _DEFERRAL.replace("{answer}", "_HAVE_BLAS")
        + """
def someone_else():
    linalg.ensure_blas()
with jit._blas_probe_deferred():
    someone_else()
    inside = "scipy.linalg" in sys.modules
print(json.dumps([inside, linalg.ensure_blas is numbas]))
"""
    )
    assert out == [True, True]


def test_an_answer_kept_elsewhere_is_probed_at_once() -> None:
    # A numba that keeps the answer under another name: what it stored is the
    # deferred "yes", so the real probe runs as the import ends (and would
    # raise, as numba's own import would have).
    out = probe_outcome(
        _DEFERRAL.replace("{answer}", "BLAS_FOUND")
        + """
with jit._blas_probe_deferred():
    module = fake_arraymath()
    inside = "scipy.linalg" in sys.modules
print(json.dumps([inside, "scipy.linalg" in sys.modules, module.BLAS_FOUND,
                  module.ensure_blas is numbas, linalg.ensure_blas is numbas]))
"""
    )
    assert out == [False, True, True, True, True]


def test_a_failed_import_or_a_numba_without_the_probe_is_left_as_it_was() -> None:
    out = probe_outcome(
        _DEFERRAL.replace("{answer}", "_HAVE_BLAS")
        + """
try:
    with jit._blas_probe_deferred():
        raise ImportError("numba's implementations failed to import")
except ImportError:
    pass
restored = linalg.ensure_blas is numbas
del linalg.ensure_blas
with jit._blas_probe_deferred():  # nothing to defer
    pass
missing = hasattr(linalg, "ensure_blas")
linalg.ensure_blas = numbas
sys.modules["numba.np.arraymath"] = types.ModuleType("numba.np.arraymath")
with jit._blas_probe_deferred():  # imported already: nothing to defer
    same = linalg.ensure_blas is numbas
print(json.dumps([restored, missing, same, "scipy.linalg" in sys.modules]))
"""
    )
    assert out == [True, False, True, False]
