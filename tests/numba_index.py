"""Cache index files of navkit's kernels, as numba writes them, and copies of navkit to cache.

The command's notice (``navkit.cli._kernels``) counts a kernel as cached only
when numba would use its index: written by this numba version, stamped with the
source as it is now, naming a data file that exists (review 47). Tests that
stand a cache in for numba's write it with numba's own code
(``IndexDataCacheFile`` and the locator's stamp), not with the check's reading
of the format, so that the check is tested against numba.
"""

from __future__ import annotations

import importlib
import shutil
import sys
from pathlib import Path
from typing import Any

import navkit


def navkit_copy(folder: Path) -> Path:
    """A copy of navkit's package (no caches) in ``folder``/navkit, for a fresh process.

    Returns ``folder``: the entry of ``sys.path`` that imports the copy.
    """
    shutil.copytree(
        Path(navkit.__file__).parent, folder / "navkit",
        ignore=shutil.ignore_patterns("__pycache__"),
    )  # fmt: skip
    return folder


def index_name(module: str, function: str, line: int) -> str:
    """numba's index file name of ``function`` (first line ``line``) of ``module``."""
    tag = f"py{sys.version_info.major}{sys.version_info.minor}{getattr(sys, 'abiflags', '')}"
    return f"{module}.{function}-{line}.{tag}"


def write_index(
    folder: Path, package: str, module: str, function: str, *, version: str | None = None
) -> Path:
    """Write an index of the kernel with one entry and its data file in ``folder``.

    Stamped by numba's locator with the kernel's source as it is now; ``version``
    stands in for another numba's. Returns the index's path.
    """
    from numba.core import caching

    kernel = getattr(importlib.import_module(f"{package}.{module}"), function)
    py_func = kernel.py_func
    locator: Any = caching.InTreeCacheLocator(py_func, py_func.__code__.co_filename)  # type: ignore[no-untyped-call]
    base = index_name(module, function, py_func.__code__.co_firstlineno)
    index: Any = caching.IndexDataCacheFile(str(folder), base, locator.get_source_stamp())  # type: ignore[no-untyped-call]
    if version is not None:
        index._version = version
    index.save(("a signature",), ("compiled code",))
    return folder / f"{base}.nbi"


#: The distance transform's kernel: the smallest kernel the compile notice counts.
TRANSFORM = ("navkit.mapping", "_edt_kernels", "band_distances")


def empty_cache_folder(tmp_path: Path, monkeypatch: Any) -> Path:
    """The transform's cache folder, made in an empty NUMBA_CACHE_DIR of ``tmp_path``.

    ``monkeypatch`` (pytest's) points the CLI's cache check there and clears
    ``sys.frozen``, for the test's duration.
    """
    from navkit.cli import _kernels

    monkeypatch.delattr(sys, "frozen", raising=False)
    monkeypatch.setattr(_kernels, "_numba_cache_dir", lambda: str(tmp_path))
    (folder,) = _kernels.cache_folders(TRANSFORM[0])
    folder.mkdir()
    return folder
