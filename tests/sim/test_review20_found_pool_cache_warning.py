"""Spawned and forkserver pool workers do not repeat the parent's KernelCacheWarning.

Review 20, FOUND item 3. Where numba finds no writable cache folder, navkit
warns once per process (:class:`~navkit.errors.KernelCacheWarning`). A forked
worker inherits its parent's "already said"; a spawned or forkserver worker
starts afresh and said it again at its first kernel, once per worker, after
the parent (or ``navkit run``) had already said it. The pool now tells its
workers when the parent has warned; the parent's one warning stays.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

from navkit.errors import KernelCacheWarning
from navkit.sim._pool import _start_worker

_RUN = """
import json, multiprocessing, sys, warnings
from navkit._shared.jit import cache_problem
from navkit.sim._pool import process_pool


def no_cache_folder():
    # What a read-only installation with a read-only HOME and no NUMBA_CACHE_DIR
    # looks like to numba (before navkit makes its kernels in this process).
    import numba.core.caching as caching
    impl = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl")
    impl._locator_classes = []
    return cache_problem()  # makes the kernels' dispatchers (compiles nothing)


if __name__ == "__main__":
    multiprocessing.set_start_method(sys.argv[1])
    warnings.simplefilter("default")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mine = no_cache_folder()  # the parent warns
    for w in caught:
        print("PARENT", w.category.__name__, file=sys.stderr, flush=True)
    with process_pool(2) as pool:
        theirs = [f.result() for f in [pool.submit(no_cache_folder) for _ in range(4)]]
    print(json.dumps({"same": mine is not None and all(p == mine for p in theirs)}))
"""


def _run(method: str, tmp_path: Path) -> tuple[dict[str, bool], str]:
    script = tmp_path / "run_pool.py"  # a file: spawn workers import the main module
    script.write_text(_RUN)
    # NUMBA_CACHE_DIR is kept (nothing is cached anyway: no cache locator is left).
    env = {k: v for k, v in os.environ.items() if k != "PYTHONWARNINGS"}
    done = subprocess.run(
        [sys.executable, str(script), method],
        capture_output=True, text=True, timeout=600, env=env, cwd=tmp_path,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1]), done.stderr


@pytest.mark.parametrize(
    "method",
    ["spawn", pytest.param("forkserver", marks=pytest.mark.slow)],
)
def test_workers_do_not_repeat_the_parents_warning(method: str, tmp_path: Path) -> None:
    if method not in __import__("multiprocessing").get_all_start_methods():
        pytest.skip(f"no {method} start method here")
    out, stderr = _run(method, tmp_path)
    assert out["same"]
    assert "PARENT KernelCacheWarning" in stderr  # the parent's own warning stays
    assert stderr.count("KernelCacheWarning") == 1, stderr[-3000:]


def test_a_worker_told_of_the_warning_ignores_only_that_warning() -> None:
    handler = signal.getsignal(signal.SIGINT)  # the initializer ignores SIGINT: put back
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            _start_worker(True)
            warnings.warn("cache", KernelCacheWarning, stacklevel=1)
            warnings.warn("other", RuntimeWarning, stacklevel=1)
        assert [str(w.message) for w in caught] == ["other"]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            _start_worker(False)
            warnings.warn("cache", KernelCacheWarning, stacklevel=1)
        assert [str(w.message) for w in caught] == ["cache"]
    finally:
        signal.signal(signal.SIGINT, handler)
