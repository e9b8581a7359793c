"""The command's compile notice in a frozen application (``sys.frozen``, no source files).

numba caches a frozen application's kernels in its user-wide folder alone, named
after the (relative) path in the kernel's code; the notice looked beside the
package instead and said "compiling navkit's kernels once" in every run.
"""

from __future__ import annotations

import compileall
import os
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from numba_index import navkit_copy

_SCRIPT = """
import sys
sys.frozen = True
sys.path.insert(0, sys.argv[1])
import navkit
assert navkit.__file__.endswith("__init__.pyc"), navkit.__file__
from navkit.cli._kernels import kernels_cached
import navkit.planning.grid._astar_kernels as kernels
from numba.core import caching
before = kernels_cached("astar")
# numba's own choice of folder for the key kernel.
impl = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl")
py_func = kernels.grid_search.py_func
for locator_class in impl._locator_classes:
    locator = locator_class.from_function(py_func, py_func.__code__.co_filename)
    if locator is not None:
        break
# An index as numba writes it (stamped with the executable, as numba does frozen).
tag = f"py{sys.version_info.major}{sys.version_info.minor}{getattr(sys, 'abiflags', '')}"
name = f"_astar_kernels.grid_search-{py_func.__code__.co_firstlineno}.{tag}"
index = caching.IndexDataCacheFile(locator.get_cache_path(), name, locator.get_source_stamp())
index.save(("a signature",), ("compiled code",))
print(before, kernels_cached("astar"), type(locator).__name__)
"""


def test_a_frozen_application_finds_its_cached_kernels(tmp_path: Path) -> None:
    app = navkit_copy(tmp_path / "app")
    # As a freezer ships them: bytecode beside no source, named by relative paths.
    assert compileall.compile_dir(app / "navkit", quiet=1, legacy=True, ddir="navkit")
    for source in (app / "navkit").rglob("*.py"):
        source.unlink()
    run = tmp_path / "run"
    run.mkdir()
    env = {k: v for k, v in os.environ.items() if not k.startswith(("NUMBA_", "PYTHONWARN"))}
    env["XDG_CACHE_HOME"] = str(tmp_path / "cache")
    done = subprocess.run(
        [sys.executable, "-c", _SCRIPT, str(app)],
        cwd=run, env=env, capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    before, after, locator = done.stdout.split()
    assert locator.lstrip("_") == "UserWideCacheLocator"
    assert (before, after) == ("False", "True")
