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
from collections.abc import Iterator, Sequence
from pathlib import Path

from navkit._shared.locks import ForkSafeLock

__all__ = ["RENAME_LOCK", "atomic_path", "atomic_paths"]

#: Random temporary names tried before giving up.
_ATTEMPTS = 100

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
    every temporary file is flushed to disk (``fsync``) and given the mode of
    the existing target (a new one keeps ``0o666`` less the umask, what a plain
    write gives), *then* they are renamed over the targets in order
    (``os.replace``) and the folders are synced where the system allows. If
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
    IsADirectoryError
        A target that is a folder, found before the block runs or before the
        renames (a folder made meanwhile): no target is replaced, not even the
        ones before it in ``targets``.

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
            temporaries.append(_new_temporary(target))
        yield tuple(temporaries)
        # Again, now: the rename over a folder fails, after those of the targets before it.
        _check_targets(targets)
        for temporary, target in zip(temporaries, targets, strict=True):
            _sync(temporary, os.O_RDWR)
            with contextlib.suppress(FileNotFoundError):
                os.chmod(temporary, stat.S_IMODE(os.stat(target).st_mode))
        with RENAME_LOCK:
            _replace_all(temporaries, targets)
    finally:
        for temporary in temporaries:
            temporary.unlink(missing_ok=True)
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


def _check_targets(targets: Sequence[Path]) -> None:
    """Refuse targets that are not regular files, before any is replaced."""
    for target in targets:
        if target.is_dir():
            raise IsADirectoryError(errno.EISDIR, "a folder cannot be written as a file", target)
        if target.exists() and not target.is_file():
            raise ValueError(
                f"{target} is not a regular file (a device, a pipe or a socket): it is written "
                "by renaming a new file over it, which would replace it"
            )


def _name_max(folder: Path) -> int:
    """Longest file name (bytes) the file system of ``folder`` takes; 255 if it cannot say."""
    try:
        limit = int(os.pathconf(folder, "PC_NAME_MAX"))
    except (AttributeError, OSError, ValueError):  # no pathconf (Windows), no such folder
        return 255
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
        os.replace(temporaries[0], targets[0])
        return
    # Hard links to the targets as they are, to put them back if a later rename fails.
    backups: list[tuple[Path | None, bool]] = []
    try:
        for target in targets:
            backups.append(_backup(target))
        done = 0
        try:
            for temporary, target in zip(temporaries, targets, strict=True):
                os.replace(temporary, target)
                done += 1
        except BaseException:
            for target, (backup, existed) in zip(targets[:done], backups[:done], strict=True):
                with contextlib.suppress(OSError):
                    if backup is not None:
                        os.replace(backup, target)
                    elif not existed:
                        target.unlink(missing_ok=True)
                    # An old target that could not be linked stays new: removing it
                    # would lose both versions.
            raise
    finally:
        for backup, _ in backups:
            if backup is not None:
                backup.unlink(missing_ok=True)


def _backup(target: Path) -> tuple[Path | None, bool]:
    """A new hard link to ``target`` beside it (None if none made), and whether ``target`` exists.

    Where the file system has no hard links the target cannot be put back: the
    renames then go ahead without (as before a rollback existed), and a failed
    one leaves such targets before it new.
    """
    for _ in range(_ATTEMPTS):
        link = target.with_name(_compact_name(target, secrets.token_hex(4)))
        try:
            # A symbolic link is linked itself, not what it points to (POSIX link()
            # on Linux), so that putting it back restores the link.
            os.link(target, link, follow_symlinks=False)
        except FileExistsError:
            continue
        except FileNotFoundError:
            return None, False
        except OSError:
            return None, True
        return link, True
    return None, True  # pragma: no cover


def _new_temporary(target: Path) -> Path:
    """Create a new empty hidden file beside ``target`` (mode 0o666 less the umask)."""
    name_max = _name_max(target.parent)
    compact = False
    for _ in range(_ATTEMPTS):
        tag = secrets.token_hex(4)
        name = _compact_name(target, tag) if compact else _temporary_name(target, tag, name_max)
        temporary = target.with_name(name)
        try:
            fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        except FileExistsError:
            continue
        except OSError as exc:
            # A file system whose limit is in characters or UTF-16 units while
            # pathconf answers in bytes (vfat, exFAT: 255 characters, "1530"
            # bytes) refuses a name the byte count let through.
            if exc.errno != errno.ENAMETOOLONG or compact:
                raise
            compact = True
            continue
        os.close(fd)
        return temporary
    raise FileExistsError(f"cannot create a temporary file beside {target}")  # pragma: no cover


def _sync(path: Path, flags: int) -> None:
    fd = os.open(path, flags)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)
