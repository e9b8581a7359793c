"""Writing files atomically: temporary files beside the targets, then ``os.replace``.

Every file navkit writes (maps, pictures, JSON results) goes through
:func:`atomic_paths`: readers see the old file or the whole new one, and a
failure (an exception, a full disk, an interrupt) leaves every target as it was
and no temporary file behind.
"""

from __future__ import annotations

import contextlib
import errno
import os
import secrets
import stat
import sys
import time
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path

from navkit._shared.locks import ForkSafeLock

try:
    import fcntl
except ImportError:  # Windows
    fcntl = None  # type: ignore[assignment]

__all__ = ["RENAME_LOCK", "atomic_path", "atomic_paths", "check_folder", "link_loop"]

#: Random temporary names tried before giving up.
_ATTEMPTS = 100

#: Windows: how long a rename refused with ``PermissionError`` is tried again, s.
#: Windows refuses to rename over a file that another program has open (a virus
#: scanner or indexer looking at the new file, a reader of the old one) for as
#: long as it is open; such holds last milliseconds.
_WINDOWS_RETRY_SECONDS = 1.0

#: Windows' errors for a path longer than ``MAX_PATH`` (260) characters:
#: ``ERROR_PATH_NOT_FOUND``, ``ERROR_FILENAME_EXCED_RANGE``.
_WINDOWS_PATH_ERRORS = (3, 206)

#: Windows' error for a path whose symbolic links never end in a file
#: (``ERROR_CANT_RESOLVE_FILENAME``; Python gives it no ``ELOOP`` errno).
_WINDOWS_LINK_LOOP = 1921

#: Symbolic links followed looking for the file in a folder's way (Linux's own
#: limit, ``MAXSYMLINKS``): a chain longer than that is a loop to the system.
_MAX_LINKS = 40

#: Held while one :func:`atomic_paths` renames its files over their targets: two
#: threads saving the same files (a map's image and YAML) would otherwise
#: interleave their renames and leave one's image with the other's YAML. A
#: writer that looks at the targets before writing (is this image the map's?)
#: holds it too, so that it never sees another thread's save half renamed. A
#: writer whose save also removes a file its renames make stale (``write_map``:
#: the map's image in the other format) holds it from that choice, through its
#: ``atomic_paths`` block, to the removal, so that no other thread's save comes
#: in between: the lock is re-entrant for that.
RENAME_LOCK = ForkSafeLock(reentrant=True)


@contextlib.contextmanager
def atomic_paths(targets: Sequence[Path]) -> Iterator[tuple[Path, ...]]:
    """Yield one new empty temporary file per target; on success rename them over the targets.

    Each temporary file is created exclusively in its target's folder, hidden,
    named ``.<stem>.<random>.tmp<suffix>`` (the target's suffix kept, for
    writers that pick a format from it). The caller writes them (by path; a
    writer may replace the empty file). When the ``with`` block ends normally
    every temporary file is flushed to disk (``fsync``; on macOS
    ``F_FULLFSYNC``, as ``fsync`` there leaves the data in the drive's cache)
    and given the mode of the existing target (a new one keeps ``0o666`` less
    the umask, what a plain write gives; not on Windows, where a mode is only
    a read-only flag and a read-only target is not replaced), *then* they are
    renamed over the targets in order (``os.replace``; on Windows tried again
    for up to a second while another program has a file open) and the folders
    are synced where the system allows (not on Windows). If
    anything fails before the renames, no target is touched; if a rename fails
    (a permission, a file system error), the targets renamed before it are put
    back as they were (from hard links made just before, where the file system
    has them; a target that did not exist is removed). Only a crash during the
    renames can leave some targets new and others old. The temporary files are
    always removed. Threads of one process take turns for the renames, so
    that two saves of the same targets at once leave all of one save's files
    (the later one's) rather than a mix; other processes are not waited for.

    Parameters
    ----------
    targets : sequence of Path
        The files to write, in existing folders (not folders themselves).

    Yields
    ------
    tuple of Path
        The temporary files, one per target, in order.

    Raises
    ------
    ValueError
        A target that exists and is not a regular file (a device such as
        ``/dev/null``, a named pipe, a socket): the rename would replace the
        device or pipe itself (as root, ``/dev/null`` too). Nothing is created.
        A target that is a loop of symbolic links (``a`` links to ``b``,
        which links to ``a``): no file is there whose mode the new one could
        take, and what the system's own writers (``open``, a shell's ``>``)
        refuse with ``ELOOP`` is refused here too, before anything is
        created, not after the block has written its temporary file. (A
        symbolic link that ends in a file, or in nothing, is itself replaced
        by the new file, which takes the mode of the file it pointed to.)
    IsADirectoryError
        A target that is a folder, found before the block runs or before the
        renames (a folder made meanwhile): no target is replaced, not even the
        ones before it in ``targets``.
    FileNotFoundError
        A target's folder does not exist, or cannot be reached because it, or
        a folder above it, is a loop of symbolic links (``a/b/out.json`` with
        ``a`` linking to itself): :func:`check_folder`'s error, naming the
        folder (and the loop), raised before anything is created. A loop made
        later (during the block, or as the files are synced and renamed) is
        refused in the same words (or, at a target, as the ``ValueError``
        above), not as the system's ``OSError`` (``ELOOP``); a temporary file
        in a folder moved away to make room for the loop cannot be reached
        to be removed.
    NotADirectoryError
        A file stands where a folder of a target's path should be (named).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     a, b = Path(folder) / "a.txt", Path(folder) / "b.txt"
    ...     with atomic_paths([a, b]) as (ta, tb):
    ...         _ = ta.write_text("A"), tb.write_text("B")
    ...     print(sorted(p.name for p in Path(folder).iterdir()), a.read_text() + b.read_text())
    ['a.txt', 'b.txt'] AB
    """
    _check_targets(targets)
    temporaries: list[Path] = []
    try:
        for target in targets:
            _new_temporary(target, temporaries)
        yield tuple(temporaries)
        # Again, now: the rename over a folder fails, after those of the targets before it.
        _check_targets(targets)
        try:
            for temporary, target in zip(temporaries, targets, strict=True):
                _sync(temporary, os.O_RDWR)
                if not _windows():
                    # (On Windows a mode is only the read-only flag: copied, it would make
                    # the temporary file one that cannot be removed if the rename fails.)
                    with contextlib.suppress(FileNotFoundError):
                        os.chmod(temporary, stat.S_IMODE(os.stat(target).st_mode))
            with RENAME_LOCK:
                _replace_all(temporaries, targets)
        except OSError:
            # A loop of links made since the check (at a target: ELOOP from the mode's
            # os.stat; in a folder: from the sync or the rename) is refused in the
            # words of one made a moment earlier, not as the system's OSError.
            _check_targets(targets)
            raise
    finally:
        try:
            _remove_all(temporaries)
        except BaseException:
            _remove_all(temporaries)  # an interrupt may have cut the removals short: again
            raise
    for folder in dict.fromkeys(target.parent for target in targets):
        with contextlib.suppress(OSError):  # make the renames durable where possible (POSIX)
            _sync(folder, os.O_RDONLY)


@contextlib.contextmanager
def atomic_path(target: Path) -> Iterator[Path]:
    """Yield a new empty temporary file beside ``target``; rename it over ``target`` on success.

    :func:`atomic_paths` for one file.

    Parameters
    ----------
    target : Path
        The file to write, in an existing folder.

    Yields
    ------
    Path
        The temporary file to write.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     with atomic_path(Path(folder) / "out.json") as temporary:
    ...         _ = temporary.write_text("{}")
    ...     print([p.name for p in Path(folder).iterdir()])
    ['out.json']
    """
    with atomic_paths((target,)) as (temporary,):
        yield temporary


def link_loop(path: Path) -> bool:
    """Whether following the symbolic links of ``path`` (or of its folders) never ends.

    ``Path.exists`` and ``Path.is_dir`` say False for such a path, as for a
    missing one; only opening or ``stat`` tells them apart (``ELOOP``).

    Parameters
    ----------
    path : Path
        Any path.

    Returns
    -------
    bool
        True if ``os.stat(path)`` fails with ``ELOOP`` (on Windows, with
        ``ERROR_CANT_RESOLVE_FILENAME``).

    Raises
    ------
    ValueError
        ``path`` holds a NUL character (``os.stat``'s error).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     a, b = Path(folder) / "a", Path(folder) / "b"
    ...     a.symlink_to(b)
    ...     print(link_loop(a), a.exists())
    ...     b.symlink_to(a)
    ...     print(link_loop(a), a.exists(), link_loop(a / "x.json"))
    False False
    True False True
    """
    try:
        os.stat(path)
    except OSError as exc:
        return exc.errno == errno.ELOOP or getattr(exc, "winerror", None) == _WINDOWS_LINK_LOOP
    return False


def check_folder(target: Path, name: str | None = None) -> None:
    """Refuse a ``target`` whose folder is not there to write into.

    The one test of every writer: a folder that does not exist and one that a
    loop of symbolic links makes unreachable are the same failure (no folder
    to write into), in the same words. ``Path.is_dir`` says False for both;
    the loop, told apart by :func:`link_loop`, is named in the message (the
    highest folder of the path that loops: for ``a/b/out.json`` with ``a``
    linking to itself, ``a``).

    Parameters
    ----------
    target : Path
        The file to be written.
    name : str, optional
        The argument or option that gave ``target`` (``"path"``, ``"--json"``):
        the message starts with it. Without it (:func:`atomic_paths`, which
        knows no argument) the error is in the system's form, naming the
        folder as its ``filename`` (and a file standing where a folder of the
        path should be as ``NotADirectoryError``).

    Raises
    ------
    FileNotFoundError
        The folder of ``target`` does not exist, or is a loop of symbolic
        links, or lies below one: ``"{name}: folder {folder} does not exist"``
        (with ``" ({loop} is a loop of symbolic links)"`` after it for a
        loop); without ``name``, ``errno.ENOENT`` with ``strerror`` ``"no
        such folder"`` (and the same parenthesis) and the folder as
        ``filename``.
    NotADirectoryError
        A file where a folder of the path should be, or where one should be
        on the way through a symbolic link's target (``b/out.json`` with
        ``b -> a/b``, ``a`` a file: ``a``, as ``open`` finds it, not a
        missing ``b``): ``"{name}: {file} is a file, not a folder"``; without
        ``name``, ``errno.ENOTDIR`` with that file as ``filename``.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     check_folder(Path(folder) / "out.json", "path")  # a folder: nothing said
    ...     loop = Path(folder) / "a"
    ...     loop.symlink_to("a")
    ...     try:
    ...         check_folder(loop / "b" / "out.json", "--json")
    ...     except FileNotFoundError as exc:
    ...         print(str(exc).replace(folder, "..."))
    --json: folder .../a/b does not exist (.../a is a loop of symbolic links)
    """
    folder = target.parent
    if folder.is_dir():
        return
    loop = next((p for p in (*reversed(folder.parents), folder) if link_loop(p)), None)
    why = "" if loop is None else f" ({loop} is a loop of symbolic links)"
    # Named as the system would: the file, not the folder below it.
    blocker = None if loop is not None else _file_in_path(folder)
    if name is not None:
        if blocker is not None:
            raise NotADirectoryError(f"{name}: {blocker} is a file, not a folder")
        raise FileNotFoundError(f"{name}: folder {folder} does not exist{why}")
    if blocker is not None:
        raise NotADirectoryError(errno.ENOTDIR, "not a folder", os.fspath(blocker))
    raise FileNotFoundError(errno.ENOENT, f"no such folder{why}", os.fspath(folder))


def _check_targets(targets: Sequence[Path]) -> None:
    """Refuse targets that are not regular files, or not in a folder, before any is replaced."""
    for target in targets:
        # Every folder first: none of the targets before a missing one gets a temporary file.
        check_folder(target)
    for target in targets:
        if target.is_dir():
            raise IsADirectoryError(errno.EISDIR, "a folder cannot be written as a file", target)
        if link_loop(target):
            # Found here, not by the mode's os.stat after the block (an OSError once
            # the temporary file was written), nor as a temporary file's name.
            raise ValueError(f"{target} is a loop of symbolic links: it names no file to replace")
        if target.exists() and not target.is_file():
            raise ValueError(
                f"{target} is not a regular file (a device, a pipe or a socket): it is written "
                "by renaming a new file over it, which would replace it"
            )


def _name_max(folder: Path) -> int:
    """Longest file name (bytes) the file system of ``folder`` takes; 255 if it cannot say."""
    # A platform test, not the except alone: Windows' type stubs have no pathconf.
    limit = 255
    if sys.platform != "win32":
        with contextlib.suppress(AttributeError, OSError, ValueError):  # no such folder
            limit = int(os.pathconf(folder, "PC_NAME_MAX"))
    # pathconf answers -1 for "no limit" (not an error); 0 is no answer either.
    # Taken as the limit, either would cut every name down to ".{tag}.tmp",
    # dropping the suffix that writers pick their format from.
    return limit if limit > 0 else 255


def _temporary_name(target: Path, tag: str, name_max: int) -> str:
    """``.{stem}.{tag}.tmp{suffix}``, the stem shortened to fit ``name_max`` bytes.

    The suffix is kept (writers such as matplotlib pick the format from it)
    unless even an empty stem leaves no room for it. A target name near the
    limit is legal; its temporary name, 14 bytes longer, would not be.
    """
    stem, suffix = target.stem, target.suffix
    while True:
        name = f".{stem}.{tag}.tmp{suffix}"
        if len(os.fsencode(name)) <= name_max:
            return name
        if not stem:
            return f".{tag}.tmp"
        stem = stem[:-1]


def _compact_name(target: Path, tag: str) -> str:
    """A temporary name no longer than ``target``'s however a file system counts.

    The name adds 14 ASCII characters to the stem; dropping 14 characters of the
    stem, each at least one byte, character or UTF-16 unit, makes up for them.
    A stem too short for that gives ``.{tag}.tmp`` (14 characters).
    """
    stem = target.stem[:-14]
    return f".{stem}.{tag}.tmp{target.suffix}" if stem else f".{tag}.tmp"


def _replace_all(temporaries: Sequence[Path], targets: Sequence[Path]) -> None:
    """Rename each temporary file over its target; undo the renames done if one fails."""
    if len(targets) == 1:
        _replace(temporaries[0], targets[0])
        return
    # Hard links to the targets as they are, to put them back if a later rename fails.
    backups: list[tuple[Path | None, bool]] = []
    try:
        for target in targets:
            _backup(target, backups)
        done = 0
        try:
            for temporary, target in zip(temporaries, targets, strict=True):
                # Counted before: an interrupt as the rename returns must undo it too.
                done += 1
                _replace(temporary, target)
        except BaseException as failure:
            if done and os.path.lexists(temporaries[done - 1]):
                done -= 1  # that rename failed, or the interrupt came before it
            # On Windows a restore may wait (see _replace): a first Ctrl-C then must
            # not end the rollback part-way (the backups are removed below: the old
            # files of the targets not yet put back would be lost, an image and its
            # YAML from different saves). The wait goes on and the Ctrl-C is raised
            # once every target has been tried; a second one stops the waiting.
            interrupt: BaseException | None = None
            insisted = False
            for target, (backup, existed) in zip(targets[:done], backups[:done], strict=True):
                while True:
                    try:
                        _put_back(target, backup, existed, wait=not insisted)
                    except OSError:
                        pass  # not put back: that target stays new, the others are tried
                    except BaseException as exc:  # a Ctrl-C while waiting
                        if interrupt is None:
                            interrupt = exc
                            continue  # the same restore again, waiting again
                        insisted = True  # no more waiting, here or for the others
                        with contextlib.suppress(OSError):
                            _put_back(target, backup, existed, wait=False)
                    break
            if interrupt is not None:
                raise interrupt from failure
            raise
    finally:
        try:
            _remove_all(backup for backup, _ in backups)
        except BaseException:
            _remove_all(backup for backup, _ in backups)  # an interrupt may have cut them short
            raise


def _remove_all(paths: Iterable[Path | None]) -> None:
    """Remove each of ``paths`` that exists (None: nothing).

    A Ctrl-C landing in a removal leaves that file and the ones after it: the
    callers then call this again (for the interrupt may also land as this
    function is entered), and raise the interrupt after. A path that a loop of
    symbolic links made since (its folder moved away, a loop in its place)
    names no file any more, as one whose folder was removed: skipped, so that
    the error that ended the write is the one raised.
    """
    for path in paths:
        if path is not None:
            try:
                path.unlink(missing_ok=True)
            except OSError:
                if not link_loop(path.parent):
                    raise


def _put_back(target: Path, backup: Path | None, existed: bool, *, wait: bool) -> None:
    """Restore ``target`` from ``backup`` (see :func:`_backup`); remove it if it is new.

    ``wait``: on Windows, try a refused rename again for a while (:func:`_replace`).
    An old target that could not be linked stays new: removing it would lose both
    versions.
    """
    if backup is not None:
        if wait:
            _replace(backup, target)
        else:
            os.replace(backup, target)
    elif not existed:
        target.unlink(missing_ok=True)


def _windows() -> bool:
    """Whether this is Windows (looked up at each call, for tests that pretend it is)."""
    return sys.platform == "win32"


def _replace(source: Path, target: Path) -> None:
    """``os.replace``; on Windows tried again for a while when another program holds a file."""
    if not _windows():
        os.replace(source, target)
        return
    deadline = time.monotonic() + _WINDOWS_RETRY_SECONDS
    delay = 0.001
    while True:
        try:
            os.replace(source, target)
            return
        except PermissionError:
            # A read-only target stays refused until someone clears its flag: no wait.
            if time.monotonic() >= deadline or _read_only(target):
                raise
        time.sleep(delay)
        delay = min(2 * delay, 0.1)


def _read_only(path: Path) -> bool:
    """Whether ``path`` is marked read-only (Windows' ``FILE_ATTRIBUTE_READONLY``).

    Where ``os.stat`` gives no file attributes (not Windows: the tests that
    pretend it is), no write permission in its mode stands for the flag, as
    Python's ``os.stat`` on Windows reports it. A path that cannot be read
    (gone, say) is not read-only.
    """
    try:
        info = os.lstat(path)  # a symbolic link is replaced itself, not what it points to
    except OSError:
        return False
    attributes = getattr(info, "st_file_attributes", None)
    if attributes is not None:
        return bool(attributes & stat.FILE_ATTRIBUTE_READONLY)
    return not info.st_mode & stat.S_IWRITE


def _backup(target: Path, backups: list[tuple[Path | None, bool]]) -> None:
    """Append a new hard link to ``target`` beside it (None if none made), and whether it exists.

    Where the file system has no hard links the target cannot be put back: the
    renames then go ahead without (as before a rollback existed), and a failed
    one leaves such targets before it new. The link is listed before it is
    made, so that an interrupt just after cannot leave it behind unlisted.
    """
    for _ in range(_ATTEMPTS):
        link = target.with_name(_compact_name(target, secrets.token_hex(4)))
        backups.append((link, True))
        try:
            # A symbolic link is linked itself, not what it points to (POSIX link()
            # on Linux), so that putting it back restores the link.
            os.link(target, link, follow_symlinks=False)
        except FileExistsError:
            backups.pop()  # another file's name: not ours to remove
            continue
        except FileNotFoundError:
            backups[-1] = (None, False)
        except OSError:
            backups[-1] = (None, True)
        return
    backups.append((None, True))  # every name taken: no link, as where links fail


def _new_temporary(target: Path, temporaries: list[Path]) -> None:
    """Create a new empty hidden file beside ``target`` (mode 0o666 less the umask).

    Its path is appended to ``temporaries`` before the file is made, so that
    an interrupt just after cannot leave it behind unlisted.
    """
    name_max = _name_max(target.parent)
    compact = False
    for _ in range(_ATTEMPTS):
        tag = secrets.token_hex(4)
        name = _compact_name(target, tag) if compact else _temporary_name(target, tag, name_max)
        temporary = target.with_name(name)
        temporaries.append(temporary)
        try:
            fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        except FileExistsError:
            temporaries.pop()  # another file's name: not ours to remove
            continue
        except OSError as exc:
            temporaries.pop()
            if exc.errno in (errno.ENOENT, errno.ENOTDIR, errno.ELOOP):
                # The folder gone (or looped) since _check_targets: named as the folder
                # the caller gave, not as the temporary file (".map.1f2e3d4c.tmp.pgm"),
                # a name the caller never heard of.
                try:
                    check_folder(target)
                except OSError as missing:
                    raise missing from None
            # A file system whose limit is in characters or UTF-16 units while
            # pathconf answers in bytes (vfat, exFAT: 255 characters, "1530"
            # bytes) refuses a name the byte count let through. Windows refuses
            # a path of 260 characters or more (unless long paths are enabled)
            # as "not found": a target just short of it has a temporary beyond.
            too_long = exc.errno == errno.ENAMETOOLONG or (
                _windows() and getattr(exc, "winerror", None) in _WINDOWS_PATH_ERRORS
            )
            if not too_long or compact:
                raise
            compact = True
            continue
        os.close(fd)
        return
    raise FileExistsError(f"cannot create a temporary file beside {target}")


def _file_in_path(folder: Path, links: int = 0) -> Path | None:
    """The file that stands where a folder of ``folder``'s path (itself included) should be.

    The path is followed as the system follows it, from the top: the first
    part that is a file (directly, or as a link ending in one) is named as
    the path spells it. A part that cannot be reached for a file further on
    in a symbolic link's target (``b/x`` with ``b -> a/b``, ``a`` a file:
    ``ENOTDIR``) is looked for along that target, so that the file named is
    the one in the way (``a``), not a folder said not to exist. None if
    nothing but a missing part (or a loop) stands in the way.
    """
    for part in (*reversed(folder.parents), folder):
        try:
            mode = os.stat(part).st_mode
        except OSError as exc:
            # ENOTDIR with every part above a folder: the last part is a link whose
            # target runs through a file. Linux follows at most 40 links in a path.
            if exc.errno != errno.ENOTDIR or links >= _MAX_LINKS:
                return None
            try:
                target = part.parent / os.readlink(part)
            except OSError:  # no link (or no longer one): nothing more to tell
                return None
            blocker = _file_in_path(target, links + 1)
            return None if blocker is None else _tidy(blocker)
        if not stat.S_ISDIR(mode):
            return part
    return None


def _tidy(path: Path) -> Path:
    """``path`` without ``.`` and ``..`` parts (from a link's target) if that is the same file."""
    tidy = Path(os.path.normpath(path))
    with contextlib.suppress(OSError):
        if tidy != path and os.path.samefile(tidy, path):
            return tidy
    return path


def _sync(path: Path, flags: int) -> None:
    """Flush ``path`` to the disk: ``fsync``, or on macOS ``F_FULLFSYNC`` where it works."""
    fd = os.open(path, flags)
    try:
        if sys.platform != "win32":  # no fcntl there (nor in its type stubs)
            full_sync = getattr(fcntl, "F_FULLFSYNC", None) if sys.platform == "darwin" else None
            if full_sync is not None:
                try:
                    fcntl.fcntl(fd, full_sync)  # the drive's cache too (fsync stops short of it)
                    return
                except OSError:  # a file system without it (network shares): fsync then
                    pass
        os.fsync(fd)
    finally:
        os.close(fd)
