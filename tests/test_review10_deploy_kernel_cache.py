"""navkit works where numba cannot cache its kernels (a read-only installation)."""

from __future__ import annotations

import json
import os
import subprocess
import sys

# numba finds no writable cache folder: what a read-only installation with a
# read-only HOME and no NUMBA_CACHE_DIR looks like to it.
_NO_CACHE_FOLDER = """
import numba.core.caching as caching
impl = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl")
impl._locator_classes = []
"""

_CALLS = _NO_CACHE_FOLDER + """
import json
import warnings
import numpy as np
from navkit.geometry import rollout
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    path = rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.5]]), 0.5)
    again = rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.5]]), 0.5)
from navkit._shared.jit import cache_problem
print(json.dumps({
    "path": path.tolist(), "again": again.tolist(), "problem": cache_problem(),
    "warnings": [(w.category.__name__, str(w.message)) for w in caught],
}))
"""


def _env() -> dict[str, str]:
    return {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}


def test_kernels_run_uncached_with_one_warning_naming_numba_cache_dir() -> None:
    # numba refused to make any cache=True dispatcher ("cannot cache function ...:
    # no locator available"), so every navkit kernel call raised RuntimeError.
    done = subprocess.run(
        [sys.executable, "-c", _CALLS], env=_env(), capture_output=True, text=True, timeout=300
    )
    assert done.returncode == 0, done.stderr[-2000:]
    out = json.loads(done.stdout.strip().splitlines()[-1])
    assert out["path"] == out["again"]
    assert len(out["path"]) == 2 and out["path"][0] == [0.0, 0.0, 0.0]
    assert out["path"][1][2] == 0.25  # heading after 0.5 s at 0.5 rad/s
    assert [kind for kind, _ in out["warnings"]] == ["KernelCacheWarning"]
    message = out["warnings"][0][1]
    assert "NUMBA_CACHE_DIR" in message and "cannot cache" in message
    assert out["problem"] == message
