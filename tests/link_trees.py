"""Folders of files and symbolic links for the writers' tests (review 45).

``tree`` is what a test compares before and after a refused write (nothing
written, nothing removed, no link followed or changed); ``loop`` makes the
simplest loop of symbolic links; ``file_in_link`` a file met on the way
through a link's target (review 46); ``folder_refusal`` what ``check_folder``
says of a folder it refuses.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from navkit._shared.files import check_folder


def tree(folder: Path) -> dict[str, str]:
    """Every entry below ``folder`` (links not followed): what it holds, as a string.

    A link's target (``"-> target"``), a file's text (its bytes in hex when they
    are not UTF-8: images), ``"/"`` for a folder.
    """
    entries = {}
    for path in sorted(folder.rglob("*")):  # rglob follows no links to folders
        key = str(path.relative_to(folder))
        if path.is_symlink():
            entries[key] = f"-> {os.readlink(path)}"
        elif path.is_file():
            data = path.read_bytes()
            try:
                entries[key] = data.decode()
            except UnicodeDecodeError:
                entries[key] = data.hex()
        else:
            entries[key] = "/"
    return entries


def loop(folder: Path) -> Path:
    """``a -> b`` and ``b -> a`` in ``folder``; returns ``a``."""
    (folder / "a").symlink_to("b")
    (folder / "b").symlink_to("a")
    return folder / "a"


def file_in_link(folder: Path) -> tuple[Path, Path]:
    """A file ``a`` and a link ``b -> a/b`` in ``folder``; returns ``(b, a)``.

    ``b/...`` names no folder: the system goes through ``b`` to ``a/b`` and
    finds the file ``a`` where a folder should be (``ENOTDIR``, "Not a
    directory", from ``open``).
    """
    (folder / "a").write_text("keep me")
    (folder / "b").symlink_to(Path("a", "b"))
    return folder / "b", folder / "a"


def folder_refusal(
    target: Path, named: bool, expected: type[OSError]
) -> tuple[OSError, str | None]:
    """``check_folder(target)`` refuses with exactly ``expected``: the error and the file named.

    ``named``: the check is given the argument name ``"path"``. The file named
    (``NotADirectoryError`` only, else None) is read from the message when
    named, from the exception's ``filename`` otherwise.
    """
    with pytest.raises(OSError) as caught:
        check_folder(target, "path" if named else None)
    error = caught.value
    assert type(error) is expected, error
    if expected is not NotADirectoryError:
        return error, None
    if named:
        return error, str(error).removeprefix("path: ").removesuffix(" is a file, not a folder")
    return error, error.filename
