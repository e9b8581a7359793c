"""The EKF probe draws are the same bits on every x86-64 CPU (review 35).

test_review26_ekfx_exact_state.py's ``_draw`` (review 26's draw and the
reviewer's fuzz draw, whose outcome counts both review-26 files pin) was built
with NumPy's ``10.0 ** array`` and OpenBLAS's ``@``: without NumPy's AVX-512
loops (``NPY_DISABLE_CPU_FEATURES``, as on a CPU with AVX2 only) ``power``
rounded some draws an ulp apart, and the pinned counts failed there (one
rejected update fewer of each draw, and others). The draws are now built from
the generator's raw outputs with exactly rounded operations only
(tests/portable_random.py). Each probe here draws in a fresh process under one
choice of NumPy's SIMD level and OpenBLAS's kernel; all must agree.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from openblas_kernels import has_avx512
from portable_random import LOG2_10, gram, log_uniform, matvec, normals, quadratic
from subprocess_probe import probe_outcome

_TESTS = Path(__file__).resolve().parents[1]

_PROBE = """
import hashlib, json, sys
sys.path[:0] = sys.argv[1:3]
import numpy as np
from test_review26_ekfx_exact_state import _draw
digest = hashlib.sha256()
for kind in ("review", "fuzz"):
    for case in _draw(kind, int(sys.argv[3])):
        for part in case[:5]:
            digest.update(np.ascontiguousarray(part, dtype=np.float64).tobytes())
        digest.update(repr(case[5]).encode())
print(json.dumps(digest.hexdigest()))
"""

# NumPy 2.4's names of its dispatch targets above AVX2 (numpy.show_runtime()).
_NO_AVX512 = "AVX512_SPR AVX512_ICL X86_V4"


def _settings() -> dict[str, dict[str, str]]:
    settings = {
        "Haswell": {"OPENBLAS_CORETYPE": "Haswell"},
        "Sandybridge, NumPy without AVX2 or AVX-512": {
            "OPENBLAS_CORETYPE": "Sandybridge",
            "NPY_DISABLE_CPU_FEATURES": f"{_NO_AVX512} X86_V3",
        },
    }
    if has_avx512():
        settings["SkylakeX, NumPy without AVX-512"] = {
            "OPENBLAS_CORETYPE": "SkylakeX",
            "NPY_DISABLE_CPU_FEATURES": _NO_AVX512,
        }
        settings["SkylakeX"] = {"OPENBLAS_CORETYPE": "SkylakeX"}
    return settings


def test_the_probe_draws_are_the_same_under_every_simd_level_and_kernel(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # 400 updates of each draw. Before, against Haswell's kernel with NumPy's AVX-512
    # loops: 124 and 111 of them differed without those loops, 29 and 9 under SkylakeX's.
    digests = {}
    for label, env in _settings().items():
        monkeypatch.delenv("NPY_DISABLE_CPU_FEATURES", raising=False)
        for key, value in env.items():
            monkeypatch.setenv(key, value)
        digests[label] = probe_outcome(
            _PROBE, str(_TESTS), str(_TESTS / "estimation"), "400", timeout=300
        )
    assert len(set(digests.values())) == 1, json.dumps(digests, indent=1)


def test_the_portable_normals_have_the_normal_moments() -> None:
    x = normals(np.random.default_rng(35), 200_000)
    assert abs(float(np.mean(x))) < 0.01
    assert abs(float(np.var(x)) - 1.0) < 0.01
    assert float(x.min()) >= -6.0 and float(x.max()) <= 6.0
    assert abs(float(np.mean(np.abs(x) > 2.0)) - 0.0455) < 0.003  # normal 4.55 %, this 4.4 %


def test_log_uniform_spreads_magnitudes_evenly_in_log() -> None:
    v = log_uniform(np.random.default_rng(35), -40.0, -9.0, 100_000)
    assert isinstance(v, np.ndarray)
    assert float(v.min()) >= 1e-40 and float(v.max()) < 1.0615e-9
    decades = np.floor(np.log10(v)).astype(int)
    counts = np.bincount(decades + 40, minlength=32)
    # About 1/31 of the draws in each decade from 1e-40 to 1e-9, a few above 1e-9.
    assert np.all(np.abs(counts[:31] / len(v) - 1 / 31) < 0.004)
    assert counts[31] < 100 and len(counts) == 32
    one = log_uniform(np.random.default_rng(1), -6.0, 0.0)
    assert isinstance(one, float) and 1e-6 <= one < 1.0615
    # (1 + f) 2**e against 2**(e + f): the mantissa at most 6.15 % above.
    f = np.linspace(0.0, 1.0, 1001)
    ratio = (1.0 + f) / 2.0**f
    assert float(ratio.min()) == 1.0 and float(ratio.max()) < 1.0615
    assert abs(2.0**LOG2_10 - 10.0) < 1e-14


def test_the_ordered_products_are_the_exact_products_rounded_in_order() -> None:
    rng = np.random.default_rng(35)
    a = rng.normal(size=(4, 3))
    v = rng.normal(size=3)
    p = gram(a)
    np.testing.assert_array_equal(p, p.T)
    np.testing.assert_allclose(p, a @ a.T, rtol=1e-13, atol=1e-15)
    for i in range(4):
        assert matvec(a, v)[i] == (a[i, 0] * v[0] + a[i, 1] * v[1]) + a[i, 2] * v[2]
        for j in range(4):
            assert p[i, j] == (a[i, 0] * a[j, 0] + a[i, 1] * a[j, 1]) + a[i, 2] * a[j, 2]
    w = rng.normal(size=4)
    exact = math.fsum(float(w[i] * p[i, j] * w[j]) for i in range(4) for j in range(4))
    assert quadratic(w, p) == pytest.approx(exact, rel=1e-12, abs=1e-12)
