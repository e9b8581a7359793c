"""Whether navkit's compiled kernels are cached yet, and the notice when they are not.

numba compiles navkit's kernels on their first call and caches the machine code
on disk (``cache=True``), so only the very first run pays for it. Whether a run
will compile is checked cheaply, without compiling anything or loading numba's
compiler: by whether each key kernel its estimate counts (the kind of work's own
and the distance transform's, :data:`SHARED_KERNELS`) has a cache index file
(``<module>.<function>-<line>.py<XY>.nbi``) numba would use, in the folder numba
would cache it in — ``$NUMBA_CACHE_DIR/<folder>_<sha1 of the folder path>/`` when
that variable is set, otherwise the ``__pycache__`` folder beside the kernel's
source (or, when that is not writable, numba's user-wide cache folder, which has
the same layout as ``NUMBA_CACHE_DIR``). In a frozen application without the
source files (``sys.frozen``), numba caches in the user-wide folder alone, named
after the path the kernel's code gives: the kernel's module is imported to read it.

numba uses an index only when it was written by the same numba version and for
the source file as it is now (numba's ``IndexDataCacheFile._load_index``): the
file holds the version (a pickle), then a pickle of the source's stamp and the
compiled entries' data files. The stamp is the source's ``(st_mtime, st_size)``
in numba 0.62 and the SHA-256 digest of its bytes in 0.68 (of
``sys.executable`` in a frozen application); numba drops an index whose stamp
differs and recompiles silently. An index whose stamp, version or entries do not
pass counts as no cache here too, as numba would then compile (review 47: after
an upgrade or an edit the notice was missing). What this does not see, the
entries' machine (CPU name and features: a cache copied from another machine),
needs numba's code generator; the notice then stays silent as before.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import pickle
import sys
import warnings
from pathlib import Path
from typing import Any, TextIO

from navkit._shared.jit import cache_problem, jit_disabled, numba_user_cache_folder
from navkit.errors import KernelCacheWarning

__all__ = [
    "KERNELS",
    "SHARED_KERNELS",
    "announce_compilation",
    "cache_folders",
    "check_cache",
    "kernels_cached",
]

#: Compiling the exact distance transform behind every costmap
#: (``navkit.mapping._edt_kernels``), s: part of each kind of work below (``navkit
#: plan`` inflates its map; so do the scenarios on maps, and diff-astar's
#: localiser transforms its map too). A cold ``navkit plan``'s warm-up with the
#: transform already cached took 0.4-0.7 s less (review 46).
_DISTANCE_TRANSFORM = 0.5

#: Key kernels of each kind of work, ``(package, module, function)``, and about
#: how long compiling everything that work needs takes on a cold cache, s: its
#: own kernels and the distance transform. CPU seconds of a cold ``navkit plan``
#: warm-up (2.4-2.6 s with A*, 4.1-4.4 s with Field D*) and of a cold one-trial
#: ``navkit run diff-astar`` or ``demo`` less a warm one (9.4-10.1 s), on a busy
#: 2-core machine, 2026-12-07 (review 46: Field D*'s 8 s dated from 2026-12-01,
#: before its first use got cheaper, and none counted the distance transform).
KERNELS: dict[str, tuple[tuple[str, str, str], float]] = {
    # _sample: called by both run kernels (edges-only worlds and the rest).
    "simulation": (("navkit.sim", "_segment_kernels", "_sample"), 9.5 + _DISTANCE_TRANSFORM),
    "astar": (("navkit.planning.grid", "_astar_kernels", "grid_search"), 2.1 + _DISTANCE_TRANSFORM),
    "field_dstar": (
        ("navkit.planning.grid", "_field_path_kernels", "extract_path"),
        3.8 + _DISTANCE_TRANSFORM,
    ),
}

#: Kernels every kind of work above runs besides its own, each cached on its own
#: (an upgrade changing only ``_edt_kernels`` recompiles it alone), with the
#: part of each estimate it is, s: keys :func:`kernels_cached` takes too.
SHARED_KERNELS: dict[str, tuple[tuple[str, str, str], float]] = {
    "distance_transform": (
        ("navkit.mapping", "_edt_kernels", "band_distances"),
        _DISTANCE_TRANSFORM,
    ),
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
    return Path(numba_user_cache_folder())


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
    source_dir = _source_dir(package)
    if source_dir is None:
        return []
    custom = _numba_cache_dir()
    if custom and _could_write(Path(custom) / _subfolder(source_dir)):
        return [Path(custom) / _subfolder(source_dir)]
    # numba passes over a NUMBA_CACHE_DIR it cannot make or write to (a typo, a
    # read-only mount) and caches where it would without one.
    return [source_dir / "__pycache__", _user_wide_dir() / _subfolder(source_dir)]


def _source_dir(package: str) -> Path | None:
    """The folder of ``package``'s source files (None for what is not a package)."""
    spec = importlib.util.find_spec(package)
    if spec is None or not spec.submodule_search_locations:
        return None
    return Path(next(iter(spec.submodule_search_locations)))


def _could_write(folder: Path) -> bool:
    """Whether ``folder`` is, or could be made, a writable folder (numba's test, not made)."""
    try:
        for existing in (folder, *folder.parents):
            if existing.exists():
                return existing.is_dir() and os.access(existing, os.W_OK | os.X_OK)
    except OSError:  # a folder on the way that cannot be looked into
        return False
    return False


def kernels_cached(kind: str) -> bool:
    """Whether the key kernel of ``kind`` of work, or a shared one, is in numba's on-disk cache.

    Parameters
    ----------
    kind : str
        A key of :data:`KERNELS` (``"simulation"``, ``"astar"``,
        ``"field_dstar"``: that work's own kernels) or of
        :data:`SHARED_KERNELS` (``"distance_transform"``).

    Returns
    -------
    bool
        True when a cache index file of it is there that numba would use:
        written by this numba version, for the source file as it is now (its
        stamp: see the module's notes), naming a data file that exists.

    Examples
    --------
    >>> isinstance(kernels_cached("astar"), bool)
    True
    """
    (package, module, function), _ = KERNELS[kind] if kind in KERNELS else SHARED_KERNELS[kind]
    abiflags = getattr(sys, "abiflags", "")
    tag = f"py{sys.version_info.major}{sys.version_info.minor}{abiflags}"
    pattern = f"{module}.{function}-*.{tag}.nbi"
    folders = cache_folders(package)
    frozen = getattr(sys, "frozen", False)
    if frozen:
        folders = _frozen_folders(f"{package}.{module}", function) or folders
    # numba stamps a frozen application's kernels with its executable.
    source_dir = _source_dir(package)
    if frozen:
        source = Path(sys.executable)
    elif source_dir is None:  # pragma: no cover - the keys name navkit's packages
        return False
    else:
        source = source_dir / f"{module}.py"
    stamps = _SourceStamps(source)
    version = _numba_version()
    return any(
        _index_usable(index, stamps, version)
        for folder in folders
        if folder.is_dir()
        for index in folder.glob(pattern)
    )


def _numba_version() -> str:
    """The version numba writes in its index files ("" without numba)."""
    try:
        import numba
    except ImportError:  # pragma: no cover - numba is a dependency
        return ""
    return str(numba.__version__)


class _SourceStamps:
    """The stamps numba may have given ``source``, each read when first asked for.

    Parameters
    ----------
    source : Path
        The file numba stamps a kernel's cache with.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     source = Path(folder) / "k.py"
    ...     _ = source.write_bytes(b"x = 1")
    ...     stamps = _SourceStamps(source)
    ...     (stamps.fresh((source.stat().st_mtime, 5)), stamps.fresh((0.0, 5)))
    (True, False)
    """

    def __init__(self, source: Path) -> None:
        self.source = source
        self._digest: bytes | None = None

    def fresh(self, stamp: object) -> bool:
        """Whether numba would take ``stamp``, read from an index, as the source's own.

        Parameters
        ----------
        stamp : object
            The stamp an index holds: ``(st_mtime, st_size)`` (numba 0.62) or
            the SHA-256 digest of the source's bytes (numba 0.68).

        Returns
        -------
        bool
            Whether it equals the source's stamp now (False when the source
            cannot be read: numba could not stamp it either). A stamp of
            another form, from a numba this does not know, counts as fresh
            (what numba then does is not known here: the notice stays silent,
            as it was before stamps were checked).

        Examples
        --------
        >>> _SourceStamps(Path("no-such-file.py")).fresh((0.0, 0))
        False
        """
        try:
            if isinstance(stamp, bytes):
                if self._digest is None:
                    self._digest = hashlib.sha256(self.source.read_bytes()).digest()
                return stamp == self._digest
            if isinstance(stamp, tuple):
                status = self.source.stat()
                return stamp == (status.st_mtime, status.st_size)
        except OSError:
            return False
        return True


def _index_usable(index: Path, stamps: _SourceStamps, version: str) -> bool:
    """Whether numba would load a compiled entry through ``index`` (its ``_load_index``).

    An index of another numba version, of a stale source stamp, with no entry
    whose data file exists, or that cannot be read counts as no cache.
    """
    try:
        with index.open("rb") as file:
            # numba reads the version first and the rest only when it matches:
            # another version may pickle differently.
            if pickle.load(file) != version:
                return False
            stamp, overloads = pickle.loads(file.read())
        entries = list(overloads.values())
    except Exception:  # any failure to read it: a broken or foreign file
        return False
    if not stamps.fresh(stamp):
        return False
    return any(isinstance(name, str) and (index.parent / name).is_file() for name in entries)


def _frozen_folders(module: str, function: str) -> list[Path]:
    """Where numba caches a kernel of a frozen application whose source is not beside it.

    numba then caches it in its user-wide folder alone, under the folder of the
    file its code names (a relative path in a frozen application: taken from
    the current folder); ``NUMBA_CACHE_DIR`` and ``__pycache__`` need the file.
    Empty when the file exists (numba's usual folders apply).
    """
    kernel: Any = getattr(importlib.import_module(module), function, None)
    code = getattr(getattr(kernel, "py_func", kernel), "__code__", None)
    if code is None or os.path.exists(code.co_filename):
        return []
    return [_user_wide_dir() / _subfolder(Path(os.path.abspath(code.co_filename)).parent)]


def check_cache(stream: TextIO) -> str | None:
    """Load numba and say on ``stream``, in one line, when it cannot cache navkit's kernels.

    Called by the command before a run: worker processes forked afterwards
    inherit numba loaded and the problem already said, instead of each
    printing the library's two-line :class:`~navkit.errors.KernelCacheWarning`.
    The warning filters in force still apply (``-W ignore::...`` silences the line).

    Parameters
    ----------
    stream : text stream
        Where to write (standard error).

    Returns
    -------
    str or None
        Why numba cannot cache the kernels (:func:`navkit._shared.jit.cache_problem`),
        or None when it can.

    Examples
    --------
    >>> import io
    >>> check_cache(io.StringIO()) is None or True
    True
    """
    with warnings.catch_warnings(record=True) as caught:
        problem = cache_problem()
    for warning in caught:
        if issubclass(warning.category, KernelCacheWarning):
            stream.write(f"navkit: warning: {' '.join(str(warning.message).split())}\n")
        else:  # pragma: no cover - numba's own warnings, shown as they would have been
            warnings.showwarning(
                warning.message, warning.category, warning.filename, warning.lineno
            )
    stream.flush()
    return problem


def announce_compilation(
    kind: str, stream: TextIO, *, problem: str | None = None, processes: int = 1
) -> bool:
    """Say on ``stream`` that kernels will be compiled, when they are not cached.

    Parameters
    ----------
    kind : str
        A key of :data:`KERNELS`.
    stream : text stream
        Where to write (standard error).
    problem : str, optional
        Why numba cannot cache the kernels (:func:`check_cache`): then they are
        compiled in every run, whatever the cache folders hold, and the notice
        says so rather than promising a cache.
    processes : int, optional
        How many processes run the work, each compiling for itself.

    Returns
    -------
    bool
        Whether the notice was written (a kernel it counts was not cached, or
        the cache is unusable; never with numba's JIT disabled, which compiles
        nothing). Its estimate counts only the kernels not cached.

    Examples
    --------
    >>> import io
    >>> announce_compilation("astar", io.StringIO()) in (True, False)
    True
    >>> notice = io.StringIO()
    >>> announce_compilation("astar", notice, problem="read-only", processes=2)
    True
    >>> print(notice.getvalue().strip())
    navkit: compiling navkit's kernels (about 3 s, in each of 2 processes), again in every run: numba cannot cache them here
    """  # noqa: E501
    if jit_disabled():
        return False
    seconds = KERNELS[kind][1]
    if problem is None:
        # Each kernel counted is cached on its own (the shared ones' seconds are
        # part of the kind's): only what is missing is compiled.
        own = seconds - sum(part for _, part in SHARED_KERNELS.values())
        seconds = (0.0 if kernels_cached(kind) else own) + sum(
            part for shared, (_, part) in SHARED_KERNELS.items() if not kernels_cached(shared)
        )
        if seconds == 0.0:
            return False
    each = f", in each of {processes} processes" if processes > 1 else ""
    # Below a second, "about 0 s" would read as nothing to wait for.
    about = f"{seconds:.0f}" if seconds >= 1.0 else f"{seconds:.1f}"
    if problem is not None:
        stream.write(
            f"navkit: compiling navkit's kernels (about {about} s{each}), again in every"
            " run: numba cannot cache them here\n"
        )
    else:
        stream.write(
            f"navkit: compiling navkit's kernels once (about {about} s{each}), cached"
            " afterwards (`navkit warmup` compiles them all ahead)\n"
        )
    stream.flush()
    return True
