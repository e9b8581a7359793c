"""``navkit warmup`` where it cannot do its job: the JIT disabled, no cache folder."""

from __future__ import annotations

import os
import subprocess
import sys

_MAIN = "import sys; from navkit.cli import main; sys.exit(main(sys.argv[1:]))"


def _env(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env.update(extra)
    return env


def test_warmup_with_the_jit_disabled_says_so() -> None:
    # It printed "Every kernel was already cached: nothing to compile."
    done = subprocess.run(
        [sys.executable, "-c", _MAIN, "warmup", "--only", "geometry", "--workers", "1"],
        env=_env(NUMBA_DISABLE_JIT="1"), capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    assert "NUMBA_DISABLE_JIT" in done.stdout
    assert "cached" not in done.stdout


def test_warmup_without_a_writable_cache_folder_is_one_error_line() -> None:
    # Every kernel raised numba's RuntimeError ("cannot cache function ..."): a
    # traceback, and warming a cache that cannot exist would be pointless anyway.
    script = (
        "import numba.core.caching as caching\n"
        "impl = getattr(caching, 'CacheImpl', None) or getattr(caching, '_CacheImpl')\n"
        "impl._locator_classes = []\n" + _MAIN.replace("; ", "\n")
    )
    done = subprocess.run(
        [sys.executable, "-c", script, "warmup", "--only", "geometry", "--workers", "1"],
        env=_env(), capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert done.returncode == 1
    assert "Traceback" not in done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("navkit: error: ")
    assert "NUMBA_CACHE_DIR" in lines[0]
    assert done.stdout == ""
