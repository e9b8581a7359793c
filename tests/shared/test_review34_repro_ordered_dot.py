"""``ordered_dot``: short dot products with the same bits on every CPU (review 34).

``np.dot`` of two short vectors is OpenBLAS's ``ddot``, whose kernel is chosen
for the CPU: the AVX2-era kernels (Haswell, Zen, Sandy Bridge, Nehalem) add up
to 15 rounded products in order, the AVX-512 ones (SkylakeX, Cooper Lake,
Sapphire Rapids) fuse multiplies and adds and add in another order, so a norm or
a speed limit differed in its last bit on a recent Xeon. ``ordered_dot`` adds in
order everywhere: checked here against exact rational arithmetic (each product
and each sum rounded once) and, in fresh processes, against ``np.dot`` under each
OpenBLAS kernel this CPU can run.
"""

from __future__ import annotations

import json
from fractions import Fraction

import numpy as np
import pytest

from navkit._shared.products import ORDERED_MAX, ordered_dot
from openblas_kernels import core_types
from subprocess_probe import probe_outcome


def _in_order(a: np.ndarray, b: np.ndarray) -> float:
    # The oracle: each product rounded to float64 once, then each running sum.
    total = 0.0
    for x, y in zip(a.tolist(), b.tolist(), strict=True):
        total = float(Fraction(total) + Fraction(float(Fraction(x) * Fraction(y))))
    return total


def _vectors(n: int, count: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    scale = 10.0 ** rng.integers(-3, 4, size=(count, 1))
    return rng.normal(size=(count, n)) * scale, rng.normal(size=(count, n))


@pytest.mark.parametrize("n", range(1, ORDERED_MAX + 1))
def test_the_products_are_added_in_order(n: int) -> None:
    a, b = _vectors(n, 300, n)
    got = np.array([ordered_dot(x, y) for x, y in zip(a, b, strict=True)])
    want = np.array([_in_order(x, y) for x, y in zip(a, b, strict=True)])
    np.testing.assert_array_equal(got, want)


def test_cancelling_products_give_exactly_zero() -> None:
    # Two rounded products of opposite sign cancel exactly; a fused multiply-add
    # keeps the first product's rounding error (what turned 0 into 1e-17).
    x = np.array([0.1, 0.1])
    y = np.array([0.7, -0.7])
    assert ordered_dot(x, y) == 0.0
    assert ordered_dot(np.array([1.0 / 3.0, 1.0 / 3.0]), np.array([3.0, -3.0])) == 0.0


def test_longer_vectors_are_np_dot() -> None:
    a, b = _vectors(ORDERED_MAX + 1, 50, 99)
    for x, y in zip(a, b, strict=True):
        assert ordered_dot(x, y) == float(np.dot(x, y))


def test_overflow_is_inf_without_warning_under_any_errstate() -> None:
    big = np.array([1e200, 1e200])
    with np.errstate(all="raise"):
        assert ordered_dot(big, big) == np.inf
        assert ordered_dot(np.array([1e-200, 1e-200]), np.array([1e-200, 1e-200])) == 0.0


_PROBE = """
import hashlib, json
import numpy as np
from navkit._shared.products import ordered_dot
rng = np.random.default_rng(5)
same = {}
mine = []
for n in range(1, 16):
    a = rng.normal(size=(400, n)) * 10.0 ** rng.integers(-3, 4, size=(400, 1))
    b = rng.normal(size=(400, n))
    ours = [ordered_dot(x, y) for x, y in zip(a, b, strict=True)]
    same[n] = all(o == float(np.dot(x, y)) for o, x, y in zip(ours, a, b))
    mine.append(np.array(ours))
digest = hashlib.sha256(np.concatenate(mine).tobytes()).hexdigest()
print(json.dumps({"digest": digest, "blas_in_order": all(same.values())}))
"""


@pytest.mark.slow
def test_the_same_bits_under_every_openblas_kernel(monkeypatch: pytest.MonkeyPatch) -> None:
    outcomes = {}
    for core in core_types(("Haswell", "Sandybridge", "Nehalem"), ("SkylakeX", "SapphireRapids")):
        monkeypatch.setenv("OPENBLAS_CORETYPE", core)
        outcomes[core] = probe_outcome(_PROBE)
    assert len({o["digest"] for o in outcomes.values()}) == 1, json.dumps(outcomes)
    # The documented figures' kernels add in order: ordered_dot keeps their bits.
    for core in ("Haswell", "Sandybridge", "Nehalem"):
        assert outcomes[core]["blas_in_order"], core
