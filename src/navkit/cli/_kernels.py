"""Whether navkit's compiled kernels are cached yet, and the notice when they are not.

numba compiles navkit's kernels on their first call and caches the machine code
on disk (``cache=True``), so only the very first run pays for it. Whether a run
will compile is checked cheaply, without importing or compiling anything: by
whether the cache index file (``<module>.<function>-<line>.py<XY>.nbi``) of one
key kernel exists in the folder numba would cache it in —
``$NUMBA_CACHE_DIR/<folder>_<sha1 of the folder path>/`` when that variable is
set, otherwise the ``__pycache__`` folder beside the kernel's source (or, when
that is not writable, numba's user-wide cache folder, which has the same layout
as ``NUMBA_CACHE_DIR``).
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
from pathlib import Path
from typing import Any, TextIO

__all__ = ["KERNELS", "announce_compilation", "cache_folders", "kernels_cached"]

#: Key kernels of each kind of work, ``(package, module, function)``, and about
#: how long compiling everything that work needs takes on a cold cache, s
#: (measured on 2 cores).
KERNELS: dict[str, tuple[tuple[str, str, str], float]] = {
    # _sample: called by both run kernels (edges-only worlds and the rest).
    "simulation": (("navkit.sim", "_segment_kernels", "_sample"), 10.0),
    "astar": (("navkit.planning.grid", "_astar_kernels", "grid_search"), 3.0),
    "field_dstar": (("navkit.planning.grid", "_field_path_kernels", "extract_path"), 8.0),
}


def _numba_cache_dir() -> str:
    """numba's ``NUMBA_CACHE_DIR`` setting ("" when unset)."""
    try:
        from numba.core import config
    except ImportError:  # pragma: no cover - numba is a dependency
        return os.environ.get("NUMBA_CACHE_DIR", "")
    return str(getattr(config, "CACHE_DIR", "") or "")


def _user_wide_dir() -> Path:
    """numba's user-wide cache folder (where it caches beside read-only installs)."""
    try:
        from numba.misc import appdirs

        dirs: Any = appdirs.AppDirs
        return Path(dirs(appname="numba", appauthor=False).user_cache_dir)
    except (ImportError, AttributeError):  # pragma: no cover - numba moved it
        return Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "numba"


def _subfolder(source_dir: Path) -> str:
    """numba's cache sub-folder for sources in ``source_dir`` (``_CacheLocator``)."""
    path = os.path.abspath(source_dir)
    return f"{os.path.basename(path)}_{hashlib.sha1(path.encode()).hexdigest()}"


def cache_folders(package: str) -> list[Path]:
    """The folders numba may cache the kernels of ``package`` in, most likely first.

    Parameters
    ----------
    package : str
        A navkit package holding kernel modules (``"navkit.sim"``).

    Returns
    -------
    list of Path
        Candidate folders (they need not exist).

    Examples
    --------
    >>> cache_folders("navkit.sim")[0].name in ("__pycache__",) or bool(_numba_cache_dir())
    True
    """
    spec = importlib.util.find_spec(package)
    if spec is None or not spec.submodule_search_locations:
        return []
    source_dir = Path(next(iter(spec.submodule_search_locations)))
    custom = _numba_cache_dir()
    if custom:
        return [Path(custom) / _subfolder(source_dir)]
    return [source_dir / "__pycache__", _user_wide_dir() / _subfolder(source_dir)]


def kernels_cached(kind: str) -> bool:
    """Whether the key kernel of ``kind`` of work is in numba's on-disk cache.

    Parameters
    ----------
    kind : str
        A key of :data:`KERNELS` (``"simulation"``, ``"astar"``, ``"field_dstar"``).

    Returns
    -------
    bool
        True when its cache index file exists (a stale index, after navkit's
        source changed, still counts: numba then recompiles silently).

    Examples
    --------
    >>> isinstance(kernels_cached("astar"), bool)
    True
    """
    (package, module, function), _ = KERNELS[kind]
    tag = f"py{sys.version_info.major}{sys.version_info.minor}"
    pattern = f"{module}.{function}-*.{tag}.nbi"
    return any(any(folder.glob(pattern)) for folder in cache_folders(package) if folder.is_dir())


def announce_compilation(kind: str, stream: TextIO) -> bool:
    """Say on ``stream`` that kernels will be compiled, when they are not cached.

    Parameters
    ----------
    kind : str
        A key of :data:`KERNELS`.
    stream : text stream
        Where to write (standard error).

    Returns
    -------
    bool
        Whether the notice was written (the cache was cold).

    Examples
    --------
    >>> import io
    >>> announce_compilation("astar", io.StringIO()) in (True, False)
    True
    """
    if kernels_cached(kind):
        return False
    seconds = KERNELS[kind][1]
    stream.write(
        f"navkit: compiling navkit's kernels once (about {seconds:.0f} s), cached afterwards"
        " (`navkit warmup` compiles them all ahead)\n"
    )
    stream.flush()
    return True
