"""numba's deferred BLAS probe: asked once, shown as it is, numba's call only (review 52, MUTANT32).

``jit._BlasProbe`` stands for ``numba.np.arraymath._HAVE_BLAS`` until numba
reads it, and ``jit._blas_probe_deferred`` defers only the call that numba's
``arraymath._check_blas`` makes as it is imported. The mutation review found
no test that the probe asks once (a probe asking at every read passed), of
its ``repr`` before and after, nor that a function of that name elsewhere
is probed as numba probes (an ``or`` for the ``and`` of the check passed).
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from navkit._shared.jit import _BlasProbe
from subprocess_probe import probe_outcome


def test_the_probe_asks_once_and_shows_its_answer() -> None:
    asked: list[int] = []

    def check() -> bool:
        asked.append(1)
        return len(asked) == 1  # a second question would get another answer

    probe = _BlasProbe(check)
    assert repr(probe) == "<numba BLAS probe: not asked yet>"
    assert asked == []
    assert bool(probe) is True
    assert probe
    assert bool(probe) is True
    assert asked == [1]
    assert repr(probe) == "True"
    assert repr(_BlasProbe(lambda: 0)) == "<numba BLAS probe: not asked yet>"
    none = _BlasProbe(lambda: 0)
    assert not none
    assert repr(none) == "False"


def test_a_check_blas_of_another_module_is_probed_as_numba_probes() -> None:
    # Only numba.np.arraymath's _check_blas is deferred: a function of the same name
    # elsewhere calling ensure_blas during the deferral gets numba's own probe.
    out = probe_outcome(
        """
import json, sys
from navkit._shared import jit
import numba.np.linalg as linalg
numbas = linalg.ensure_blas
def _check_blas():
    linalg.ensure_blas()
with jit._blas_probe_deferred():
    _check_blas()
    inside = "scipy.linalg" in sys.modules
print(json.dumps([inside, linalg.ensure_blas is numbas]))
"""
    )
    assert out == [True, True]
