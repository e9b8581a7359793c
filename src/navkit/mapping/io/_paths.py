"""File-path arguments of the readers and writers, and files opened safely (private).

Examples
--------
>>> as_path("map.yaml", "path").name
'map.yaml'
>>> as_path(3, "path")
Traceback (most recent call last):
...
TypeError: path must be a str or an os.PathLike, got int
"""

from __future__ import annotations

import os
import stat
import sys
from pathlib import Path
from typing import Any, BinaryIO

from navkit._shared.files import link_loop
from navkit._shared.relative_paths import relative_to_cwd

__all__ = ["as_path", "missing_file", "open_regular"]


def as_path(value: Any, name: str) -> Path:
    """``value`` (a ``str`` or ``os.PathLike`` of ``str``) as a Path: not empty, no NUL."""
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(f"{name} must be a str or an os.PathLike, got {type(value).__name__}")
    text = os.fspath(value)
    if not isinstance(text, str):
        raise TypeError(f"{name} must be a str path, got {type(text).__name__}")
    if not text:  # Path("") would be the working directory
        raise ValueError(f"{name} must not be empty")
    if "\x00" in text:
        raise ValueError(f"{name} must not contain a NUL character, got {text!r}")
    return Path(text)


def missing_file(path: Path, what: str) -> FileNotFoundError:
    """The error for a file ``path`` that cannot be reached: "{what} {path} does not exist".

    With the working directory a relative ``path`` was looked up in, or the
    loop of symbolic links on its way (``path`` itself or a folder above it),
    which ``Path.exists`` reports as missing and ``open`` as the bare
    ``OSError`` "Too many levels of symbolic links" (``ELOOP``).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     loop = Path(folder) / "a.log"
    ...     loop.symlink_to(loop)
    ...     str(missing_file(loop / "x.log", "log")).endswith("a.log is a loop of symbolic links)")
    True
    """
    loop = next((p for p in (*reversed(path.parents), path) if link_loop(p)), None)
    where = relative_to_cwd(path) if loop is None else f" ({loop} is a loop of symbolic links)"
    return FileNotFoundError(f"{what} {path} does not exist{where}")


def open_regular(path: Path, what: str) -> BinaryIO:
    """``path`` opened for reading in binary, refused unless it is a regular file.

    The check is made on the open descriptor, and every read goes through it: a
    check of the name and then an open by name would read whatever was put there
    in between (a FIFO blocks the read for ever). A FIFO does not block this open
    (``O_NONBLOCK``); the descriptor blocks again once it is known to be a file.

    Raises
    ------
    FileNotFoundError
        ``path`` does not exist, or is a loop of symbolic links (as
        :func:`missing_file` says).
    ValueError
        ``path`` is a directory, a FIFO, a device or a socket.
    """
    nonblock = getattr(os, "O_NONBLOCK", 0)
    # O_NOCTTY: a terminal device opened here must not become the controlling one.
    flags = os.O_RDONLY | nonblock | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_BINARY", 0)
    try:
        fd = os.open(path, flags)
    except FileNotFoundError:
        raise missing_file(path, what) from None
    except IsADirectoryError:  # where a directory cannot be opened for reading
        raise ValueError(f"{what} {path} is a directory") from None
    except PermissionError:
        # Windows refuses to open a directory as a file with EACCES, not EISDIR.
        if os.path.isdir(path):
            raise ValueError(f"{what} {path} is a directory") from None
        raise
    except OSError:
        if link_loop(path):  # ELOOP: "Too many levels of symbolic links", naming no loop
            raise missing_file(path, what) from None
        raise
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            kind = "a directory" if stat.S_ISDIR(mode) else "not a regular file"
            raise ValueError(f"{what} {path} is {kind}")
        if sys.platform != "win32" and nonblock:  # Windows has no O_NONBLOCK
            os.set_blocking(fd, True)
    except BaseException:
        os.close(fd)
        raise
    # The file object owns the descriptor from here (it closes it if dropped), with no
    # Python code in between: an interrupt inside os.fdopen (Python) closed it twice, and
    # the second close's EBADF OSError replaced the KeyboardInterrupt.
    return open(fd, "rb")
