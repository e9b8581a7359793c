"""Shared fixtures: the real-data folder beside the repository; hypothesis's profile."""

from __future__ import annotations

import os
from pathlib import Path

# Before NumPy loads OpenBLAS (it reads this once): the kernels of CPUs with AVX2
# and FMA, whatever this CPU's newest are. OpenBLAS picks its matrix-product
# kernels for the CPU, and they differ in the last bits (their order of sums and
# fused multiply-adds): the tests' random draws built with ``@`` (covariances
# ``a @ a.T``, measurements ``h @ x``) differed on an AVX-512 Xeon, and so did the
# outcome counts pinned over thousands of them (review 34). Those draws are now
# the same bits under every kernel and SIMD level (tests/portable_random.py,
# review 35), but the EKF's exact fallbacks use LAPACK, whose verdicts at the
# boundary of positive definiteness depend on the kernel (the simulation guide's
# "Reproducibility across machines"): under the AVX-512 kernels the counts of
# test_review26_ekfp_exact_covariance.py's probe draws (one P of each) and of
# test_review27_ekf_joseph_doubt.py's slow 18,000-update harness (13,696 applied
# for 13,702) differ, so they are pinned under these. Tests of navkit's own results under
# each kernel set the variable themselves
# (tests/sim/test_review34_lead_repro_fusion_odometry.py).
if "OPENBLAS_CORETYPE" not in os.environ:
    _CPU = Path("/proc/cpuinfo")
    if _CPU.exists() and {"avx2", "fma"} <= set(_CPU.read_text().split()):
        os.environ["OPENBLAS_CORETYPE"] = "Haswell"

import copy
import pickle
import signal
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np
import pytest
from hypothesis import settings

from hypothesis_scale import EXAMPLES_SCALE

# No per-example deadline: tests never assert wall-clock times, and on a loaded
# 2-core machine a first example that imports SciPy or loads a compiled kernel
# can take longer than hypothesis's default 200 ms (a flaky DeadlineExceeded).
settings.register_profile("navkit", deadline=None)
# Opt-in hunt for rare draws before CI's random seeds find them:
# NAVKIT_HYPOTHESIS_PROFILE=thorough runs every @given test with at least
# THOROUGH_EXAMPLES examples (see pytest_collection_modifyitems: most tests set
# their own max_examples, which a profile alone would not raise), and
# NAVKIT_HYPOTHESIS_EXAMPLES_SCALE=k (tests/hypothesis_scale.py) k times its count.
THOROUGH_EXAMPLES = 1000
settings.register_profile("thorough", deadline=None, max_examples=THOROUGH_EXAMPLES)
_PROFILE = os.environ.get("NAVKIT_HYPOTHESIS_PROFILE", "navkit")
if _PROFILE not in ("navkit", "thorough"):
    raise ValueError(f"NAVKIT_HYPOTHESIS_PROFILE must be 'navkit' or 'thorough', got {_PROFILE!r}")
settings.load_profile(_PROFILE)


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Each @given test's example count: its own, at least ``THOROUGH_EXAMPLES`` under
    the thorough profile, times ``EXAMPLES_SCALE``.

    hypothesis reads a test's settings from an attribute it does not document, at
    call time (``hypothesis_twins.slow_twin`` relies on the same one); all the
    other settings are kept. Every @given test has one (without ``@settings``,
    the profile's, as hypothesis stores it).
    """
    # A parametrized test is one function for many items: scaled once.
    done: set[int] = set()
    for item in items:
        test = getattr(item, "obj", None)
        test = getattr(test, "__func__", test)  # a test method: its function
        own = getattr(test, "_hypothesis_internal_use_settings", None)
        if own is None or id(test) in done:
            continue
        done.add(id(test))
        count = own.max_examples
        if _PROFILE == "thorough":
            count = max(count, THOROUGH_EXAMPLES)
        count *= EXAMPLES_SCALE
        if count != own.max_examples:
            test._hypothesis_internal_use_settings = settings(  # type: ignore[union-attr]
                own, max_examples=count
            )


# Ctrl-C as Python sets it up, also when the suite was started with SIGINT ignored
# (a background job of a non-interactive shell, nohup): the interrupt tests send
# SIGINT to this process and to probe processes, which inherit an ignored signal
# and would wait for it until their timeouts. A caught signal is reset to its
# default on exec, so the probes get Python's handler again.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)


@pytest.fixture(autouse=True)
def _numpy_error_state() -> Iterator[None]:
    """Each test starts from, and gives back, the error state numpy had before it.

    A test that interrupts code at every call can land inside
    ``np.errstate.__enter__`` (Python code) after it set its context
    variable: that state stayed set for every later test (in NumPy 2.3 a leaked
    ``np.linalg.cholesky`` callback made shapely's ``invalid value`` warnings
    raise ``LinAlgError``). Resetting the outer errstate's token restores it.
    """
    with np.errstate():
        yield


@pytest.fixture
def restore_mpmath_digits() -> Iterator[None]:
    """For tests that set mpmath's global precision: later tests find it as it was.

    Use with ``pytestmark = pytest.mark.usefixtures("restore_mpmath_digits")``.
    """
    mp = pytest.importorskip("mpmath")
    saved = mp.mp.dps
    yield
    mp.mp.dps = saved


SHARED_DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data"


@pytest.fixture(scope="session")
def shared_data() -> Path:
    """Path of ``../shared/data``; skips the test when the folder is absent."""
    if not SHARED_DATA.is_dir():
        pytest.skip(f"real data folder {SHARED_DATA} is not available")
    return SHARED_DATA


_DUPLICATES: dict[str, Callable[[Any], Any]] = {
    "pickle": lambda obj: pickle.loads(pickle.dumps(obj)),
    "deepcopy": copy.deepcopy,
    "copy": copy.copy,
}


@pytest.fixture(params=list(_DUPLICATES))
def duplicate(request: pytest.FixtureRequest) -> Callable[[Any], Any]:
    """Each way of copying a record: a pickle round trip, ``copy.deepcopy``, ``copy.copy``."""
    return _DUPLICATES[request.param]
