"""KernelCacheWarning names the user's line that made navkit compile, not navkit's own."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

# numba finds no writable cache folder (as tests/test_review10_deploy_kernel_cache.py):
# what a read-only installation with a read-only HOME and no NUMBA_CACHE_DIR looks like.
_NO_CACHE_FOLDER = """\
import numba.core.caching as caching
impl = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl")
impl._locator_classes = []
"""

_RECORD = """\
import json
import warnings
warnings.simplefilter("always")
caught = []
warnings.showwarning = lambda message, category, filename, lineno, *rest: caught.append(
    (category.__name__, filename, lineno)
)
"""

_REPORT = """\
print(json.dumps(caught))
"""


def _env() -> dict[str, str]:
    return {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}


def _run(tmp_path: Path, body: str) -> tuple[str, list[list[object]], int]:
    """Run ``body`` as a script file; its path, the warnings shown and the line of ``# HERE``."""
    source = _NO_CACHE_FOLDER + _RECORD + body + _REPORT
    script = tmp_path / "user_script.py"
    script.write_text(source)
    line = next(i for i, text in enumerate(source.splitlines(), 1) if text.endswith("# HERE"))
    done = subprocess.run(
        [sys.executable, str(script)],
        env=_env(),
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return str(script), json.loads(done.stdout.strip().splitlines()[-1]), line


def test_warning_points_at_the_call_of_a_public_function(tmp_path: Path) -> None:
    # It named navkit/_shared/jit.py (stacklevel=2 from its own helper), so a
    # filter by module or the shown location pointed into navkit.
    script, caught, line = _run(
        tmp_path,
        "import numpy as np\n"
        "from navkit.geometry import rollout\n"
        "rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.5]]), 0.5)  # HERE\n",
    )
    assert caught == [["KernelCacheWarning", script, line]]


def test_warning_from_a_kernel_made_at_import_points_at_the_import(tmp_path: Path) -> None:
    # Once numba is loaded, a kernel module imported later makes its dispatchers
    # while being imported: importlib's frames lie between it and the user.
    script, caught, line = _run(
        tmp_path,
        "import navkit._shared.jit as jit\n"
        "import sys\n"
        "assert not [m for m in sys.modules if m.startswith('navkit.geometry')]\n"
        "jit.load_numba()\n"
        "assert jit.cache_problem() is None\n"
        "import navkit.geometry  # HERE\n",
    )
    assert caught == [["KernelCacheWarning", script, line]]


def test_warning_can_be_filtered_by_the_users_module(tmp_path: Path) -> None:
    _, caught, _ = _run(
        tmp_path,
        "warnings.filterwarnings('ignore', module='__main__')\n"
        "import numpy as np\n"
        "from navkit.geometry import rollout\n"
        "rollout((0.0, 0.0, 0.0), np.array([[1.0, 0.0, 0.5]]), 0.5)  # HERE\n",
    )
    assert caught == []


def test_stack_walk_passes_through_importlibs_public_functions() -> None:
    # A kernel first made under importlib.import_module (e.g. a lazily imported
    # scenario module) must still name the user's line, not importlib/__init__.py.
    from navkit._shared import jit

    navkit_side: dict[str, object] = {"__name__": "navkit.fake", "walk": jit._user_stacklevel}
    exec("def warn_site():\n    return walk()", navkit_side)
    importlib_side: dict[str, object] = {"__name__": "importlib", "inner": navkit_side["warn_site"]}
    exec("def import_module():\n    return inner()", importlib_side)
    import_module = importlib_side["import_module"]
    assert callable(import_module)
    # warn_site (1, navkit) <- import_module (2, importlib) <- this test (3, the user)
    assert import_module() == 3
